//! The editor on a basis file read on demand ([`ReducedBasis::on_demand`] over
//! [`BasisFileBlocks`]: the rows of `U` read when a constraint first touches them, the `f32` copy
//! formed in one pass over the file, never `U` in `f64`) against the same basis loaded whole
//! ([`ReducedBasis::from_spectral`]): after every edit — constraints added, a drag (the first
//! value change builds the drag cache, the next uses it), a smaller basis size, a constraint on
//! rows not read before — the field shown is the same bit for bit where `M1` is diagonal (the
//! same rows, the same `f32` copy); with a Galerkin `M1` (co-integrable rows through mass solves,
//! equal to round-off) the constraints hold to `1e-10` and the fields agree to `f32` rounding.

use serde_json::json;
use std::sync::Arc;
use tvf_core::generate::icosphere;
use tvf_core::SurfaceMesh;
use tvf_design::ReducedBasis;
use tvf_discretizations::{catalog_entry, DEFAULT_DISCRETIZATION};
use tvf_editor::{EditOp, Editor, EditorSetup};
use tvf_spectral::{load_basis, save_computed_basis, BasisFileBlocks, BasisFileKey, BasisRequest};

/// An editor on `icosphere(3)` with `basis` and the catalog entry `id`.
fn editor(id: &str, basis: ReducedBasis) -> Editor {
    let mesh = SurfaceMesh::from(icosphere(3));
    let complex = catalog_entry(id).unwrap().build(&mesh).unwrap();
    Editor::start(EditorSetup {
        mesh,
        basis,
        constraints: None,
        basis_size: None,
        complex,
    })
    .unwrap()
}

/// The edits applied to both editors, in order.
fn edits() -> Vec<serde_json::Value> {
    let vector = |x: f64| {
        json!({"op": "set", "constraint":
            {"id": "v", "kind": "vector", "face": 10, "value": [x, 1.0, 0.0]}})
    };
    vec![
        json!({"op": "add", "constraint":
            {"id": "v", "kind": "vector", "face": 10, "value": [0.0, 1.0, 0.0]}}),
        json!({"op": "add", "constraint":
            {"id": "c", "kind": "curl", "face": 500, "value": 3.0}}),
        vector(0.5),
        vector(0.8),
        json!({"op": "basis_size", "value": 60}),
        json!({"op": "add", "constraint":
            {"id": "w", "kind": "vector", "face": 900, "value": [1.0, 0.0, 0.5]}}),
        vector(1.2),
    ]
}

/// Both editors of catalog entry `id` (the basis file's 80 lowest eigenfields), edited alike;
/// fields compared after every edit (bit for bit if `exact`), constraints checked at the end.
fn on_demand_equals_whole(id: &str, exact: bool) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("basis.tvfb");
    let mesh = SurfaceMesh::from(icosphere(3));
    let complex = catalog_entry(id).unwrap().build(&mesh).unwrap();
    let key = BasisFileKey::new(&mesh, complex.as_ref());
    save_computed_basis(&path, complex.as_ref(), &BasisRequest::fields(80), &key).unwrap();
    let whole = load_basis(&path, &key, complex.as_ref()).unwrap();
    let whole = editor(id, ReducedBasis::from_spectral(&whole).unwrap());
    let blocks = BasisFileBlocks::open(&path, &key, complex)
        .unwrap()
        .unwrap();
    let on_demand = editor(id, ReducedBasis::on_demand(Arc::new(blocks)).unwrap());
    for (step, op) in edits().iter().enumerate() {
        for editor in [&whole, &on_demand] {
            let op = EditOp::parse(op.to_string().as_bytes()).unwrap();
            editor
                .edit(op)
                .unwrap_or_else(|e| panic!("edit {step}: {e}"));
        }
        let (expected, found) = (
            whole.face_vectors().unwrap(),
            on_demand.face_vectors().unwrap(),
        );
        if exact {
            assert_eq!(found, expected, "field after edit {step}");
        } else {
            let scale = expected
                .iter()
                .flatten()
                .fold(0.0f64, |m, x| m.max(x.abs()));
            for (a, b) in found.iter().flatten().zip(expected.iter().flatten()) {
                assert!(
                    (a - b).abs() <= 1e-6 * scale,
                    "edit {step}: {a} against {b}"
                );
            }
        }
    }
    let report = on_demand.check().unwrap();
    assert_eq!(report.constraints.len(), 3);
    assert!(report.max_relative < 1e-10, "{}", report.max_relative);
}

#[test]
fn an_editor_on_a_basis_file_read_on_demand_shows_the_loaded_basis_field() {
    on_demand_equals_whole(DEFAULT_DISCRETIZATION, true);
    on_demand_equals_whole("whitney-galerkin", false);
}
