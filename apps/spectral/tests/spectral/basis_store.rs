//! The basis store: computes once, reads back the identical basis, replaces damaged files,
//! recomputes when the matrices of a complex change (never reusing the old basis), and opens a
//! basis file with the complex it was computed for.

use crate::common::{changed_diagonal, coupled_field_mass, downgrade, WithFieldMass};
use std::path::PathBuf;
use tvf_core::discretization::{BoundaryCondition, HodgeComplex};
use tvf_core::generate::{open_cylinder, torus};
use tvf_discretizations::{
    build_complex, builtin_catalog, complex_id, BoxedComplex, Catalog, CatalogEntry, Conforming,
    CrouzeixRaviart, FaceFields, FiniteElementComplex, LagrangeP1, MassLumping, PaperSpace,
};
use tvf_spectral::{
    open_basis_file, BasisFileUseError, BasisSize, BasisStore, SpectralBasis, StoredBasisOrigin,
};

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
    let ending = format!(
        "-nonconforming-voronoi-{:016x}-d12.tvfb",
        complex.matrix_hash().value()
    );
    assert!(name.ends_with(&ending), "{name}");

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

    let (opened_complex, opened) =
        open_basis_file(builtin_catalog(), &file, &mesh, None, None).unwrap();
    assert_eq!(opened_complex.id(), "conforming-barycentric+normal");
    assert_eq!(opened.eigenvalues(), basis.eigenvalues());

    let other = open_basis_file(
        builtin_catalog(),
        &file,
        &mesh,
        Some("dec-circumcentric"),
        None,
    );
    assert!(matches!(
        other,
        Err(BasisFileUseError::OtherDiscretization { .. })
    ));
    let other = open_basis_file(
        builtin_catalog(),
        &file,
        &mesh,
        None,
        Some(BoundaryCondition::Tangential),
    );
    let message = other.err().unwrap().to_string();
    assert!(
        message.contains("'normal'")
            && message.contains("'tangential'")
            && message.contains(".tvfb"),
        "{message}"
    );
}

/// An entry of a catalog of one's own: the conforming complex with Voronoi masses under the id
/// `own-voronoi`.
fn own_entry() -> CatalogEntry {
    CatalogEntry::new(
        "own-voronoi",
        "the conforming complex with Voronoi masses, under another id",
        |mesh, boundary| -> Result<BoxedComplex, _> {
            let lumping = MassLumping::Voronoi;
            Ok(Box::new(FiniteElementComplex::from_spaces_with_boundary(
                complex_id("own-voronoi", mesh.topology(), boundary),
                mesh,
                LagrangeP1::new(mesh, lumping)?,
                CrouzeixRaviart::new(mesh, lumping)?,
                FaceFields::new(mesh)?,
                boundary,
            )?))
        },
    )
    .with_boundary_condition(BoundaryCondition::Tangential, "co-potentials zero")
}

#[test]
fn a_basis_file_of_an_own_entry_reopens_through_its_catalog_only() {
    let folder = tempfile::tempdir().unwrap();
    let store = BasisStore::new(folder.path().to_path_buf());
    let mesh = open_cylinder(12, 4, 1.0);
    let catalog = Catalog::builtin().with(own_entry()).unwrap();
    let complex = catalog.build_complex("own-voronoi", None, &mesh).unwrap();
    assert_eq!(complex.id(), "own-voronoi+tangential");
    let (basis, _) = store
        .basis(&mesh, complex.as_ref(), BasisSize::Pairs(3), None)
        .unwrap();
    let file = store.file(&mesh, complex.as_ref(), BasisSize::Pairs(3));

    let (opened_complex, opened) = open_basis_file(&catalog, &file, &mesh, None, None).unwrap();
    assert_eq!(opened_complex.id(), "own-voronoi+tangential");
    assert_eq!(opened.eigenvalues(), basis.eigenvalues());

    let message = open_basis_file(builtin_catalog(), &file, &mesh, None, None)
        .err()
        .unwrap()
        .to_string();
    assert!(
        message.contains("unknown discretization 'own-voronoi'") && message.contains(".tvfb"),
        "{message}"
    );
}

