//! End-to-end: how every subcommand writes its output. A missing parent folder is refused by
//! every subcommand with a message naming the output; an output equal to an input is refused;
//! folder outputs appear whole or not at all (tested with an injected write failure); an
//! interrupted write (SIGINT, SIGTERM) leaves no temporary, stale temporaries are swept, and a
//! command's outputs appear together or not at all; a complete basis larger than the machine's
//! memory is refused with its size.

use crate::common::{assert_success, tvf};
use std::path::{Path, PathBuf};
use std::process::{Output, Stdio};
use std::time::{Duration, Instant, SystemTime};
use tvf_core::generate::genus_surface;
use tvf_core::io::write_obj;

/// The variable with which the `tvf` binary injects write faults (`fail:NAME`, `stall:NAME`).
const WRITE_FAULT_VARIABLE: &str = "TVF_TEST_WRITE_FAULT";

/// Faces of `--example torus`.
const TORUS_FACES: usize = 2304;

fn run(dir: &Path, args: &[&str]) -> Output {
    tvf()
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the tvf binary runs")
}

fn run_with_fault(dir: &Path, fault: &str, args: &[&str]) -> Output {
    tvf()
        .current_dir(dir)
        .env(WRITE_FAULT_VARIABLE, fault)
        .args(args)
        .output()
        .expect("the tvf binary runs")
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Names in `dir` of our temporaries (`.tvf-write-*`, `.tvf-folder-*`).
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".tvf-"))
        .collect()
}

/// A working folder with a mesh file, a torus field and a constraint file.
fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    write_obj(dir.path().join("m.obj"), &genus_surface(1, 4)).unwrap();
    std::fs::write(dir.path().join("f.txt"), "1 0 0\n".repeat(TORUS_FACES)).unwrap();
    std::fs::write(
        dir.path().join("c.json"),
        r#"{"constraints": [{"id": "a", "kind": "vector", "face": 3, "value": [1, 0, 0]}]}"#,
    )
    .unwrap();
    dir
}

#[test]
fn every_subcommand_refuses_a_missing_parent_folder_naming_the_output() {
    let dir = workspace();
    let d = dir.path();
    let cases: Vec<Vec<&str>> = vec![
        vec!["basis", "m.obj", "-k", "10", "-o", "missing/x.tvfb"],
        vec!["render", "m.obj", "-o", "missing/x.png"],
        vec!["export", "m.obj", "f.txt", "-o", "missing/x.vtk"],
        vec!["decompose", "m.obj", "f.txt", "-o", "missing/parts"],
        vec!["operators", "m.obj", "-o", "missing/ops"],
        vec![
            "filter",
            "m.obj",
            "f.txt",
            "--rest",
            "0",
            "-o",
            "missing/x.npy",
        ],
        vec!["analyze", "m.obj", "f.txt", "-o", "missing/analysis"],
        vec![
            "compress",
            "m.obj",
            "f.txt",
            "--pairs",
            "4",
            "-o",
            "missing/x.tvfc",
        ],
        vec!["decompress", "m.obj", "x.tvfc", "-o", "missing/x.npy"],
        vec![
            "rate-distortion",
            "m.obj",
            "f.txt",
            "--pairs",
            "2",
            "-o",
            "missing/rd",
        ],
        vec![
            "spline",
            "m.obj",
            "--constraints",
            "c.json",
            "-o",
            "missing/x.npy",
        ],
        vec![
            "design",
            "m.obj",
            "--constraints",
            "c.json",
            "--full",
            "-o",
            "missing/x.npy",
        ],
        vec!["demo", "--quick", "-o", "missing/demo"],
    ];
    for args in cases {
        let output = run(d, &args);
        let message = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {message}");
        let target = args.last().unwrap();
        assert!(
            message.contains(target) && message.contains("does not exist"),
            "{args:?}: {message}"
        );
        assert!(
            !message.contains(".tvf-"),
            "{args:?} names a temporary: {message}"
        );
        assert!(!d.join("missing").exists(), "{args:?} created the folder");
    }
}

