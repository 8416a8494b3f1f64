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
/// and `filter`, and in `spline`: all see the same 12 lowest eigenvalues; `K ≥ 2F` is the
/// complete basis.
#[test]
fn k_is_the_number_of_eigenfields_in_every_subcommand() {
    let dir = tempfile::tempdir().unwrap();
    let (mesh, m) = write_mesh(dir.path());
    std::fs::write(dir.path().join("field.txt"), swirl_text(&mesh, 0.0)).unwrap();
    std::fs::write(
        dir.path().join("c.json"),
        r#"{"constraints": [{"id": "a", "kind": "vector", "face": 5, "value": [1, 0, 0]}]}"#,
    )
    .unwrap();
    let complete = format!("{} fields", 2 * mesh.face_count());
    // The runs in order (after the subcommand comes the mesh; `@NAME` is the file NAME in the
    // folder), what stdout and stderr must contain. The cache entry the first `-k 12` run with
    // `--cache-dir` makes is reused by the later ones.
    let runs: [(&[&str], &str, &str); 8] = [
        (&["spectrum", "-k", "12", "--json"], "eigenvalues", ""),
        (&["basis", "-k", "12", "-o", "@b.tvfb"], "", "12 fields"),
        (
            &["coefficients", "@field.txt", "--basis", "@b.tvfb", "--json"],
            "coefficients",
            "",
        ),
        (
            &[
                "coefficients",
                "@field.txt",
                "-k",
                "12",
                "--cache-dir",
                "@cache",
                "--json",
            ],
            "coefficients",
            "cached basis in",
        ),
        (
            &[
                "filter",
                "@field.txt",
                "-k",
                "12",
                "--cache-dir",
                "@cache",
                "-o",
                "@filtered.npy",
            ],
            "",
            "using cached basis",
        ),
        (
            &[
                "spline",
                "--constraints",
                "@c.json",
                "-k",
                "12",
                "--cache-dir",
                "@cache",
                "-o",
                "@spline.npy",
            ],
            "d = 12",
            "using cached basis",
        ),
        (
            &["basis", "-k", "100000", "-o", "@complete.tvfb"],
            "",
            &complete,
        ),
        (&["spectrum", "-k", "100000", "--json"], "eigenvalues", ""),
    ];
    let mut stdouts = Vec::new();
    for (args, on_stdout, on_stderr) in runs {
        let mut command = Command::new(env!("CARGO_BIN_EXE_tvf"));
        command.arg(args[0]).arg(&m);
        for arg in &args[1..] {
            match arg.strip_prefix('@') {
                Some(name) => command.arg(dir.path().join(name)),
                None => command.arg(arg),
            };
        }
        let (stdout, stderr) = succeeded(&command.output().unwrap(), args[0]);
        assert!(stdout.contains(on_stdout), "{args:?}: {stdout}");
        assert!(stderr.contains(on_stderr), "{args:?}: {stderr}");
        stdouts.push(stdout);
    }
    let values = |stdout: &str, list: &str, key: Option<&str>| -> Vec<f64> {
        json(stdout)[list]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| key.map_or(v, |k| &v[k]).as_f64().unwrap())
            .collect()
    };
    let spectrum = values(&stdouts[0], "eigenvalues", None);
    assert_eq!(spectrum.len(), 12);
    for stdout in &stdouts[2..4] {
        let eigenvalues = values(stdout, "coefficients", Some("eigenvalue"));
        assert_eq!(eigenvalues.len(), 12);
        for (a, b) in eigenvalues.iter().zip(&spectrum) {
            assert!((a - b).abs() <= 1e-8 * b.abs().max(1.0), "{a} vs {b}");
        }
    }
    // One cache entry, named for the discretization and the 12 fields.
    let names: Vec<String> = std::fs::read_dir(dir.path().join("cache"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 1, "{names:?}");
    assert!(
        names[0].contains("-conforming-barycentric-") && names[0].ends_with("-d12.tvfb"),
        "{names:?}"
    );
    assert_eq!(
        values(&stdouts[7], "eigenvalues", None).len(),
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
/// `--decomposition`, `--mass`, `-k` meaning eigenfields, `--basis FILE` with `--cache-dir DIR`.
#[test]
fn shared_flags_are_spelled_the_same_everywhere() {
    /// Which shared flags a subcommand's help must show.
    struct Flags {
        output: bool,
        discretization: bool,
        k: bool,
        basis: bool,
    }
    const fn flags(output: bool, discretization: bool, k: bool, basis: bool) -> Flags {
        Flags {
            output,
            discretization,
            k,
            basis,
        }
    }
    let cases = [
        ("operators", flags(true, true, false, false)),
        ("basis", flags(true, true, true, false)),
        ("spectrum", flags(false, true, true, false)),
        ("decompose", flags(true, true, false, false)),
        ("coefficients", flags(false, true, true, true)),
        ("filter", flags(true, true, true, true)),
        ("analyze", flags(true, true, true, true)),
        ("compress", flags(true, true, true, true)),
        ("decompress", flags(true, true, true, true)),
        ("rate-distortion", flags(true, true, true, true)),
        ("spline", flags(true, true, true, true)),
        ("design", flags(true, true, true, true)),
        ("render", flags(true, true, false, false)),
        ("export", flags(true, true, false, false)),
        ("edit", flags(false, true, true, true)),
        ("demo", flags(true, false, true, false)),
    ];
    for (sub, expected) in cases {
        let text = String::from_utf8_lossy(&tvf(&[sub, "--help"]).stdout).into_owned();
        if expected.output {
            assert!(text.contains("-o, --output <"), "{sub}: no `-o, --output`");
        }
        if expected.discretization {
            assert!(text.contains("--decomposition <NAME>"), "{sub}");
            assert!(text.contains("--mass <NAME>"), "{sub}");
        }
        if expected.k {
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
        if expected.basis {
            assert!(text.contains("--basis <FILE>"), "{sub}");
            assert!(text.contains("--cache-dir <DIR>"), "{sub}");
        }
    }
}
