//! Bases computed straight into their files ([`save_computed_basis`]): the file is the one the
//! in-memory computation saves, byte for byte (closed and open meshes, several spectrum-slicing
//! intervals per family); an interrupted computation leaves no file; a damaged file is refused
//! with an error naming it.

use std::path::Path;
use tvf_core::discretization::{BoundaryCondition, HodgeComplex};
use tvf_core::generate::{hemisphere, icosphere};
use tvf_discretizations::{Conforming, MassLumping};
use tvf_spectral::{
    compute_eigenfunction_basis, load_basis, save_computed_basis, save_eigenfunction_basis,
    BasisFileError, BasisFileKey, BasisFileLayout, BasisReport, BasisRequest, BasisSize,
};

/// Saves the basis of `request` both ways into `folder` and checks the files are equal, the
/// streamed one written as eigenfunctions, and whether it was `streamed`; returns the report.
fn streamed_equals_in_memory(
    mesh: &tvf_core::TriangleMesh,
    complex: &dyn HodgeComplex,
    request: &BasisRequest<'_>,
    folder: &Path,
    streamed: bool,
) -> BasisReport {
    let key = BasisFileKey::new(mesh, complex);
    let (in_memory, path) = (folder.join("in-memory.tvfb"), folder.join("streamed.tvfb"));
    let (basis, report) = compute_eigenfunction_basis(complex, request).unwrap();
    save_eigenfunction_basis(&in_memory, &basis, complex, &key).unwrap();
    let saved = save_computed_basis(&path, complex, request, &key).unwrap();
    assert_eq!(saved.streamed, streamed);
    let header = tvf_spectral::read_basis_header(&path).unwrap();
    assert!(matches!(
        header.layout,
        BasisFileLayout::Eigenfunctions { .. }
    ));
    let (expected, found) = (
        std::fs::read(&in_memory).unwrap(),
        std::fs::read(&path).unwrap(),
    );
    assert_eq!(expected.len(), found.len());
    assert!(expected == found, "the streamed file differs");
    assert_eq!(saved.eigenvalues, basis.eigenvalues());
    assert_eq!(saved.families, basis.families());
    assert_eq!(saved.report.max_field_residual, report.max_field_residual);
    assert_eq!(saved.report.solves, report.solves);
    // Only the two files: no staging folder left behind.
    assert_eq!(std::fs::read_dir(folder).unwrap().count(), 2);
    report
}

/// Five intervals or so per family (the eigensolver's default interval of 96 pairs), both
/// families solved by spectrum slicing, on a closed mesh and on an open one whose Dirichlet
/// nodes are left out of one family's eigenproblem (the columns are taken to the full node
/// numbering as they come).
#[test]
fn a_basis_streamed_to_its_file_is_the_in_memory_one_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(4);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let request = BasisRequest::fields(900).with_seed(5);
    let report = streamed_equals_in_memory(&mesh, &complex, &request, dir.path(), true);
    // The sphere's multiplets straddle the split: pairs computed above the basis were written
    // and then cut out of the file (483 + 419 computed, 483 + 417 kept).
    assert!(
        report.integrable_computed + report.cointegrable_computed
            > report.integrable_count + report.cointegrable_count,
        "{report:?}"
    );

    let dir = tempfile::tempdir().unwrap();
    let mesh = hemisphere(30);
    let complex = Conforming::with_boundary(
        &mesh,
        MassLumping::Barycentric,
        BoundaryCondition::Tangential,
    )
    .unwrap();
    streamed_equals_in_memory(&mesh, &complex, &BasisRequest::pairs(250), dir.path(), true);
}

/// A basis cut by an eigenvalue bound has counts known only at the end: computed in memory,
/// and the file is still the usual one.
#[test]
fn a_basis_cut_by_a_bound_is_saved_as_before() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(3);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let request = BasisRequest::new(BasisSize::MaxEigenvalue(60.0));
    streamed_equals_in_memory(&mesh, &complex, &request, dir.path(), false);
}

/// A computation stopped by its progress callback (as Ctrl+C stops it) after the first columns
/// were written leaves neither the file nor a temporary in the folder; the old file stays.
#[test]
fn an_interrupted_streamed_basis_leaves_no_file() {
    struct Stop;
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(4);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let key = BasisFileKey::new(&mesh, &complex);
    let path = dir.path().join("basis.tvfb");
    let stop_after_half = |progress: &tvf_spectral::BasisProgress| {
        if progress.done > 400 {
            std::panic::resume_unwind(Box::new(Stop));
        }
    };
    let request = BasisRequest::fields(900).with_progress(&stop_after_half);
    let run = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        save_computed_basis(&path, &complex, &request, &key)
    }));
    assert!(run.is_err_and(|payload| payload.is::<Stop>()));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);

    std::fs::write(&path, b"the old file").unwrap();
    let run = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        save_computed_basis(&path, &complex, &request, &key)
    }));
    assert!(run.is_err());
    assert_eq!(std::fs::read(&path).unwrap(), b"the old file");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

/// A streamed file cut short, or with one byte of an eigenfunction changed, is refused with an
/// error that names it.
#[test]
fn a_damaged_streamed_file_is_refused_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(3);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let key = BasisFileKey::new(&mesh, &complex);
    let path = dir.path().join("basis.tvfb");
    save_computed_basis(&path, &complex, &BasisRequest::fields(300), &key).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    load_basis(&path, &key, &complex).unwrap();

    std::fs::write(&path, &bytes[..bytes.len() / 2]).unwrap();
    let error = load_basis(&path, &key, &complex).unwrap_err();
    assert!(matches!(error, BasisFileError::Truncated { .. }), "{error}");
    assert!(error.to_string().contains("basis.tvfb"), "{error}");

    let mut flipped = bytes.clone();
    let middle = flipped.len() / 2;
    flipped[middle] ^= 0x10;
    std::fs::write(&path, &flipped).unwrap();
    let error = load_basis(&path, &key, &complex).unwrap_err();
    assert!(
        matches!(
            error,
            BasisFileError::Checksum {
                part: "payload",
                ..
            }
        ),
        "{error}"
    );
    assert!(error.to_string().contains("basis.tvfb"), "{error}");
}
