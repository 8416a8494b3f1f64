//! `tvf spectrum --json` on generated meshes gives the 40 lowest eigenvalues and their families
//! recorded in `fixtures/recorded_spectra_generated.json`, to 1e-10: every finite-element entry
//! on two closed meshes (`genus2`, `bumpy-torus`) and on two meshes with boundary (`pants`,
//! `hemisphere`) under both boundary conditions, and both DEC entries on the Delaunay
//! `icosphere`. The values were recorded by the version of tvf before masses became SPD
//! operators, so this checks that the lumped entries kept their spectra; it needs no
//! `../shared` (`recorded_spectra_shared_meshes.rs` does the same on real meshes).

use crate::common::{assert_success, tvf};
use serde_json::Value;
use std::path::Path;

/// Relative tolerance on each eigenvalue (absolute below 1e-6, for the harmonic zeros).
const TOLERANCE: f64 = 1e-10;

/// Eigenvalues of `value["eigenvalues"]`.
fn eigenvalues(value: &Value) -> Vec<f64> {
    value["eigenvalues"]
        .as_array()
        .expect("eigenvalues")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

#[test]
fn generated_meshes_spectra_equal_the_recorded_ones() {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/recorded_spectra_generated.json");
    let recorded: Value =
        serde_json::from_str(&std::fs::read_to_string(&fixture).expect("fixture")).expect("JSON");
    let recorded = recorded.as_object().expect("an object");
    assert_eq!(
        recorded.len(),
        26,
        "4 finite-element entries × (2 closed meshes + 2 open meshes × 2 conditions), 2 DEC entries"
    );
    for (key, expected) in recorded {
        let parts: Vec<&str> = key.split('/').collect();
        let mut command = tvf();
        command.args([
            "spectrum",
            "--example",
            parts[0],
            "-k",
            "40",
            "--json",
            "--quiet",
            "--discretization",
            parts[1],
        ]);
        if let Some(boundary) = parts.get(2) {
            command.args(["--boundary", boundary]);
        }
        let output = command.output().expect("the tvf binary runs");
        assert_success(&output);
        let found: Value = serde_json::from_slice(&output.stdout).expect("JSON output");
        assert_eq!(found["labels"], expected["labels"], "{key}: families");
        let (a, b) = (eigenvalues(expected), eigenvalues(&found));
        assert_eq!(a.len(), 40, "{key}");
        assert_eq!(a.len(), b.len(), "{key}");
        for (i, (x, y)) in a.iter().zip(&b).enumerate() {
            let scale = x.abs().max(1e-6);
            assert!(
                (x - y).abs() <= TOLERANCE * scale,
                "{key}: eigenvalue {i} was {x:e}, is {y:e}"
            );
        }
    }
}
