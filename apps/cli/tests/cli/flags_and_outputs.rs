//! Flags that mean the same everywhere and outputs that look the same everywhere:
//! `-k K` is the number of eigenfields (the paper's d) in every subcommand; every written file
//! has ordinary permissions (`0o666` minus the umask, not a temporary file's `0o600`);
//! sequence compression shows progress lines off a terminal and nothing with `--quiet`.

use std::ffi::OsStr;
use std::path::Path;
use std::process::{Command, Output};
use tvf_core::generate::torus;
use tvf_core::io::write_obj;
use tvf_core::TriangleMesh;
use tvf_spectral::{write_face_vector_sequence, NpyDtype};

fn tvf<S: AsRef<OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args(args)
        .output()
        .unwrap()
}

fn succeeded(output: &Output, what: &str) -> (String, String) {
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(output.status.success(), "{what}: {stderr}");
    (String::from_utf8_lossy(&output.stdout).into_owned(), stderr)
}

fn write_mesh(dir: &Path) -> (TriangleMesh, String) {
    let mesh = torus(1.0, 0.4, 16, 8).unwrap();
    let path = dir.join("torus.obj");
    write_obj(&path, &mesh).unwrap();
    (mesh, path.to_str().unwrap().to_string())
}

fn swirl_text(mesh: &TriangleMesh, phase: f64) -> String {
    let p = mesh.positions();
    mesh.faces()
        .iter()
        .map(|f| {
            let c: [f64; 3] = std::array::from_fn(|i| (p[f[0]][i] + p[f[1]][i] + p[f[2]][i]) / 3.0);
            format!("{} {} {}\n", -c[1], c[0], (3.0 * c[0] + phase).sin())
        })
        .collect()
}

fn json(stdout: &str) -> serde_json::Value {
    serde_json::from_str(stdout).unwrap()
}

/// `-k 12` means 12 eigenfields in `basis`, `spectrum`, the cached bases of `coefficients`
/// and `filter`, and in `spline`: all see the same 12 lowest eigenvalues.
#[test]
fn k_is_the_number_of_eigenfields_in_every_subcommand() {
    let dir = tempfile::tempdir().unwrap();
    let (mesh, m) = write_mesh(dir.path());
    let field = dir.path().join("field.txt");
    std::fs::write(&field, swirl_text(&mesh, 0.0)).unwrap();
    let f = field.to_str().unwrap();
    let cache = dir.path().join("cache");
    let cache = cache.to_str().unwrap();

    let (spectrum, _) = succeeded(&tvf(&["spectrum", &m, "-k", "12", "--json"]), "spectrum");
    let spectrum: Vec<f64> = json(&spectrum)["eigenvalues"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(spectrum.len(), 12);

    let basis = dir.path().join("b.tvfb");
    let b = basis.to_str().unwrap();
    let (_, stderr) = succeeded(&tvf(&["basis", &m, "-k", "12", "-o", b]), "basis");
    assert!(stderr.contains("12 fields"), "{stderr}");

    let eigenvalues_of = |stdout: &str| -> Vec<f64> {
        json(stdout)["coefficients"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["eigenvalue"].as_f64().unwrap())
            .collect()
    };
    let (from_file, _) = succeeded(
        &tvf(&["coefficients", &m, f, "--basis", b, "--json"]),
        "coefficients --basis",
    );
    let (cached, stderr) = succeeded(
        &tvf(&[
            "coefficients",
            &m,
            f,
            "-k",
            "12",
            "--cache-dir",
            cache,
            "--json",
        ]),
        "coefficients -k",
    );
    assert!(stderr.contains("cached basis in"), "{stderr}");
    for eigenvalues in [eigenvalues_of(&from_file), eigenvalues_of(&cached)] {
        assert_eq!(eigenvalues.len(), 12);
        for (a, b) in eigenvalues.iter().zip(&spectrum) {
            assert!((a - b).abs() <= 1e-8 * b.abs().max(1.0), "{a} vs {b}");
        }
    }
    let names: Vec<String> = std::fs::read_dir(cache)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 1, "{names:?}");
    assert!(
        names[0].contains("-conforming-barycentric-") && names[0].ends_with("-d12.tvfb"),
        "{names:?}"
    );

    // filter -k 12 reuses that cache entry.
    let filtered = dir.path().join("filtered.npy");
    let (_, stderr) = succeeded(
        &tvf(&[
            OsStr::new("filter"),
            OsStr::new(&m),
            OsStr::new(f),
            OsStr::new("-k"),
            OsStr::new("12"),
            OsStr::new("--cache-dir"),
            OsStr::new(cache),
            OsStr::new("-o"),
            filtered.as_os_str(),
        ]),
        "filter",
    );
    assert!(stderr.contains("using cached basis"), "{stderr}");

    // spline -k 12 works in a basis of 12 fields (and reuses the same cache entry).
    let constraints = dir.path().join("c.json");
    std::fs::write(
        &constraints,
        r#"{"constraints": [{"id": "a", "kind": "vector", "face": 5, "value": [1, 0, 0]}]}"#,
    )
    .unwrap();
    let spline = dir.path().join("spline.npy");
    let (stdout, stderr) = succeeded(
        &tvf(&[
            OsStr::new("spline"),
            OsStr::new(&m),
            OsStr::new("--constraints"),
            constraints.as_os_str(),
            OsStr::new("-k"),
            OsStr::new("12"),
            OsStr::new("--cache-dir"),
            OsStr::new(cache),
            OsStr::new("-o"),
            spline.as_os_str(),
        ]),
        "spline",
    );
    assert!(stdout.contains("d = 12"), "{stdout}");
    assert!(stderr.contains("using cached basis"), "{stderr}");

    // K ≥ 2F: the complete basis.
    let complete = dir.path().join("complete.tvfb");
    let (_, stderr) = succeeded(
        &tvf(&[
            OsStr::new("basis"),
            OsStr::new(&m),
            OsStr::new("-k"),
            OsStr::new("100000"),
            OsStr::new("-o"),
            complete.as_os_str(),
        ]),
        "basis complete",
    );
    assert!(
        stderr.contains(&format!("{} fields", 2 * mesh.face_count())),
        "{stderr}"
    );
    let (all, _) = succeeded(
        &tvf(&["spectrum", &m, "-k", "100000", "--json"]),
        "spectrum complete",
    );
    assert_eq!(
        json(&all)["eigenvalues"].as_array().unwrap().len(),
        2 * mesh.face_count()
    );
}

