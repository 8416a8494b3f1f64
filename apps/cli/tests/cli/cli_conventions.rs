//! Conventions every subcommand follows: `--help` shows an example, usage errors exit with 2,
//! bad input (a missing file) exits with 1 and names the file; the basis cache is reused and
//! says so; a damaged cache file is recomputed with a warning; a report written into a closed
//! pipe ends tvf quietly (SIGPIPE), not with a panic.

use crate::common::{assert_success, tvf};
use std::path::Path;
use std::process::Output;
use tvf_core::generate::torus;
use tvf_core::io::write_obj;

const SUBCOMMANDS: [&str; 17] = [
    "info",
    "operators",
    "basis",
    "spectrum",
    "decompose",
    "coefficients",
    "filter",
    "analyze",
    "compress",
    "decompress",
    "rate-distortion",
    "spline",
    "design",
    "render",
    "export",
    "demo",
    "edit",
];

#[test]
fn every_subcommand_is_listed_and_its_help_shows_an_example() {
    let top = tvf().arg("--help").output().unwrap();
    assert!(top.status.success());
    let top = String::from_utf8_lossy(&top.stdout);
    for sub in SUBCOMMANDS {
        assert!(
            top.contains(&format!("  {sub} ")),
            "{sub} missing from `tvf --help`"
        );
        let output = tvf().args([sub, "--help"]).output().unwrap();
        assert_eq!(output.status.code(), Some(0), "{sub} --help");
        let help = String::from_utf8_lossy(&output.stdout);
        assert!(
            help.contains("Examples:"),
            "`tvf {sub} --help` has no examples"
        );
        let example = format!("  tvf {sub} ");
        assert!(
            help.lines().any(|l| l.starts_with(&example)),
            "`tvf {sub} --help` shows no example line starting with `tvf {sub}`:\n{help}"
        );
    }
}

#[test]
fn usage_errors_exit_with_2() {
    for args in [
        vec!["no-such-subcommand"],
        vec!["render"],
        vec!["export", "mesh.obj"],
        vec!["demo"],
        vec!["spectrum", "mesh.obj", "-k", "ten"],
        vec![
            "compress", "mesh.obj", "f.npy", "--pairs", "5", "--bits", "40", "-o", "x.tvfc",
        ],
        vec![
            "design",
            "mesh.obj",
            "--constraints",
            "c.json",
            "--full",
            "-k",
            "5",
            "-o",
            "x.npy",
        ],
        vec![
            "design",
            "mesh.obj",
            "--constraints",
            "c.json",
            "-o",
            "x.npy",
        ],
        vec!["spline", "mesh.obj", "-o", "x.npy"],
        vec!["operators", "mesh.obj", "-o", "m", "--mass", "heavy"],
        vec![
            "operators",
            "mesh.obj",
            "-o",
            "m",
            "--discretization",
            "fem",
        ],
        vec![
            "spectrum",
            "mesh.obj",
            "-k",
            "4",
            "--discretization",
            "dec-barycentric",
            "--mass",
            "voronoi",
        ],
        vec!["render", "mesh.obj", "-o", "x.png", "--color", "purple"],
        vec![
            "filter", "mesh.obj", "f.npy", "-o", "x.npy", "--basis", "b.tvfb", "-k", "5",
        ],
    ] {
        let output = tvf().args(&args).output().unwrap();
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        assert!(!output.stderr.is_empty(), "{args:?}: no message");
    }
}

fn assert_names_missing_file(output: &Output, file: &str, args: &[&str]) {
    assert_eq!(output.status.code(), Some(1), "{args:?}");
    let stderr = String::from_utf8_lossy(&output.stderr);
    let last = stderr.lines().last().unwrap_or_default();
    assert!(last.starts_with("error: "), "{args:?}: {stderr}");
    assert!(
        last.contains(file),
        "{args:?}: the error does not name {file}: {stderr}"
    );
}

