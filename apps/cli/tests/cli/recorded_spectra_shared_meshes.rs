//! `tvf spectrum --json` on kitten, eight and hand from `../shared/meshes` gives the 40 lowest
//! eigenvalues and their families recorded in `fixtures/recorded_spectra.json` (by the version of
//! tvf before the matrices-first seam for every finite-element catalog entry, and by the version
//! before masses became SPD operators for the DEC entries on the Delaunay `eight`), to 1e-10.
//! `recorded_spectra.rs` checks generated meshes the same way, without `../shared`.
//!
//! Uses `../shared/meshes`; skips (with a message) where that folder does not exist, and fails
//! there under `CI=true`.

use crate::common::{assert_success, tvf};
use serde_json::Value;
use std::path::Path;
use tvf_test_support::shared_meshes;

/// Relative tolerance on each eigenvalue (absolute below 1e-6, for the harmonic zeros).
const TOLERANCE: f64 = 1e-10;

#[test]
fn shared_meshes_spectra_equal_the_recorded_ones() {
    let Some(dir) = shared_meshes() else {
        return;
    };
    let fixture =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/recorded_spectra.json");
    let recorded: Value =
        serde_json::from_str(&std::fs::read_to_string(&fixture).expect("fixture")).expect("JSON");
    let recorded = recorded.as_object().expect("an object");
    assert_eq!(
        recorded.len(),
        14,
        "3 meshes × 4 finite-element entries, and eight × 2 DEC entries"
    );
    for (key, expected) in recorded {
        let (mesh, id) = key.split_once('-').expect("MESH-ID");
        let output = tvf()
            .args([
                "spectrum",
                "-k",
                "40",
                "--json",
                "--quiet",
                "--discretization",
                id,
            ])
            .arg(dir.join(format!("{mesh}.obj")))
            .output()
            .expect("the tvf binary runs");
        assert_success(&output);
        let found: Value = serde_json::from_slice(&output.stdout).expect("JSON output");
        assert_eq!(found["labels"], expected["labels"], "{key}: families");
        let values = |v: &Value| -> Vec<f64> {
            v["eigenvalues"]
                .as_array()
                .expect("eigenvalues")
                .iter()
                .map(|x| x.as_f64().expect("a number"))
                .collect()
        };
        let (a, b) = (values(expected), values(&found));
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