/// The mode a new file gets from `File::create` in this process (and its children): `0o666`
/// minus the umask.
#[cfg(unix)]
fn ordinary_mode(dir: &Path) -> u32 {
    use std::os::unix::fs::PermissionsExt;
    let probe = dir.join("probe");
    std::fs::File::create(&probe).unwrap();
    let mode = std::fs::metadata(&probe).unwrap().permissions().mode() & 0o777;
    std::fs::remove_file(probe).unwrap();
    mode
}

/// Every writer (core meshes, spectral fields, bases and .tvfc files, render PNG and exports,
/// CLI matrices, the demo page) gives its files ordinary permissions.
#[cfg(unix)]
#[test]
fn written_files_get_ordinary_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let (mesh, m) = write_mesh(dir.path());
    let expected = ordinary_mode(dir.path());
    let field = dir.path().join("field.txt");
    std::fs::write(&field, swirl_text(&mesh, 0.0)).unwrap();
    let f = field.to_str().unwrap();
    let d = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let runs: Vec<Vec<String>> = vec![
        vec![
            "basis".into(),
            m.clone(),
            "-k".into(),
            "6".into(),
            "-o".into(),
            d("b.tvfb"),
        ],
        vec![
            "filter".into(),
            m.clone(),
            f.into(),
            "--basis".into(),
            d("b.tvfb"),
            "-o".into(),
            d("filtered.npy"),
        ],
        vec![
            "compress".into(),
            m.clone(),
            f.into(),
            "--basis".into(),
            d("b.tvfb"),
            "--pairs".into(),
            "2".into(),
            "-o".into(),
            d("c.tvfc"),
        ],
        vec![
            "render".into(),
            m.clone(),
            f.into(),
            "--size".into(),
            "64x48".into(),
            "-o".into(),
            d("p.png"),
        ],
        vec![
            "export".into(),
            m.clone(),
            f.into(),
            "-o".into(),
            d("e.vtk"),
        ],
        vec![
            "export".into(),
            m.clone(),
            f.into(),
            "--streamlines".into(),
            "50".into(),
            "-o".into(),
            d("e.obj"),
        ],
        vec!["operators".into(), m.clone(), "-o".into(), d("ops")],
        vec![
            "decompose".into(),
            m.clone(),
            f.into(),
            "-o".into(),
            d("parts"),
        ],
        vec![
            "analyze".into(),
            m.clone(),
            f.into(),
            "--basis".into(),
            d("b.tvfb"),
            "-o".into(),
            d("analysis"),
        ],
    ];
    for args in &runs {
        succeeded(&tvf(args), &args[0]);
    }
    let files = [
        d("b.tvfb"),
        d("filtered.npy"),
        d("c.tvfc"),
        d("p.png"),
        d("e.vtk"),
        d("e.obj"),
        d("ops/S.mtx"),
        d("ops/info.json"),
        d("parts/harmonic.npy"),
        d("analysis/coefficients.csv"),
        d("analysis/energy.json"),
        d("analysis/spectrum.png"),
    ];
    for file in files {
        let mode = std::fs::metadata(&file).unwrap().permissions().mode() & 0o777;
        assert_eq!(
            mode, expected,
            "{file}: mode {mode:o}, expected {expected:o}"
        );
    }
    // A mesh written by tvf-core's writer.
    let obj = dir.path().join("core.obj");
    tvf_core::io::save_mesh(&obj, &mesh).unwrap();
    let mode = std::fs::metadata(&obj).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, expected, "core.obj: mode {mode:o}");
}

