//! End-to-end: `tvf spectrum --json` against the union of the cotan and Crouzeix–Raviart spectra
//! assembled here from the triangle geometry alone (independent of tvf's operator code).
//!
//! The real meshes come from `../shared/meshes` (skipped when absent, a failure under `CI=true`):
//! kitten and 3holes always; eight and hand too when `TVF_LONG_TESTS` is set (they take longer).

use crate::common::assert_success;
use std::path::Path;
use std::process::Command;
use std::time::Instant;
use tvf_core::io::load_mesh;
use tvf_core::TriangleMesh;
use tvf_solvers::{lowest_eigenpairs, EigenOptions};
use tvf_test_support::shared_mesh;

fn spectrum_json(mesh: &Path, k: usize, decomposition: &str) -> serde_json::Value {
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .arg("spectrum")
        .arg(mesh)
        .args([
            "-k",
            &k.to_string(),
            "--decomposition",
            decomposition,
            "--json",
            "--quiet",
        ])
        .output()
        .unwrap();
    assert_success(&output);
    serde_json::from_slice(&output.stdout).unwrap()
}

/// Cotan stiffness (vertices) and CR stiffness (edges) with barycentric masses, from angles.
fn independent_problems(mesh: &TriangleMesh) -> [(sprs::CsMat<f64>, Vec<f64>); 2] {
    let p = mesh.positions();
    let edge_index: std::collections::HashMap<(usize, usize), usize> = mesh
        .edges()
        .iter()
        .enumerate()
        .map(|(i, e)| ((e[0], e[1]), i))
        .collect();
    let mut cotan = sprs::TriMat::new((mesh.vertex_count(), mesh.vertex_count()));
    let mut cr = sprs::TriMat::new((mesh.edge_count(), mesh.edge_count()));
    let mut vertex_mass = vec![0.0; mesh.vertex_count()];
    let mut edge_mass = vec![0.0; mesh.edge_count()];
    for face in mesh.faces() {
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let area = dot(
            cross(sub(p[face[1]], p[face[0]]), sub(p[face[2]], p[face[0]])),
            cross(sub(p[face[1]], p[face[0]]), sub(p[face[2]], p[face[0]])),
        )
        .sqrt()
            / 2.0;
        // cot of the angle at corner c
        let cot: Vec<f64> = (0..3)
            .map(|c| {
                let (u, v) = (
                    sub(p[face[(c + 1) % 3]], p[face[c]]),
                    sub(p[face[(c + 2) % 3]], p[face[c]]),
                );
                dot(u, v) / (2.0 * area)
            })
            .collect();
        let opposite = |c: usize| {
            let (a, b) = (face[(c + 1) % 3], face[(c + 2) % 3]);
            edge_index[&(a.min(b), a.max(b))]
        };
        // local P1 stiffness: K_cd = −cot(angle at the third corner)/2, K_cc = Σ others
        for c in 0..3 {
            vertex_mass[face[c]] += area / 3.0;
            edge_mass[opposite(c)] += area / 3.0;
            for d in 0..3 {
                let value = if c == d {
                    (cot[(c + 1) % 3] + cot[(c + 2) % 3]) / 2.0
                } else {
                    -cot[3 - c - d] / 2.0
                };
                cotan.add_triplet(face[c], face[d], value);
                // CR basis function of the edge opposite c is 1 − 2 φ_c: gradients −2 ∇φ_c
                cr.add_triplet(opposite(c), opposite(d), 4.0 * value);
            }
        }
    }
    [(cotan.to_csr(), vertex_mass), (cr.to_csr(), edge_mass)]
}

fn check_mesh(path: &Path, genus: usize, k: usize) {
    let start = Instant::now();
    let mesh = load_mesh(path).unwrap().mesh.into_triangles().unwrap();
    let mut expected = vec![0.0; 2 * genus];
    for (stiffness, mass) in independent_problems(&mesh) {
        let pairs = lowest_eigenpairs(&stiffness, &mass, k + 1, &EigenOptions::default()).unwrap();
        expected.extend_from_slice(&pairs.values[1..]);
    }
    expected.sort_by(f64::total_cmp);
    expected.truncate(k);
    let reference_seconds = start.elapsed().as_secs_f64();
    let scale = expected[k - 1];
    for decomposition in ["conforming", "nonconforming"] {
        let json = spectrum_json(path, k, decomposition);
        let values: Vec<f64> = json["eigenvalues"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let labels = json["labels"].as_array().unwrap();
        assert_eq!(values.len(), k);
        assert_eq!(labels.len(), k);
        assert_eq!(
            labels.iter().filter(|l| *l == "harmonic").count(),
            2 * genus
        );
        assert!(values.windows(2).all(|w| w[0] <= w[1]), "ascending");
        for (i, (a, b)) in values.iter().zip(&expected).enumerate() {
            // relative 1e-8; harmonic zeros are exactly 0 in both
            assert!(
                (a - b).abs() <= 1e-8 * b.abs().max(1e-3 * scale),
                "{} {decomposition} #{i}: {a} vs {b}",
                path.display()
            );
        }
        println!(
            "{} {decomposition}: {k} eigenvalues in {:.2} s (reference {reference_seconds:.2} s)",
            path.display(),
            json["seconds"].as_f64().unwrap()
        );
    }
}

#[test]
fn spectrum_equals_the_union_of_the_cotan_and_cr_spectra() {
    let mut meshes = vec![("kitten", 1), ("3holes", 3)];
    if std::env::var_os("TVF_LONG_TESTS").is_some() {
        meshes.extend([("eight", 2), ("hand", 0)]);
    }
    for (name, genus) in meshes {
        if let Some(path) = shared_mesh(&format!("{name}.obj")) {
            check_mesh(&path, genus, 100);
        }
    }
}

#[test]
fn spectrum_json_on_a_generated_mesh_and_bad_input() {
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args([
            "spectrum",
            "--example",
            "genus2",
            "-k",
            "12",
            "--json",
            "--quiet",
        ])
        .output()
        .unwrap();
    assert_success(&output);
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let labels: Vec<&str> = json["labels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap())
        .collect();
    assert_eq!(&labels[..4], ["harmonic"; 4]);
    assert!(labels[4..]
        .iter()
        .all(|l| *l == "integrable" || *l == "cointegrable"));
    assert!(json["seconds"].as_f64().unwrap() >= 0.0);
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args(["spectrum", "nowhere.off", "-k", "5"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("nowhere.off"));
}
