//! `--example NAME` combined with a second positional (`FIELD`, `FILE.tvfc`): with the example
//! in place of MESH, the one positional is the field, in every subcommand that takes one, and
//! the result equals the one from the same mesh given as a file. Misuse is a usage error (2).

use std::path::Path;
use std::process::{Command, Output};
use tvf_core::generate::{bumpy_torus, icosphere};
use tvf_core::io::write_obj;
use tvf_core::TriangleMesh;

fn tvf(args: &[&dyn AsRef<std::ffi::OsStr>]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_tvf"));
    for arg in args {
        command.arg(arg);
    }
    command.output().unwrap()
}

fn succeeded(output: &Output, what: &str) -> String {
    assert!(
        output.status.success(),
        "{what}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// One 3D vector per face: a swirl about the z axis plus a wave (not tangent; tools project).
fn write_field(path: &Path, mesh: &TriangleMesh) {
    let p = mesh.positions();
    let text: String = mesh
        .faces()
        .iter()
        .map(|f| {
            let c: [f64; 3] = std::array::from_fn(|i| (p[f[0]][i] + p[f[1]][i] + p[f[2]][i]) / 3.0);
            format!("{} {} {}\n", -c[1], c[0], (2.0 * c[0]).sin())
        })
        .collect();
    std::fs::write(path, text).unwrap();
}

/// The example `icosphere` is `icosphere(3)`: every subcommand with `MESH FIELD` accepts
/// `--example icosphere FIELD` and produces the same output as with the mesh as a file.
#[test]
fn every_mesh_and_field_subcommand_takes_an_example_and_a_field() {
    let dir = tempfile::tempdir().unwrap();
    let d = |name: &str| dir.path().join(name);
    let mesh = icosphere(3);
    let mesh_file = d("icosphere.obj");
    write_obj(&mesh_file, &mesh).unwrap();
    let field = d("field.txt");
    write_field(&field, &mesh);
    let cache = d("cache");
    let basis = [
        &"-k" as &dyn AsRef<std::ffi::OsStr>,
        &"24",
        &"--cache-dir",
        &cache,
    ];

    // Same output with the example and with the file (decompose: deterministic files).
    for (source, out) in [("example", d("parts-example")), ("file", d("parts-file"))] {
        let output = if source == "example" {
            tvf(&[
                &"decompose",
                &"--example",
                &"icosphere",
                &field,
                &"-o",
                &out,
            ])
        } else {
            tvf(&[&"decompose", &mesh_file, &field, &"-o", &out])
        };
        succeeded(&output, "decompose");
    }
    for part in ["integrable.npy", "cointegrable.npy", "harmonic.npy"] {
        assert_eq!(
            std::fs::read(d("parts-example").join(part)).unwrap(),
            std::fs::read(d("parts-file").join(part)).unwrap(),
            "{part}"
        );
    }

    let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![
        &"coefficients",
        &"--example",
        &"icosphere",
        &field,
        &"--json",
    ];
    args.extend(basis);
    let json: serde_json::Value =
        serde_json::from_str(&succeeded(&tvf(&args), "coefficients")).unwrap();
    assert_eq!(json["coefficients"].as_array().unwrap().len(), 24);

    let filtered = d("filtered.npy");
    let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![
        &"filter",
        &"--example",
        &"icosphere",
        &field,
        &"-o",
        &filtered,
    ];
    args.extend(basis);
    succeeded(&tvf(&args), "filter");
    assert!(filtered.is_file());

    let analysis = d("analysis");
    let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![
        &"analyze",
        &"--example",
        &"icosphere",
        &field,
        &"-o",
        &analysis,
    ];
    args.extend(basis);
    succeeded(&tvf(&args), "analyze");
    assert!(analysis.join("spectrum.png").is_file());

    let compressed = d("field.tvfc");
    let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![
        &"compress",
        &"--example",
        &"icosphere",
        &field,
        &"--pairs",
        &"8",
        &"-o",
        &compressed,
    ];
    args.extend(basis);
    succeeded(&tvf(&args), "compress");
    assert!(compressed.is_file());

    let decompressed = d("decompressed.npy");
    let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![
        &"decompress",
        &"--example",
        &"icosphere",
        &compressed,
        &"-o",
        &decompressed,
    ];
    args.extend(basis);
    succeeded(&tvf(&args), "decompress");
    assert!(decompressed.is_file());

    let rd = d("rd");
    let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![
        &"rate-distortion",
        &"--example",
        &"icosphere",
        &field,
        &"--pairs",
        &"2,4",
        &"-o",
        &rd,
    ];
    args.extend(basis);
    succeeded(&tvf(&args), "rate-distortion");
    assert!(rd.join("rate_distortion.csv").is_file());

    let vtk = d("field.vtk");
    succeeded(
        &tvf(&[&"export", &"--example", &"icosphere", &field, &"-o", &vtk]),
        "export",
    );
    let text = std::fs::read_to_string(&vtk).unwrap();
    assert!(text.contains(&format!("CELL_DATA {}", mesh.face_count())));
}

/// The command from the issue: `tvf render --example bumpy-torus field.npy -o out.png` draws
/// the field (the picture differs from the mesh alone).
#[test]
fn render_takes_an_example_and_a_field() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = bumpy_torus(1.0, 0.3, 96, 48, 24, 0.35).unwrap();
    let field = dir.path().join("field.txt");
    write_field(&field, &mesh);
    let with_field = dir.path().join("out.png");
    let alone = dir.path().join("mesh.png");
    let size: [&dyn AsRef<std::ffi::OsStr>; 2] = [&"--size", &"200x150"];
    let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![
        &"render",
        &"--example",
        &"bumpy-torus",
        &field,
        &"-o",
        &with_field,
    ];
    args.extend(size);
    succeeded(&tvf(&args), "render with a field");
    let mut args: Vec<&dyn AsRef<std::ffi::OsStr>> =
        vec![&"render", &"--example", &"bumpy-torus", &"-o", &alone];
    args.extend(size);
    succeeded(&tvf(&args), "render the mesh alone");
    let a = image::open(&with_field).unwrap().to_rgba8();
    let b = image::open(&alone).unwrap().to_rgba8();
    assert_eq!(a.dimensions(), (200, 150));
    assert_ne!(a.as_raw(), b.as_raw(), "the field was not drawn");
}

/// A mesh file and --example, two positionals with --example, or none where one is required:
/// usage errors with exit code 2 and a message.
#[test]
fn misusing_example_is_a_usage_error() {
    let cases: [&[&str]; 6] = [
        &[
            "filter",
            "--example",
            "icosphere",
            "a.npy",
            "b.npy",
            "-o",
            "x.npy",
        ],
        &[
            "render",
            "--example",
            "icosphere",
            "a.npy",
            "b.npy",
            "-o",
            "x.png",
        ],
        &["decompose", "--example", "icosphere", "-o", "parts"],
        &["decompress", "--example", "icosphere", "-o", "x.npy"],
        &[
            "basis",
            "mesh.obj",
            "--example",
            "icosphere",
            "-k",
            "4",
            "-o",
            "b.tvfb",
        ],
        &["render", "--example", "icosphere", "--parts", "-o", "x.png"],
    ];
    for args in cases {
        let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
            .args(args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains("error:"), "{args:?}: {stderr}");
    }
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args([
            "filter",
            "--example",
            "icosphere",
            "a.npy",
            "b.npy",
            "-o",
            "x.npy",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("--example replaces MESH") && stderr.contains("b.npy"),
        "{stderr}"
    );
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args(["decompose", "--example", "icosphere", "-o", "parts"])
        .output()
        .unwrap();
    assert!(
        String::from_utf8_lossy(&output.stderr).contains("<FIELD>"),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}
