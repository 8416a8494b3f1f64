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

    // The subcommands that work in a basis, with `--example icosphere`, one positional and the
    // basis flags; `@NAME` is the file NAME in the folder, and the file each must write (none for
    // coefficients: its JSON on stdout). Compress runs before decompress, which reads its file.
    let runs: [(&[&str], &str); 6] = [
        (&["coefficients", "@field.txt", "--json"], ""),
        (
            &["filter", "@field.txt", "-o", "@filtered.npy"],
            "filtered.npy",
        ),
        (
            &["analyze", "@field.txt", "-o", "@analysis"],
            "analysis/spectrum.png",
        ),
        (
            &[
                "compress",
                "@field.txt",
                "--pairs",
                "8",
                "-o",
                "@field.tvfc",
            ],
            "field.tvfc",
        ),
        (
            &["decompress", "@field.tvfc", "-o", "@decompressed.npy"],
            "decompressed.npy",
        ),
        (
            &[
                "rate-distortion",
                "@field.txt",
                "--pairs",
                "2,4",
                "-o",
                "@rd",
            ],
            "rd/rate_distortion.csv",
        ),
    ];
    let mut coefficients = String::new();
    for (args, written) in runs {
        let mut command = Command::new(env!("CARGO_BIN_EXE_tvf"));
        command.arg(args[0]).args(["--example", "icosphere"]);
        for arg in &args[1..] {
            match arg.strip_prefix('@') {
                Some(name) => command.arg(d(name)),
                None => command.arg(arg),
            };
        }
        command.args(["-k", "24", "--cache-dir"]).arg(&cache);
        let stdout = succeeded(&command.output().unwrap(), args[0]);
        if written.is_empty() {
            coefficients = stdout;
        } else {
            assert!(d(written).is_file(), "{args:?}: no {written}");
        }
    }
    let json: serde_json::Value = serde_json::from_str(&coefficients).unwrap();
    assert_eq!(json["coefficients"].as_array().unwrap().len(), 24);

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
    // The arguments and what the message must name besides `error:`.
    let cases: [(&[&str], &[&str]); 6] = [
        (
            &[
                "filter",
                "--example",
                "icosphere",
                "a.npy",
                "b.npy",
                "-o",
                "x.npy",
            ],
            &["--example replaces MESH", "b.npy"],
        ),
        (
            &[
                "render",
                "--example",
                "icosphere",
                "a.npy",
                "b.npy",
                "-o",
                "x.png",
            ],
            &[],
        ),
        (
            &["decompose", "--example", "icosphere", "-o", "parts"],
            &["<FIELD>"],
        ),
        (
            &["decompress", "--example", "icosphere", "-o", "x.npy"],
            &[],
        ),
        (
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
            &[],
        ),
        (
            &["render", "--example", "icosphere", "--parts", "-o", "x.png"],
            &[],
        ),
    ];
    for (args, names) in cases {
        let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
            .args(args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        for name in ["error:"].iter().chain(names) {
            assert!(stderr.contains(name), "{args:?}: no {name} in {stderr}");
        }
    }
}
