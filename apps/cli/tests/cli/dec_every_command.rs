//! The DEC 1-form entry of the catalog (`dec-circumcentric`) through every subcommand that builds
//! a complex, on the Delaunay icosphere(3), with nothing in the commands special to it: the
//! catalog line is all it takes.

use crate::common::{assert_success, tvf, write_field_and_constraints};
use serde_json::Value;
use std::path::Path;
use tvf_core::generate::icosphere;
use tvf_core::io::write_obj;

const DEC: &str = "dec-circumcentric";

fn run(dir: &Path, args: &[&str]) -> std::process::Output {
    let output = tvf()
        .current_dir(dir)
        .args(args)
        .args(["--discretization", DEC, "--quiet"])
        .output()
        .expect("the tvf binary runs");
    assert_success(&output);
    output
}

fn json(output: &std::process::Output) -> Value {
    serde_json::from_slice(&output.stdout).expect("JSON on stdout")
}

#[test]
fn dec_runs_through_every_command() {
    let temp = tempfile::tempdir().unwrap();
    let dir = temp.path();
    let mesh = icosphere(3);
    write_obj(dir.join("sphere.obj"), &mesh).unwrap();
    write_field_and_constraints(&mesh, dir);

    // spectrum: the sphere's l = 1 level (eigenvalue ≈ 2) three times in each family.
    let spectrum = json(&run(dir, &["spectrum", "sphere.obj", "-k", "6", "--json"]));
    assert_eq!(spectrum["discretization"], DEC);
    for value in spectrum["eigenvalues"].as_array().unwrap() {
        let value = value.as_f64().unwrap();
        assert!((value - 2.0).abs() < 0.05, "l = 1 eigenvalue {value}");
    }

    run(dir, &["basis", "sphere.obj", "-k", "40", "-o", "b.tvfb"]);
    let coefficients = json(&run(
        dir,
        &[
            "coefficients",
            "sphere.obj",
            "field.txt",
            "--basis",
            "b.tvfb",
            "--json",
        ],
    ));
    assert_eq!(coefficients["discretization"], DEC);
    let decompose = json(&run(
        dir,
        &[
            "decompose",
            "sphere.obj",
            "field.txt",
            "-o",
            "parts",
            "--json",
        ],
    ));
    assert!(dir.join("parts/integrable.npy").is_file(), "{decompose}");
    run(
        dir,
        &[
            "filter",
            "sphere.obj",
            "field.txt",
            "-k",
            "40",
            "-o",
            "smooth.npy",
        ],
    );
    run(
        dir,
        &[
            "analyze",
            "sphere.obj",
            "field.txt",
            "-k",
            "40",
            "-o",
            "analysis",
        ],
    );
    run(
        dir,
        &[
            "compress",
            "sphere.obj",
            "field.txt",
            "--pairs",
            "15",
            "-o",
            "f.tvfc",
        ],
    );
    run(
        dir,
        &["decompress", "sphere.obj", "f.tvfc", "-o", "back.npy"],
    );
    run(
        dir,
        &[
            "rate-distortion",
            "sphere.obj",
            "field.txt",
            "--pairs",
            "5,15",
            "-o",
            "rd",
        ],
    );
    let spline = json(&run(
        dir,
        &[
            "spline",
            "sphere.obj",
            "--constraints",
            "c.json",
            "-k",
            "60",
            "-o",
            "spline.npy",
            "--json",
        ],
    ));
    assert_eq!(spline["discretization"], DEC);
    run(
        dir,
        &[
            "design",
            "sphere.obj",
            "--constraints",
            "c.json",
            "--reduced",
            "-k",
            "60",
            "-o",
            "reduced.npy",
        ],
    );
    run(
        dir,
        &[
            "design",
            "sphere.obj",
            "--constraints",
            "c.json",
            "--full",
            "-o",
            "full.npy",
        ],
    );
    run(
        dir,
        &[
            "render",
            "sphere.obj",
            "spline.npy",
            "--color",
            "curl",
            "-o",
            "spline.png",
            "--size",
            "160x120",
        ],
    );
    run(
        dir,
        &[
            "export",
            "sphere.obj",
            "spline.npy",
            "--format",
            "vtk",
            "-o",
            "spline.vtk",
        ],
    );
    run(dir, &["operators", "sphere.obj", "-o", "matrices"]);
    let info: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("matrices/info.json")).unwrap())
            .unwrap();
    assert_eq!(info["nodes"]["fields"], "edges");
    assert!(
        !dir.join("matrices/J.mtx").exists(),
        "DEC has no rotation J"
    );
    run(
        dir,
        &["demo", "--quick", "--mesh", "sphere.obj", "-o", "demo"],
    );
    for file in [
        "smooth.npy",
        "analysis",
        "back.npy",
        "rd",
        "spline.npy",
        "reduced.npy",
        "full.npy",
        "spline.png",
        "spline.vtk",
        "matrices/d0.mtx",
        "demo/index.html",
    ] {
        assert!(dir.join(file).exists(), "{file} was not written");
    }
}

#[test]
fn dec_on_a_non_delaunay_mesh_is_refused_with_the_edge_count() {
    let temp = tempfile::tempdir().unwrap();
    // A torus from a quad grid: its diagonals have cot α + cot β = 0 (right angles opposite).
    let mesh = tvf_core::generate::torus(1.0, 0.4, 16, 8).unwrap();
    write_obj(temp.path().join("torus.obj"), &mesh).unwrap();
    // Counted here independently: edges whose two opposite corners' cotangents sum to ≤ 0.
    let mut sums = std::collections::HashMap::new();
    for f in mesh.faces() {
        for c in 0..3 {
            let p = |k: usize| mesh.positions()[f[(c + k) % 3]];
            let (o, a, b) = (p(0), p(1), p(2));
            let u: [f64; 3] = std::array::from_fn(|k| a[k] - o[k]);
            let v: [f64; 3] = std::array::from_fn(|k| b[k] - o[k]);
            let dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
            let cross = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let cot = dot / (cross[0].powi(2) + cross[1].powi(2) + cross[2].powi(2)).sqrt();
            let edge = (
                f[(c + 1) % 3].min(f[(c + 2) % 3]),
                f[(c + 1) % 3].max(f[(c + 2) % 3]),
            );
            *sums.entry(edge).or_insert(0.0) += cot;
        }
    }
    let bad = sums.values().filter(|&&s| s <= 1e-12).count();
    assert!(bad > 0);
    let output = tvf()
        .current_dir(temp.path())
        .args([
            "spectrum",
            "torus.obj",
            "-k",
            "10",
            "--discretization",
            "dec-barycentric",
        ])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("torus.obj"), "{stderr}");
    assert!(stderr.contains("not Delaunay"), "{stderr}");
    assert!(stderr.contains(&format!("{bad} edges")), "{bad}: {stderr}");
}