/// The basis of 8 fields for `complex` from `store`: the basis, the file it was read from
/// (`None` if it was computed, which saves it under its name) and why a file under that name
/// could not be used, if there was one.
fn basis_of<H: HodgeComplex>(
    store: &BasisStore,
    mesh: &tvf_core::TriangleMesh,
    complex: &H,
) -> (SpectralBasis, Option<PathBuf>, Option<String>) {
    let (basis, origin) = store
        .basis(mesh, complex, BasisSize::Fields(8), None)
        .unwrap();
    match origin {
        StoredBasisOrigin::Read { file, .. } => (basis, Some(file), None),
        StoredBasisOrigin::Computed {
            unusable_file,
            saved,
        } => {
            assert_eq!(
                saved.unwrap(),
                store.file(mesh, complex, BasisSize::Fields(8))
            );
            (basis, None, unusable_file)
        }
    }
}

#[test]
fn a_changed_assembly_is_recomputed_never_reused() {
    let folder = tempfile::tempdir().unwrap();
    let store = BasisStore::new(folder.path());
    let mesh = torus(1.0, 0.4, 12, 6).unwrap();
    let lumped = || Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let original = lumped();
    let one_entry = {
        let inner = lumped();
        let m1 = changed_diagonal(inner.m1(), 3, 1.0 + 1e-12);
        WithFieldMass::new(inner, m1)
    };
    let sparse = {
        let inner = lumped();
        let m1 = coupled_field_mass(inner.m1(), 0.3);
        WithFieldMass::new(inner, m1)
    };
    // Same id and mesh, three names that differ in the matrix hash only.
    let size = BasisSize::Fields(8);
    let names: Vec<String> = [
        store.file(&mesh, &original, size),
        store.file(&mesh, &one_entry, size),
        store.file(&mesh, &sparse, size),
    ]
    .iter()
    .map(|f| f.file_name().unwrap().to_string_lossy().into_owned())
    .collect();
    assert_eq!(names[0].len(), names[1].len());
    assert!(names[0] != names[1] && names[1] != names[2] && names[0] != names[2]);

    let (first, read, _) = basis_of(&store, &mesh, &original);
    assert_eq!(read, None);
    // The changed assemblies are computed, not read from the original's file.
    let (changed, read, unusable) = basis_of(&store, &mesh, &one_entry);
    assert_eq!((read, unusable), (None, None));
    assert_eq!(changed.field_mass().storage(), one_entry.m1().storage());
    let (sparse_basis, read, _) = basis_of(&store, &mesh, &sparse);
    assert_eq!(read, None);
    // Each is read back from its own file, identical.
    for (complex_basis, again) in [
        (&first, basis_of(&store, &mesh, &original)),
        (&changed, basis_of(&store, &mesh, &one_entry)),
        (&sparse_basis, basis_of(&store, &mesh, &sparse)),
    ] {
        assert!(again.1.is_some(), "read from the store");
        assert_eq!(again.0.fields(), complex_basis.fields());
        assert_eq!(again.0.eigenvalues(), complex_basis.eigenvalues());
        assert_eq!(
            again.0.field_mass().storage(),
            complex_basis.field_mass().storage()
        );
    }

    // A file of other matrices under this name is not used: recomputed, the reason given.
    let original_file = store.file(&mesh, &original, size);
    let one_entry_file = store.file(&mesh, &one_entry, size);
    std::fs::copy(&original_file, &one_entry_file).unwrap();
    let (_, read, unusable) = basis_of(&store, &mesh, &one_entry);
    assert_eq!(read, None);
    let problem = unusable.unwrap();
    assert!(
        problem.contains("other matrices") && problem.contains("M1"),
        "{problem}"
    );

    // Nor is a file without a matrix hash (format version 2) under the current name.
    let bytes = std::fs::read(&original_file).unwrap();
    std::fs::write(&original_file, downgrade(&bytes, 2)).unwrap();
    let (again, read, unusable) = basis_of(&store, &mesh, &original);
    assert_eq!(read, None);
    let problem = unusable.unwrap();
    assert!(problem.contains("predates matrix hashes"), "{problem}");
    assert_eq!(again.fields(), first.fields());
    assert_eq!(std::fs::read(&original_file).unwrap(), bytes);
}