#[test]
fn an_output_equal_to_an_input_is_refused_and_the_input_kept() {
    let dir = workspace();
    let d = dir.path();
    let mesh = std::fs::read(d.join("m.obj")).unwrap();
    let field = std::fs::read(d.join("f.txt")).unwrap();
    let constraints = std::fs::read(d.join("c.json")).unwrap();
    let curve = br#"{"points": [[0, 1], [10, 0]]}"#;
    std::fs::write(d.join("curve.json"), curve).unwrap();
    for args in [
        vec!["render", "m.obj", "f.txt", "-o", "m.obj"],
        vec!["render", "m.obj", "f.txt", "-o", "./f.txt"],
        vec!["export", "m.obj", "f.txt", "-o", "m.obj"],
        vec!["filter", "m.obj", "f.txt", "--rest", "0", "-o", "f.txt"],
        vec![
            "filter",
            "m.obj",
            "f.txt",
            "--integrable",
            "@curve.json",
            "-o",
            "curve.json",
        ],
        vec![
            "filter",
            "m.obj",
            "f.txt",
            "--cointegrable",
            "@./curve.json",
            "-o",
            "curve.json",
        ],
        vec!["spline", "m.obj", "--constraints", "c.json", "-o", "c.json"],
        vec![
            "design",
            "m.obj",
            "--constraints",
            "c.json",
            "--full",
            "-o",
            "m.obj",
        ],
    ] {
        let output = run(d, &args);
        let message = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {message}");
        assert!(message.contains("also an input"), "{args:?}: {message}");
    }
    assert_eq!(std::fs::read(d.join("m.obj")).unwrap(), mesh);
    assert_eq!(std::fs::read(d.join("f.txt")).unwrap(), field);
    assert_eq!(std::fs::read(d.join("c.json")).unwrap(), constraints);
    assert_eq!(std::fs::read(d.join("curve.json")).unwrap(), curve);
}

#[test]
fn folder_outputs_appear_whole_or_not_at_all() {
    let dir = workspace();
    let d = dir.path();
    let cache = d.join("cache").display().to_string();
    let torus = |rest: &[&str]| -> Vec<String> {
        let mut args = vec!["--example", "torus", "f.txt"];
        args.extend_from_slice(rest);
        args.iter().map(|s| s.to_string()).collect()
    };
    // (subcommand arguments, output folder, the file whose write fails, the files it writes)
    let cases: Vec<(Vec<String>, &str, &str, Vec<&str>)> = vec![
        (
            [vec!["decompose".to_string()], torus(&["-o", "parts"])].concat(),
            "parts",
            "harmonic.npy",
            vec![
                "integrable.npy",
                "cointegrable.npy",
                "harmonic.npy",
                "potential.npy",
            ],
        ),
        (
            [
                vec!["analyze".to_string()],
                torus(&["-k", "20", "--cache-dir", &cache, "-o", "an"]),
            ]
            .concat(),
            "an",
            "spectrum.png",
            vec!["coefficients.csv", "energy.json", "spectrum.png"],
        ),
        (
            [
                vec!["rate-distortion".to_string()],
                torus(&[
                    "-k",
                    "20",
                    "--cache-dir",
                    &cache,
                    "--pairs",
                    "2,4",
                    "-o",
                    "rd",
                ]),
            ]
            .concat(),
            "rd",
            "rate_distortion.png",
            vec!["rate_distortion.csv", "rate_distortion.png"],
        ),
        (
            ["operators", "--example", "torus", "-o", "ops"]
                .iter()
                .map(|s| s.to_string())
                .collect(),
            "ops",
            "info.json",
            vec!["d0.mtx", "S.mtx", "info.json"],
        ),
        (
            ["demo", "--quick", "-o", "demo"]
                .iter()
                .map(|s| s.to_string())
                .collect(),
            "demo",
            "index.html",
            vec!["index.html", "mesh.png"],
        ),
    ];
    for (args, folder, failing, files) in cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let output = run_with_fault(d, &format!("fail:{failing}"), &args);
        let message = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {message}");
        assert!(message.contains("injected"), "{args:?}: {message}");
        assert!(!d.join(folder).exists(), "{args:?} left a partial folder");
        assert!(temporaries(d).is_empty(), "{args:?}: {:?}", temporaries(d));
        // Without the fault the folder appears with every file.
        let output = run(d, &args);
        assert_success(&output);
        for file in files {
            assert!(d.join(folder).join(file).is_file(), "{args:?}: {file}");
        }
        assert!(temporaries(d).is_empty(), "{args:?}: {:?}", temporaries(d));
    }
    // Into an existing folder: a failure changes nothing in it.
    let existing = d.join("existing");
    std::fs::create_dir(&existing).unwrap();
    std::fs::write(existing.join("notes.txt"), "mine").unwrap();
    let args = ["decompose", "--example", "torus", "f.txt", "-o", "existing"];
    let output = run_with_fault(d, "fail:potential.npy", &args);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    let names: Vec<_> = std::fs::read_dir(&existing).unwrap().collect();
    assert_eq!(names.len(), 1, "{names:?}");
    assert_success(&run(d, &args));
    assert!(existing.join("notes.txt").is_file() && existing.join("harmonic.npy").is_file());
    // A sequence written as a folder of frames: all frames or none.
    let frames = d.join("frames.npy");
    let frame: Vec<[f64; 3]> = vec![[1.0, 0.0, 0.0]; TORUS_FACES];
    tvf_spectral::write_face_vector_sequence(
        &frames,
        &[frame.clone(), frame.clone(), frame],
        tvf_spectral::NpyDtype::F64,
    )
    .unwrap();
    let compress = [
        "compress",
        "--example",
        "torus",
        "frames.npy",
        "--pairs",
        "4",
        "-k",
        "20",
        "--cache-dir",
        &cache,
        "-o",
        "s.tvfc",
    ];
    assert_success(&run(d, &compress));
    let decompress = [
        "decompress",
        "--example",
        "torus",
        "s.tvfc",
        "--cache-dir",
        &cache,
        "-o",
        "out",
    ];
    let output = run_with_fault(d, "fail:frame_00001.npy", &decompress);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    assert!(!d.join("out").exists());
    assert!(temporaries(d).is_empty(), "{:?}", temporaries(d));
}