#[test]
fn a_missing_mesh_exits_with_1_and_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no-such-mesh.obj");
    let m = missing.to_str().unwrap();
    let out = dir.path().join("out");
    let o = out.to_str().unwrap();
    let field = dir.path().join("field.txt");
    std::fs::write(&field, "1 0 0\n").unwrap();
    let f = field.to_str().unwrap();
    for args in [
        vec!["info", m],
        vec!["operators", m, "--decomposition", "conforming", "-o", o],
        vec!["basis", m, "-k", "5", "-o", o],
        vec!["spectrum", m, "-k", "5"],
        vec!["decompose", m, f, "-o", o],
        vec!["coefficients", m, f, "-k", "5"],
        vec!["filter", m, f, "-o", o],
        vec!["analyze", m, f, "-o", o],
        vec!["compress", m, f, "--pairs", "5", "-o", o],
        vec!["decompress", m, f, "-o", o],
        vec!["rate-distortion", m, f, "--pairs", "5", "-o", o],
        vec!["spline", m, "--constraints", f, "-o", o],
        vec!["design", m, "--constraints", f, "--full", "-o", o],
        vec!["edit", m],
        vec!["render", m, "-o", o],
        vec!["export", m, f, "-o", o],
        vec!["demo", "--mesh", m, "-o", o],
    ] {
        let output = tvf().args(&args).output().unwrap();
        assert_names_missing_file(&output, "no-such-mesh.obj", &args);
    }
}

fn write_torus(dir: &Path) -> String {
    let path = dir.join("torus.obj");
    write_obj(&path, &torus(1.0, 0.4, 16, 8).unwrap()).unwrap();
    path.to_str().unwrap().to_string()
}

#[test]
fn a_missing_field_or_basis_exits_with_1_and_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = write_torus(dir.path());
    let o = dir.path().join("out");
    let o = o.to_str().unwrap();
    for args in [
        vec!["render", &mesh, "no-such-field.npy", "-o", o],
        vec!["export", &mesh, "no-such-field.npy", "-o", "x.vtk"],
        vec!["filter", &mesh, "no-such-field.npy", "-k", "3", "-o", o],
    ] {
        let output = tvf().args(&args).output().unwrap();
        assert_names_missing_file(&output, "no-such-field.npy", &args);
    }
    let field = dir.path().join("field.txt");
    std::fs::write(&field, "1 0 0\n".repeat(256)).unwrap();
    let args = [
        "coefficients",
        &mesh,
        field.to_str().unwrap(),
        "--basis",
        "no-such-basis.tvfb",
    ];
    let output = tvf().args(args).output().unwrap();
    assert_names_missing_file(&output, "no-such-basis.tvfb", &args);
}

#[test]
fn a_computed_basis_is_cached_reused_and_recomputed_when_damaged() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = write_torus(dir.path());
    let cache = dir.path().join("cache");
    let field = dir.path().join("field.txt");
    std::fs::write(&field, "1 0 0\n".repeat(256)).unwrap();
    let coefficients = |extra: &[&str]| {
        let output = tvf()
            .args([
                "coefficients",
                &mesh,
                field.to_str().unwrap(),
                "-k",
                "6",
                "--json",
            ])
            .arg("--cache-dir")
            .arg(&cache)
            .args(extra)
            .output()
            .unwrap();
        assert_success(&output);
        (
            String::from_utf8_lossy(&output.stdout).into_owned(),
            String::from_utf8_lossy(&output.stderr).into_owned(),
        )
    };
    let (first, stderr) = coefficients(&[]);
    assert!(stderr.contains("cached basis in"), "{stderr}");
    let files: Vec<_> = std::fs::read_dir(&cache)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(files.len(), 1, "{files:?}");
    let name = files[0].file_name().unwrap().to_string_lossy().into_owned();
    // {fingerprint}-{complex id}-{matrix hash}-{size}.tvfb
    let parts: Vec<&str> = name.rsplitn(3, '-').collect();
    assert_eq!(parts[0], "d6.tvfb", "{name}");
    assert_eq!(parts[1].len(), 16, "the matrix hash in {name}");
    assert!(parts[2].ends_with("-conforming-barycentric"), "{name}");

    let (second, stderr) = coefficients(&[]);
    assert!(stderr.contains("using cached basis"), "{stderr}");
    assert_eq!(first, second, "the cached basis gives other coefficients");

    // Another discretization is another cache entry.
    let (_, stderr) = coefficients(&["--mass", "voronoi"]);
    assert!(!stderr.contains("using cached basis"), "{stderr}");
    assert_eq!(std::fs::read_dir(&cache).unwrap().count(), 2);

    // A damaged cache file: warning, recomputed, same result.
    let mut bytes = std::fs::read(&files[0]).unwrap();
    let middle = bytes.len() / 2;
    bytes[middle] ^= 0xff;
    std::fs::write(&files[0], bytes).unwrap();
    let (third, stderr) = coefficients(&[]);
    assert!(
        stderr.contains("warning: cached basis is unusable"),
        "{stderr}"
    );
    assert!(stderr.contains("damaged"), "{stderr}");
    assert_eq!(first, third);
    let (_, stderr) = coefficients(&[]);
    assert!(stderr.contains("using cached basis"), "{stderr}");

    // --no-cache neither reads nor writes; --quiet silences the notes.
    let (_, stderr) = coefficients(&["--no-cache", "--quiet"]);
    assert!(stderr.is_empty(), "{stderr}");
}