/// Compressing a sequence reports progress per frame as plain lines when stderr is not a
/// terminal (as in this test), and nothing with --quiet; the file is the same either way.
#[test]
fn sequence_compression_shows_progress_unless_quiet() {
    let dir = tempfile::tempdir().unwrap();
    let (mesh, m) = write_mesh(dir.path());
    let frames: Vec<Vec<[f64; 3]>> = (0..8)
        .map(|k| {
            swirl_text(&mesh, 0.3 * k as f64)
                .lines()
                .map(|l| {
                    let v: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
                    [v[0], v[1], v[2]]
                })
                .collect()
        })
        .collect();
    let array = dir.path().join("frames.npy");
    write_face_vector_sequence(&array, &frames, NpyDtype::F64).unwrap();
    let a = array.to_str().unwrap();
    let basis = dir.path().join("b.tvfb");
    let b = basis.to_str().unwrap();
    succeeded(
        &tvf(&["basis", &m, "-k", "20", "--quiet", "-o", b]),
        "basis",
    );
    let loud = dir.path().join("loud.tvfc");
    let quiet = dir.path().join("quiet.tvfc");
    let (_, stderr) = succeeded(
        &tvf(&[
            "compress",
            &m,
            a,
            "--basis",
            b,
            "--pairs",
            "6",
            "-o",
            loud.to_str().unwrap(),
        ]),
        "compress",
    );
    assert!(stderr.contains("compress: frames 8/8"), "{stderr}");
    assert!(stderr.contains("compress: 8 frames"), "{stderr}");
    assert!(
        !stderr.contains('\r'),
        "terminal control in plain output: {stderr:?}"
    );
    let (_, stderr) = succeeded(
        &tvf(&[
            "compress",
            &m,
            a,
            "--basis",
            b,
            "--pairs",
            "6",
            "--quiet",
            "-o",
            quiet.to_str().unwrap(),
        ]),
        "compress --quiet",
    );
    assert!(stderr.is_empty(), "{stderr}");
    assert_eq!(
        std::fs::read(&loud).unwrap(),
        std::fs::read(&quiet).unwrap()
    );

    let out = dir.path().join("back.npy");
    let (_, stderr) = succeeded(
        &tvf(&[
            "decompress",
            &m,
            loud.to_str().unwrap(),
            "--basis",
            b,
            "-o",
            out.to_str().unwrap(),
        ]),
        "decompress",
    );
    assert!(stderr.contains("decompress: frames 8/8"), "{stderr}");
}

