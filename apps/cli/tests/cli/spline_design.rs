//! End-to-end: `tvf spline` and `tvf design` on a generated genus-1 mesh written to an OBJ file:
//! output files, printed residuals, and errors naming the constraint file.

use std::path::Path;
use std::process::{Command, Output};
use tvf_core::generate::genus_surface;
use tvf_core::io::write_obj;
use tvf_spectral::read_face_vectors;

fn tvf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args(args)
        .output()
        .expect("the tvf binary runs")
}

const CONSTRAINTS: &str = r#"{"omega": 0.1, "constraints": [
  {"id": "east", "kind": "vector", "face": 12, "value": [1, 0, 0]},
  {"id": "north", "kind": "vector", "face": 100, "barycentric": [0.2, 0.3, 0.5], "value": [0, 1, 0]},
  {"id": "source", "kind": "divergence", "vertex": 40, "value": 2.0, "weight": 5},
  {"id": "vortex", "kind": "curl", "edge": 77, "value": -1.0},
  {"id": "swirl", "kind": "curl", "face": 150, "barycentric": [0.3, 0.3, 0.4], "value": 1.0}]}"#;

fn setup(dir: &Path) -> (String, String, usize) {
    let mesh = genus_surface(1, 4);
    let mesh_path = dir.join("ring.obj");
    write_obj(&mesh_path, &mesh).expect("write mesh");
    let constraints = dir.join("c.json");
    std::fs::write(&constraints, CONSTRAINTS).expect("write constraints");
    (
        mesh_path.display().to_string(),
        constraints.display().to_string(),
        mesh.face_count(),
    )
}

/// The relative residual printed for constraint `id`.
fn printed_residual(stdout: &str, id: &str) -> f64 {
    let line = stdout
        .lines()
        .find(|l| l.split_whitespace().next() == Some(id))
        .unwrap_or_else(|| panic!("no residual line for {id} in:\n{stdout}"));
    line.split_whitespace()
        .nth(2)
        .and_then(|v| v.parse().ok())
        .expect("relative residual")
}