#[test]
fn a_basis_file_must_match_the_requested_discretization() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = write_torus(dir.path());
    let basis = dir.path().join("b.tvfb");
    let output = tvf()
        .args([
            "basis",
            &mesh,
            "-k",
            "4",
            "--decomposition",
            "nonconforming",
            "-o",
        ])
        .arg(&basis)
        .output()
        .unwrap();
    assert!(output.status.success());
    let field = dir.path().join("field.txt");
    std::fs::write(&field, "0 1 0\n".repeat(256)).unwrap();
    let output = tvf()
        .args(["coefficients", &mesh, field.to_str().unwrap(), "--basis"])
        .arg(&basis)
        .args(["--decomposition", "conforming"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("b.tvfb")
            && stderr.contains("'nonconforming-barycentric'")
            && stderr.contains("'conforming-barycentric' was asked for"),
        "{stderr}"
    );
    // The same through --discretization.
    let output = tvf()
        .args(["coefficients", &mesh, field.to_str().unwrap(), "--basis"])
        .arg(&basis)
        .args(["--discretization", "dec-barycentric"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("'dec-barycentric' was asked for"));
    // Without --decomposition the file's own discretization is used.
    let output = tvf()
        .args(["coefficients", &mesh, field.to_str().unwrap(), "--basis"])
        .arg(&basis)
        .output()
        .unwrap();
    assert_success(&output);
    assert!(String::from_utf8_lossy(&output.stderr).contains("using basis"));
}

/// (SIGPIPE is Unix's; elsewhere a closed pipe is an ordinary write error.)
#[cfg(unix)]
#[test]
fn a_report_into_a_closed_pipe_ends_quietly() {
    use std::os::fd::{FromRawFd, OwnedFd};
    use std::os::unix::process::ExitStatusExt;
    // A pipe whose reading end is closed before tvf starts: its first write meets no reader.
    let mut fds = [0; 2];
    // SAFETY: `fds` has room for the two descriptors pipe() writes.
    assert_eq!(unsafe { libc::pipe(fds.as_mut_ptr()) }, 0);
    // SAFETY: both descriptors were just created and are owned by nobody else.
    let (reading, writing) =
        unsafe { (OwnedFd::from_raw_fd(fds[0]), OwnedFd::from_raw_fd(fds[1])) };
    drop(reading);
    let output = tvf()
        .args(["info", "--example", "torus"])
        .stdout(writing)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(
        output.status.signal(),
        Some(libc::SIGPIPE),
        "{:?}",
        output.status
    );
}

/// `--no-cache` and `--cache-dir` on a subcommand that keeps no basis cache (`spectrum`,
/// `basis`, `check` …) are refused with a sentence that says so and names the subcommands that
/// take them, not clap's advice to pass `-- --no-cache` as a positional argument; every
/// subcommand that reuses a basis takes them.
#[test]
fn cache_flags_are_taken_where_a_cache_is_used_and_refused_clearly_elsewhere() {
    for args in [
        &["spectrum", "--example", "torus", "-k", "4", "--no-cache"][..],
        &[
            "basis",
            "--example",
            "torus",
            "-k",
            "4",
            "--cache-dir=x",
            "-o",
            "b.tvfb",
        ],
        &["check", "--no-cache"],
        &["convergence", "--no-cache"],
    ] {
        let output = tvf().args(args).output().unwrap();
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            stderr.contains(&format!("tvf {} keeps no basis cache", args[0])),
            "{args:?}: {stderr}"
        );
        assert!(stderr.contains("coefficients, "), "{stderr}");
        assert!(!stderr.contains("-- --no-cache"), "{stderr}");
    }
    for sub in [
        "coefficients",
        "filter",
        "analyze",
        "compress",
        "decompress",
        "rate-distortion",
        "spline",
        "design",
        "edit",
    ] {
        let help = tvf().args([sub, "--help"]).output().unwrap();
        let help = String::from_utf8_lossy(&help.stdout);
        assert!(
            help.contains("--no-cache") && help.contains("--cache-dir"),
            "{sub}"
        );
    }
}