/// Every subcommand that prints a report takes `--json` and then prints exactly one JSON
/// object on stdout (progress and notes stay on stderr).
#[test]
fn json_reports_are_one_object_on_stdout() {
    let dir = tempfile::tempdir().unwrap();
    let (mesh, m) = write_mesh(dir.path());
    let field = dir.path().join("field.txt");
    std::fs::write(&field, swirl_text(&mesh, 0.0)).unwrap();
    let f = field.to_str().unwrap().to_string();
    let d = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let constraints = d("c.json");
    std::fs::write(
        &constraints,
        r#"{"constraints": [{"id": "a", "kind": "vector", "face": 5, "value": [1, 0, 0]},
                            {"id": "s", "kind": "divergence", "vertex": 40, "value": 1.0}]}"#,
    )
    .unwrap();
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<String>>();
    let b = d("b.tvfb");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (s(&["info", &m]), "genus"),
        (s(&["spectrum", &m, "-k", "8"]), "eigenvalues"),
        (s(&["basis", &m, "-k", "20", "-o", &b]), "eigenvalues"),
        (
            s(&["decompose", &m, &f, "-o", &d("parts")]),
            "harmonic_energy",
        ),
        (s(&["coefficients", &m, &f, "--basis", &b]), "coefficients"),
        (
            s(&["filter", &m, &f, "--basis", &b, "-o", &d("x.npy")]),
            "rest_norm",
        ),
        (
            s(&["analyze", &m, &f, "--basis", &b, "-o", &d("an")]),
            "relative_rest_norm",
        ),
        (
            s(&[
                "compress",
                &m,
                &f,
                "--basis",
                &b,
                "--pairs",
                "4",
                "-o",
                &d("x.tvfc"),
            ]),
            "bytes",
        ),
        (
            s(&[
                "rate-distortion",
                &m,
                &f,
                "--basis",
                &b,
                "--pairs",
                "2,4",
                "-o",
                &d("rd"),
            ]),
            "points",
        ),
        (
            s(&[
                "spline",
                &m,
                "--constraints",
                &constraints,
                "--basis",
                &b,
                "-o",
                &d("s.npy"),
            ]),
            "worst_relative_residual",
        ),
        (
            s(&[
                "design",
                &m,
                "--constraints",
                &constraints,
                "--reduced",
                "--basis",
                &b,
                "-o",
                &d("r.npy"),
            ]),
            "worst_relative_residual",
        ),
        (
            s(&[
                "design",
                &m,
                "--constraints",
                &constraints,
                "--full",
                "-o",
                &d("f.npy"),
            ]),
            "system_residuals",
        ),
    ];
    for (mut args, key) in cases {
        args.push("--json".to_string());
        let (stdout, _) = succeeded(&tvf(&args), &args[0]);
        let value: serde_json::Value = serde_json::from_str(&stdout)
            .unwrap_or_else(|e| panic!("{args:?}: not one JSON object ({e}): {stdout}"));
        assert!(value.get(key).is_some(), "{args:?}: no '{key}' in {stdout}");
    }
}

/// The shared flags are spelled the same in every subcommand's help: `-o, --output`,
/// `--decomposition`, `--mass`, `-k` meaning eigenfields, `--basis FILE`.
#[test]
fn shared_flags_are_spelled_the_same_everywhere() {
    let help = |sub: &str| {
        let output = tvf(&[sub, "--help"]);
        String::from_utf8_lossy(&output.stdout).into_owned()
    };
    for sub in [
        "operators",
        "basis",
        "decompose",
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
    ] {
        let text = help(sub);
        assert!(text.contains("-o, --output <"), "{sub}: no `-o, --output`");
    }
    for sub in [
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
        "edit",
    ] {
        let text = help(sub);
        assert!(text.contains("--decomposition <NAME>"), "{sub}");
        assert!(text.contains("--mass <NAME>"), "{sub}");
    }
    for sub in [
        "basis",
        "spectrum",
        "coefficients",
        "filter",
        "analyze",
        "compress",
        "decompress",
        "rate-distortion",
        "spline",
        "design",
        "edit",
        "demo",
    ] {
        let text = help(sub);
        // The -k line and the next (short help keeps the text on the flag's line).
        let line: String = text
            .lines()
            .skip_while(|l| !l.trim_start().starts_with("-k <K>"))
            .take(2)
            .collect();
        assert!(
            text.contains("-k <K>")
                && (line.contains("eigenfields") || line.contains("eigenvalues")),
            "{sub}: -k is not the number of eigenfields:\n{text}"
        );
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
        assert!(help(sub).contains("--basis <FILE>"), "{sub}");
        assert!(help(sub).contains("--cache-dir <DIR>"), "{sub}");
    }
}
