//! The editing engine on every catalog entry (icosphere(3) is Delaunay, so DEC builds too): a
//! vector, a divergence and a curl constraint at points of faces are met by the spline to
//! round-off, and the field frame the page draws has two face-frame coefficients per face.

use crate::common::icosphere_basis_for;
use tvf_core::generate::icosphere;
use tvf_core::SurfaceMesh;
use tvf_discretizations::builtin_catalog;
use tvf_editor::{decode_field_frame, EditOp, Editor, EditorSetup};

#[test]
fn every_catalog_entry_edits_and_meets_its_constraints() {
    for entry in builtin_catalog() {
        let mesh = SurfaceMesh::from(icosphere(3));
        let faces = mesh.face_count();
        let complex = entry.build(&mesh).unwrap();
        let editor = Editor::start(EditorSetup {
            mesh,
            basis: icosphere_basis_for(entry.id()),
            constraints: None,
            basis_size: None,
            complex,
        })
        .unwrap_or_else(|e| panic!("{}: {e}", entry.id()));
        for constraint in [
            r#"{"id": "v", "kind": "vector", "face": 7, "barycentric": [0.2, 0.3, 0.5], "value": [1.0, 0.5, 0.0]}"#,
            r#"{"id": "s", "kind": "divergence", "face": 300, "value": 2.0}"#,
            r#"{"id": "c", "kind": "curl", "face": 900, "barycentric": [0.6, 0.2, 0.2], "value": -1.5}"#,
        ] {
            let op = format!(r#"{{"op": "add", "constraint": {constraint}}}"#);
            let frame = editor
                .edit(EditOp::parse(op.as_bytes()).unwrap())
                .unwrap_or_else(|e| panic!("{}: {constraint}: {e}", entry.id()));
            let frame = decode_field_frame(&frame).unwrap();
            assert_eq!(
                frame.coefficients.len(),
                2 * faces,
                "{}: face-frame.coefficients",
                entry.id()
            );
            assert!(
                frame.coefficients.iter().all(|x| x.is_finite()),
                "{}",
                entry.id()
            );
            assert!(
                frame.coefficients.iter().any(|x| x.abs() > 1e-3),
                "{}: the field is not zero",
                entry.id()
            );
        }
        let check = editor.check().unwrap();
        assert_eq!(check.constraints.len(), 3, "{}", entry.id());
        assert!(
            check.max_relative < 1e-9,
            "{}: residual {}",
            entry.id(),
            check.max_relative
        );
    }
}

#[test]
fn meshes_with_boundary_edit_with_both_boundary_conditions() {
    use tvf_core::discretization::BoundaryCondition;
    use tvf_core::generate::perforated_plate;
    use tvf_design::ReducedBasis;
    use tvf_spectral::{compute_basis, BasisRequest};
    // A plate with two holes (three boundary loops), Delaunay-flipped for DEC (whose `normal`
    // is the complex of relative forms); the id names the boundary condition, as basis files on
    // meshes with boundary store it.
    let plate = perforated_plate(2, 8);
    for (id, mesh, boundary) in BoundaryCondition::ALL.into_iter().flat_map(|boundary| {
        [
            (
                "conforming-barycentric",
                SurfaceMesh::from(plate.clone()),
                boundary,
            ),
            (
                "dec-circumcentric",
                SurfaceMesh::from(tvf_conformance::corpus::delaunay_flips(&plate)),
                boundary,
            ),
        ]
    }) {
        let entry = tvf_discretizations::catalog_entry(id).unwrap();
        let complex = entry.build_with(&mesh, boundary).unwrap();
        let spectral = compute_basis(complex.as_ref(), &BasisRequest::fields(60)).unwrap();
        let editor = Editor::start(EditorSetup {
            mesh: mesh.clone(),
            basis: ReducedBasis::from_spectral(&spectral).unwrap(),
            constraints: None,
            basis_size: None,
            complex,
        })
        .unwrap_or_else(|e| panic!("{id} {boundary:?}: {e}"));
        for constraint in [
            r#"{"id": "v", "kind": "vector", "face": 7, "value": [1.0, 0.5, 0.0]}"#,
            r#"{"id": "s", "kind": "divergence", "face": 100, "value": 2.0}"#,
        ] {
            let op = format!(r#"{{"op": "add", "constraint": {constraint}}}"#);
            editor
                .edit(EditOp::parse(op.as_bytes()).unwrap())
                .unwrap_or_else(|e| panic!("{id} {boundary:?}: {constraint}: {e}"));
        }
        let check = editor.check().unwrap();
        assert!(
            check.max_relative < 1e-9,
            "{id} {boundary:?}: residual {}",
            check.max_relative
        );
    }
}
