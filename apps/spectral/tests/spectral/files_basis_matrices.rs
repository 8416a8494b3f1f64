//! Basis files are tied to the matrices of their complex: a file of the same id and mesh whose
//! matrices differ (a changed assembly) is refused naming the parts that differ, in both
//! layouts; a basis is never saved under the key of another complex; files of format versions 1
//! and 2, which carry no matrix hash, are accepted on id and mesh alone.

use crate::common;
use crate::common::{
    changed_diagonal, coupled_field_mass, downgrade, WithFieldMass, MATRIX_HASH_AT,
};
use tvf_core::discretization::{HodgeComplex, MatrixHash};
use tvf_core::generate::icosphere;
use tvf_discretizations::{build_complex, Conforming, MassLumping};
use tvf_spectral::{
    compute_basis, compute_eigenfunction_basis, load_basis, read_basis_header, save_basis,
    save_eigenfunction_basis, BasisFileError, BasisFileKey, BasisRequest,
};

fn conforming(mesh: &tvf_core::TriangleMesh) -> Conforming {
    Conforming::new(mesh, MassLumping::Barycentric).unwrap()
}

#[test]
fn the_matrix_hash_is_the_same_for_the_same_assembly_only() {
    let mesh = icosphere(1);
    let catalog = build_complex("conforming-barycentric", None, &mesh).unwrap();
    assert_eq!(conforming(&mesh).matrix_hash(), catalog.matrix_hash());
    let inner = conforming(&mesh);
    let m1 = changed_diagonal(inner.m1(), 7, 1.0 + 1e-12);
    let changed = WithFieldMass::new(inner, m1);
    assert_eq!(changed.id(), catalog.id());
    assert_eq!(
        catalog
            .matrix_hash()
            .differing_parts(&changed.matrix_hash()),
        vec!["M1"]
    );
    let dec = build_complex("dec-circumcentric", None, &mesh).unwrap();
    assert_eq!(
        catalog.matrix_hash().differing_parts(&dec.matrix_hash()),
        MatrixHash::PART_NAMES.to_vec()
    );
}

#[test]
fn a_file_of_other_matrices_is_refused_naming_the_difference() {
    let mesh = icosphere(1);
    let complex = conforming(&mesh);
    let key = BasisFileKey::new(&mesh, &complex);
    let request = BasisRequest::pairs(10);
    let dir = tempfile::tempdir().unwrap();
    let dense = dir.path().join("dense.tvfb");
    save_basis(&dense, &compute_basis(&complex, &request).unwrap(), &key).unwrap();
    let compact = dir.path().join("compact.tvfb");
    let (eigenfunctions, _) = compute_eigenfunction_basis(&complex, &request).unwrap();
    save_eigenfunction_basis(&compact, &eigenfunctions, &complex, &key).unwrap();

    // One entry of M1 changed in the last bits, or M1 made sparse: same id, same mesh.
    let one_entry = {
        let inner = conforming(&mesh);
        let m1 = changed_diagonal(inner.m1(), 7, 1.0 + 1e-12);
        WithFieldMass::new(inner, m1)
    };
    let sparse = {
        let inner = conforming(&mesh);
        let m1 = coupled_field_mass(inner.m1(), 0.3);
        WithFieldMass::new(inner, m1)
    };
    for other in [&one_entry, &sparse] {
        let other_key = BasisFileKey::new(&mesh, other);
        assert_eq!(other_key.discretization, key.discretization);
        for path in [&dense, &compact] {
            let error = load_basis(path, &other_key, other).unwrap_err();
            let message = error.to_string();
            assert!(
                matches!(
                    &error,
                    BasisFileError::WrongMatrices { differing, .. } if differing == &["M1"]
                ),
                "{message}"
            );
            for part in [
                path.display().to_string(),
                "other matrices".into(),
                "M1 differs".into(),
                format!("{:016x}", other.matrix_hash().value()),
            ] {
                assert!(message.contains(&part), "{message} lacks {part}");
            }
        }
    }

    // A file whose header names other matrices (here: another d1) is refused for this complex.
    let mut bytes = std::fs::read(&dense).unwrap();
    let d1_at = MATRIX_HASH_AT + 8;
    bytes[d1_at] ^= 1;
    common::reseal_header(&mut bytes);
    let edited = dir.path().join("edited.tvfb");
    std::fs::write(&edited, &bytes).unwrap();
    let error = load_basis(&edited, &key, &complex).unwrap_err();
    assert!(error.to_string().contains("d1 differs"), "{error}");
}

#[test]
fn a_basis_is_never_saved_under_the_key_of_other_matrices() {
    let mesh = icosphere(1);
    let complex = conforming(&mesh);
    let request = BasisRequest::pairs(6);
    let basis = compute_basis(&complex, &request).unwrap();
    let (eigenfunctions, _) = compute_eigenfunction_basis(&complex, &request).unwrap();
    let inner = conforming(&mesh);
    let m1 = changed_diagonal(inner.m1(), 0, 2.0);
    let other = WithFieldMass::new(inner, m1);
    let other_key = BasisFileKey::new(&mesh, &other);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("basis.tvfb");
    let refused = [
        save_basis(&path, &basis, &other_key).unwrap_err(),
        save_eigenfunction_basis(&path, &eigenfunctions, &complex, &other_key).unwrap_err(),
        save_basis(
            &path,
            &basis,
            &BasisFileKey {
                matrix_hash: None,
                ..BasisFileKey::new(&mesh, &complex)
            },
        )
        .unwrap_err(),
    ];
    for error in refused {
        assert!(matches!(error, BasisFileError::Invalid { .. }), "{error}");
        assert!(error.to_string().contains("matrix hash") || error.to_string().contains("M1"));
    }
    assert!(!path.exists());
}

/// Files written before matrix hashes (format versions 1 and 2) cannot be checked against the
/// matrices: they load for any complex of their id and mesh, and their header says they carry
/// no hash.
#[test]
fn files_before_matrix_hashes_load_on_id_and_mesh_alone() {
    let mesh = icosphere(1);
    let complex = conforming(&mesh);
    let key = BasisFileKey::new(&mesh, &complex);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("basis.tvfb");
    save_basis(
        &path,
        &compute_basis(&complex, &BasisRequest::pairs(6)).unwrap(),
        &key,
    )
    .unwrap();
    let inner = conforming(&mesh);
    let m1 = changed_diagonal(inner.m1(), 7, 1.0 + 1e-12);
    let other = WithFieldMass::new(inner, m1);
    let current = std::fs::read(&path).unwrap();
    for version in [1, 2] {
        std::fs::write(&path, downgrade(&current, version)).unwrap();
        assert_eq!(read_basis_header(&path).unwrap().key.matrix_hash, None);
        assert!(load_basis(&path, &BasisFileKey::new(&mesh, &other), &other).is_ok());
    }
}
