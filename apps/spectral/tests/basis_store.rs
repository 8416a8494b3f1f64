//! The basis store: computes once, reads back the identical basis, replaces damaged files, and
//! opens a basis file with the complex it was computed for.

use tvf_core::discretization::BoundaryCondition;
use tvf_core::generate::{open_cylinder, torus};
use tvf_discretizations::build_complex;
use tvf_spectral::{open_basis_file, BasisFileUseError, BasisSize, BasisStore, StoredBasisOrigin};

#[test]
fn a_stored_basis_is_computed_once_read_back_identical_and_replaced_when_damaged() {
    let folder = tempfile::tempdir().unwrap();
    let store = BasisStore::new(folder.path().join("cache"));
    let mesh = torus(1.0, 0.4, 12, 6).unwrap();
    let complex = build_complex("nonconforming-voronoi", None, &mesh).unwrap();
    let size = BasisSize::Fields(12);

    let (computed, origin) = store.basis(&mesh, complex.as_ref(), size, None).unwrap();
    let file = match origin {
        StoredBasisOrigin::Computed {
            unusable_file: None,
            saved: Ok(file),
        } => file,
        other => panic!("expected a fresh computation saved to the store, got {other:?}"),
    };
    assert_eq!(file, store.file(&mesh, complex.as_ref(), size));
    let name = file.file_name().unwrap().to_string_lossy().into_owned();
    assert!(name.ends_with("-nonconforming-voronoi-d12.tvfb"), "{name}");

    let (read, origin) = store.basis(&mesh, complex.as_ref(), size, None).unwrap();
    assert!(
        matches!(origin, StoredBasisOrigin::Read { .. }),
        "{origin:?}"
    );
    assert_eq!(read.eigenvalues(), computed.eigenvalues());
    assert_eq!(read.families(), computed.families());
    assert_eq!(read.fields(), computed.fields());

    // A truncated file is not used: recomputed, the problem named, the file replaced.
    let bytes = std::fs::read(&file).unwrap();
    std::fs::write(&file, &bytes[..bytes.len() / 2]).unwrap();
    let (again, origin) = store.basis(&mesh, complex.as_ref(), size, None).unwrap();
    match origin {
        StoredBasisOrigin::Computed {
            unusable_file: Some(problem),
            saved: Ok(_),
        } => assert!(problem.contains(&name), "{problem}"),
        other => panic!("expected a recomputation, got {other:?}"),
    }
    assert_eq!(again.eigenvalues(), computed.eigenvalues());
    assert_eq!(std::fs::read(&file).unwrap(), bytes);

    // A file of another size under this name is not used either.
    let other_size = store.file(&mesh, complex.as_ref(), BasisSize::Fields(10));
    store
        .basis(&mesh, complex.as_ref(), BasisSize::Fields(10), None)
        .unwrap();
    std::fs::copy(&other_size, &file).unwrap();
    let (_, origin) = store.basis(&mesh, complex.as_ref(), size, None).unwrap();
    match origin {
        StoredBasisOrigin::Computed {
            unusable_file: Some(problem),
            ..
        } => assert!(problem.contains("10 fields, not 12"), "{problem}"),
        other => panic!("expected a recomputation, got {other:?}"),
    }
}

#[test]
fn a_basis_file_opens_with_its_own_complex_and_refuses_another() {
    let folder = tempfile::tempdir().unwrap();
    let store = BasisStore::new(folder.path());
    let mesh = open_cylinder(16, 6, 1.0);
    let complex = build_complex(
        "conforming-barycentric",
        Some(BoundaryCondition::Normal),
        &mesh,
    )
    .unwrap();
    assert_eq!(complex.id(), "conforming-barycentric+normal");
    let (basis, _) = store
        .basis(&mesh, complex.as_ref(), BasisSize::Pairs(4), None)
        .unwrap();
    let file = store.file(&mesh, complex.as_ref(), BasisSize::Pairs(4));

    let (opened_complex, opened) = open_basis_file(&file, &mesh, None, None).unwrap();
    assert_eq!(opened_complex.id(), "conforming-barycentric+normal");
    assert_eq!(opened.eigenvalues(), basis.eigenvalues());

    let other = open_basis_file(&file, &mesh, Some("dec-circumcentric"), None);
    assert!(matches!(
        other,
        Err(BasisFileUseError::OtherDiscretization { .. })
    ));
    let other = open_basis_file(&file, &mesh, None, Some(BoundaryCondition::Tangential));
    let message = other.err().unwrap().to_string();
    assert!(
        message.contains("'normal'")
            && message.contains("'tangential'")
            && message.contains(".tvfb"),
        "{message}"
    );
}