#[test]
fn spline_meets_the_constraints_and_writes_a_field() {
    let dir = tempfile::tempdir().unwrap();
    let (mesh, constraints, faces) = setup(dir.path());
    let out = dir.path().join("spline.npy");
    let output = tvf(&[
        "spline",
        &mesh,
        "--constraints",
        &constraints,
        "-k",
        "400",
        "-o",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        stdout.contains("spline setup") && stdout.contains("spline solve"),
        "{stdout}"
    );
    for id in ["east", "north", "source", "vortex", "swirl"] {
        assert!(printed_residual(&stdout, id) < 1e-9, "{id}: {stdout}");
    }
    let vectors = read_face_vectors(&out).expect("F×3 field");
    assert_eq!(vectors.len(), faces);
    assert!(vectors.iter().flatten().all(|x| x.is_finite()));
    // Constraint "east" is met: the tangent part of (1, 0, 0) at face 12.
    assert!(vectors[12].iter().map(|x| x * x).sum::<f64>() > 0.0);
}

#[test]
fn design_full_and_reduced_write_fields_and_report_residuals() {
    let dir = tempfile::tempdir().unwrap();
    let (mesh, constraints, faces) = setup(dir.path());
    let full = dir.path().join("full.npy");
    let output = tvf(&[
        "design",
        &mesh,
        "--constraints",
        &constraints,
        "--full",
        "-o",
        full.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        stdout.contains("full factor") && stdout.contains("system residual"),
        "{stdout}"
    );
    // Soft constraints: finite residuals, not all met exactly.
    let soft: Vec<f64> = ["east", "north", "vortex"]
        .iter()
        .map(|id| printed_residual(&stdout, id))
        .collect();
    assert!(
        soft.iter().all(|r| r.is_finite()) && soft.iter().any(|&r| r > 1e-4),
        "{stdout}"
    );
    assert_eq!(read_face_vectors(&full).unwrap().len(), faces);

    let reduced = dir.path().join("reduced.txt");
    let output = tvf(&[
        "design",
        &mesh,
        "--constraints",
        &constraints,
        "--reduced",
        "-k",
        "400",
        "-o",
        reduced.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        stdout.contains("reduced factor") && stdout.contains("reduced solve"),
        "{stdout}"
    );
    assert_eq!(read_face_vectors(&reduced).unwrap().len(), faces);
}

#[test]
fn full_design_orderings_give_the_same_field() {
    let dir = tempfile::tempdir().unwrap();
    let (mesh, constraints, _) = setup(dir.path());
    let mut fields = Vec::new();
    for ordering in ["amd", "nd"] {
        let path = dir.path().join(format!("{ordering}.npy"));
        let output = tvf(&[
            "design",
            &mesh,
            "--constraints",
            &constraints,
            "--full",
            "--ordering",
            ordering,
            "-o",
            path.to_str().unwrap(),
        ]);
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(output.status.success(), "{stdout}");
        assert!(
            stdout.contains(&format!("{ordering} ordering")) && stdout.contains("rounding floor"),
            "{stdout}"
        );
        fields.push(read_face_vectors(&path).unwrap());
    }
    let scale = fields[1]
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    for (a, b) in fields[0].iter().flatten().zip(fields[1].iter().flatten()) {
        assert!((a - b).abs() <= 1e-9 * scale, "{a} vs {b}");
    }
    for bad in [
        vec!["--full", "--ordering", "colamd"],
        vec!["--reduced", "--ordering", "amd"],
    ] {
        let out = dir.path().join("bad.npy");
        let mut args = vec!["design", &mesh, "--constraints", &constraints];
        args.extend(bad.iter().copied());
        args.extend(["-o", out.to_str().unwrap()]);
        let output = tvf(&args);
        assert_eq!(output.status.code(), Some(2), "{bad:?}");
        assert!(String::from_utf8_lossy(&output.stderr).contains("--ordering"));
    }
}

#[test]
fn bad_constraint_files_are_reported_with_file_and_id() {
    let dir = tempfile::tempdir().unwrap();
    let (mesh, _, _) = setup(dir.path());
    let bad = dir.path().join("bad.json");
    std::fs::write(
        &bad,
        r#"{"constraints": [{"id": "far", "kind": "vector", "face": 999999, "value": [1, 0, 0]}]}"#,
    )
    .unwrap();
    let out = dir.path().join("x.npy");
    let output = tvf(&[
        "spline",
        &mesh,
        "--constraints",
        bad.to_str().unwrap(),
        "-k",
        "400",
        "-o",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr.contains("bad.json") && stderr.contains("'far'") && stderr.contains("out of range"),
        "{stderr}"
    );
    assert!(!out.exists());

    let twice = dir.path().join("twice.json");
    std::fs::write(
        &twice,
        r#"{"constraints": [{"id": "a", "kind": "vector", "face": 3, "value": [1, 0, 0]},
                            {"id": "b", "kind": "vector", "face": 3, "value": [0, 1, 0]}]}"#,
    )
    .unwrap();
    let output = tvf(&[
        "spline",
        &mesh,
        "--constraints",
        twice.to_str().unwrap(),
        "-k",
        "400",
        "-o",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr.contains("'b'") && stderr.contains("conflicting") && stderr.contains("\"a\""),
        "{stderr}"
    );
}

#[test]
fn a_malformed_thread_limit_variable_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let (mesh, constraints, _) = setup(dir.path());
    let out = dir.path().join("full.npy");
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args([
            "design",
            &mesh,
            "--constraints",
            &constraints,
            "--full",
            "-o",
        ])
        .arg(&out)
        .env("TVF_SEQUENTIAL_FLOP_LIMIT", "1e11x")
        .output()
        .expect("the tvf binary runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("TVF_SEQUENTIAL_FLOP_LIMIT") && stderr.contains("1e11x"),
        "{stderr}"
    );
    assert!(!out.exists(), "no field is written");
}