/// Starts `args` with a stalled write of `file`, waits until its temporary `prefix` appears in
/// `folder`, sends `signal` and returns the exit code. (Signals are Unix's; elsewhere the
/// interruption is the console's Ctrl+C, which a test cannot send to a child.)
#[cfg(unix)]
fn interrupt_while_writing(
    dir: &Path,
    args: &[&str],
    file: &str,
    prefix: &str,
    signal: i32,
) -> Option<i32> {
    let mut child = tvf()
        .current_dir(dir)
        .env(WRITE_FAULT_VARIABLE, format!("stall:{file}"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("tvf starts");
    let deadline = Instant::now() + Duration::from_secs(120);
    let folder: PathBuf = dir.join("d");
    while !temporaries(&folder).iter().any(|n| n.starts_with(prefix)) {
        assert!(Instant::now() < deadline, "no temporary appeared");
        assert!(
            child.try_wait().unwrap().is_none(),
            "tvf ended before writing"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    let pid = libc::pid_t::try_from(child.id()).unwrap();
    // SAFETY: sending a signal to our own child process.
    assert_eq!(unsafe { libc::kill(pid, signal) }, 0);
    child.wait().unwrap().code()
}

#[cfg(unix)]
#[test]
fn interrupted_writes_leave_no_temporaries_and_stale_ones_are_swept() {
    let dir = workspace();
    let d = dir.path();
    std::fs::create_dir(d.join("d")).unwrap();
    // A basis is computed into its file inside a staging folder.
    let basis = ["basis", "--example", "torus", "-k", "10", "-o", "d/x.tvfb"];
    for (signal, code) in [(libc::SIGINT, 130), (libc::SIGTERM, 143)] {
        let exit = interrupt_while_writing(d, &basis, "x.tvfb", ".tvf-folder-", signal);
        assert_eq!(exit, Some(code));
        assert!(
            temporaries(&d.join("d")).is_empty(),
            "{:?}",
            temporaries(&d.join("d"))
        );
        assert!(!d.join("d/x.tvfb").exists());
    }
    let decompose = ["decompose", "--example", "torus", "f.txt", "-o", "d/parts"];
    let exit =
        interrupt_while_writing(d, &decompose, "harmonic.npy", ".tvf-folder-", libc::SIGTERM);
    assert_eq!(exit, Some(143));
    assert!(
        temporaries(&d.join("d")).is_empty(),
        "{:?}",
        temporaries(&d.join("d"))
    );
    assert!(!d.join("d/parts").exists());

    // Stale temporaries of our pattern (an hour old) are swept; fresh ones (maybe another
    // process's) and other files stay.
    let stale = d.join("d/.tvf-write-stale.tmp");
    let stale_folder = d.join("d/.tvf-folder-stale.tmp");
    let fresh = d.join("d/.tvf-write-fresh.tmp");
    let other = d.join("d/keep.tmp");
    std::fs::create_dir(&stale_folder).unwrap();
    for p in [&stale, &fresh, &other] {
        std::fs::write(p, b"x").unwrap();
    }
    let old = SystemTime::now() - Duration::from_secs(2 * 3600);
    for p in [&stale, &other] {
        std::fs::File::options()
            .write(true)
            .open(p)
            .unwrap()
            .set_modified(old)
            .unwrap();
    }
    std::fs::File::open(&stale_folder)
        .unwrap()
        .set_modified(old)
        .unwrap();
    assert_success(&run(d, &basis));
    assert!(!stale.exists() && !stale_folder.exists());
    assert!(fresh.exists() && other.exists() && d.join("d/x.tvfb").exists());
}

/// `tvf basis -o X --export DIR` interrupted after `X` is complete, while `DIR` is written:
/// neither appears (a command's outputs appear together or not at all); without the
/// interruption both do.
#[cfg(unix)]
#[test]
fn an_interrupted_basis_leaves_neither_its_file_nor_its_export() {
    let dir = workspace();
    let d = dir.path();
    std::fs::create_dir(d.join("d")).unwrap();
    let args = [
        "basis",
        "--example",
        "torus",
        "-k",
        "10",
        "-o",
        "d/x.tvfb",
        "--export",
        "d/arrays",
    ];
    let mut child = tvf()
        .current_dir(d)
        .env(WRITE_FAULT_VARIABLE, "stall:frames.npy")
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("tvf starts");
    // fields.npy is written before frames.npy, whose write stalls: the export is then being
    // written and the basis file is complete.
    let deadline = Instant::now() + Duration::from_secs(120);
    let export_written = || {
        std::fs::read_dir(d.join("d")).unwrap().any(|entry| {
            let path = entry.unwrap().path();
            path.join("fields.npy").is_file()
        })
    };
    while !export_written() {
        assert!(Instant::now() < deadline, "the export was not written");
        assert!(child.try_wait().unwrap().is_none(), "tvf ended early");
        std::thread::sleep(Duration::from_millis(20));
    }
    let pid = libc::pid_t::try_from(child.id()).unwrap();
    // SAFETY: sending a signal to our own child process.
    assert_eq!(unsafe { libc::kill(pid, libc::SIGINT) }, 0);
    assert_eq!(child.wait().unwrap().code(), Some(130));
    assert!(
        !d.join("d/x.tvfb").exists(),
        "the basis file appeared alone"
    );
    assert!(!d.join("d/arrays").exists());
    assert!(
        temporaries(&d.join("d")).is_empty(),
        "{:?}",
        temporaries(&d.join("d"))
    );
    assert_success(&run(d, &args));
    assert!(d.join("d/x.tvfb").is_file() && d.join("d/arrays/frames.npy").is_file());
    assert!(
        temporaries(&d.join("d")).is_empty(),
        "{:?}",
        temporaries(&d.join("d"))
    );
}

#[test]
fn a_complete_basis_larger_than_memory_is_refused_with_its_size() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("big.obj");
    write_obj(&mesh, &genus_surface(1, 64)).unwrap();
    let mesh = mesh.display().to_string();
    for command in ["basis", "spectrum"] {
        let mut args = vec![command, &mesh, "-k", "1000000000000"];
        if command == "basis" {
            args.extend_from_slice(&["-o", "x.tvfb"]);
        }
        let started = Instant::now();
        let output = run(dir.path(), &args);
        let message = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{command}: {message}");
        assert!(
            message.contains("complete basis") && message.contains("GiB"),
            "{command}: {message}"
        );
        assert!(started.elapsed() < Duration::from_secs(60));
    }
}
