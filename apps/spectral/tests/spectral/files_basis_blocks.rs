//! Basis files used in blocks ([`BasisFileBlocks`]): projections, syntheses and filters equal
//! those of the basis loaded whole (to round-off: another summation order, bounded here), and
//! do not depend on the block size (bit for bit); a damaged file is refused before use, naming
//! it; a file in the fields layout is left to the whole load.

use super::common::reseal_payload;
use std::path::Path;
use tvf_core::discretization::HodgeOperators;
use tvf_core::generate::icosphere;
use tvf_discretizations::{BoxedComplex, Conforming, MassLumping, WhitneyGalerkin};
use tvf_spectral::{
    compute_eigenfunction_basis, load_basis, save_basis, save_computed_basis, BasisFileBlocks,
    BasisFileError, BasisFileKey, BasisRequest, FieldBasis, FourierAnalysis, FrequencyResponse,
    SpectralFilter,
};

/// A smooth field with a part outside any truncated basis (`n1` values).
fn test_field(n1: usize) -> Vec<f64> {
    (0..n1)
        .map(|i| (0.37 * i as f64).sin() + 0.2 * (1.9 * i as f64).cos())
        .collect()
}

/// Largest difference of `a` and `b` relative to the largest magnitude of `b`.
fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let worst = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    worst / scale
}

/// Saves the basis of `request` for `complex` to `path` (streamed where it can be) and checks
/// that its blocks give the whole basis's coefficients, syntheses and filtered field to
/// `1e-13` relative, and the same results bit for bit with blocks of a few columns.
fn blocks_equal_whole(mesh: &tvf_core::TriangleMesh, complex: BoxedComplex, path: &Path) {
    let key = BasisFileKey::new(mesh, complex.as_ref());
    save_computed_basis(path, complex.as_ref(), &BasisRequest::fields(120), &key).unwrap();
    let whole = load_basis(path, &key, complex.as_ref()).unwrap();
    let n1 = complex.field_dimension();
    let blocks = BasisFileBlocks::open(path, &key, complex).unwrap().unwrap();
    assert_eq!(FieldBasis::eigenvalues(&blocks), whole.eigenvalues());
    assert_eq!(FieldBasis::families(&blocks), whole.families());
    let field = test_field(n1);

    let (expected, found) = (
        whole.coefficients(&field).unwrap(),
        blocks.coefficients(&field).unwrap(),
    );
    assert!(relative_difference(&found, &expected) < 1e-13);
    let (expected, found) = (
        whole.reconstruct(&expected).unwrap(),
        blocks.reconstruct(&expected).unwrap(),
    );
    assert!(relative_difference(&found, &expected) < 1e-13);

    let filter = SpectralFilter::both(FrequencyResponse::LowPass { t: 0.01 }, 0.0);
    let (expected, found) = (
        filter.apply(&whole, &field).unwrap(),
        filter.apply(&blocks, &field).unwrap(),
    );
    assert!(relative_difference(&found.field, &expected.field) < 1e-13);
    assert!((found.rest_norm - expected.rest_norm).abs() <= 1e-12 * expected.rest_norm);
    let analysis = FourierAnalysis::new(&blocks, &field).unwrap();
    assert!(
        relative_difference(
            &analysis.rest,
            &FourierAnalysis::new(&whole, &field).unwrap().rest
        ) < 1e-12
    );

    // A block of 3 columns or fewer: many blocks per family, the same arithmetic per column.
    let small = blocks.with_block_bytes(3 * 8 * 642);
    let coefficients = small.coefficients(&field).unwrap();
    assert_eq!(coefficients, found.coefficients);
    let small_field = filter.apply(&small, &field).unwrap();
    assert_eq!(small_field.field, found.field);
}

/// A lumped complex (diagonal `M1`, the basis streamed to its file) and the Galerkin masses
/// (sparse `M1`, co-integrable fields through mass solves).
#[test]
fn blocks_of_a_basis_file_equal_the_basis_loaded_whole() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(3);
    let lumped = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    blocks_equal_whole(&mesh, Box::new(lumped), &dir.path().join("lumped.tvfb"));
    let galerkin = WhitneyGalerkin::new(&mesh).unwrap();
    blocks_equal_whole(&mesh, Box::new(galerkin), &dir.path().join("galerkin.tvfb"));
}

/// Cut short, one payload bit flipped, or a value made non-finite behind a valid checksum: each
/// refused when opened, with an error naming the file; changed after it was opened, refused by
/// the next product. A fields-layout file is not opened in
/// blocks (`None`).
#[test]
fn damaged_files_are_refused_before_blocks_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(3);
    let complex =
        || -> BoxedComplex { Box::new(Conforming::new(&mesh, MassLumping::Barycentric).unwrap()) };
    let key = BasisFileKey::new(&mesh, complex().as_ref());
    let path = dir.path().join("basis.tvfb");
    save_computed_basis(&path, complex().as_ref(), &BasisRequest::fields(60), &key).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let refused = |bytes: &[u8]| {
        std::fs::write(&path, bytes).unwrap();
        let error = BasisFileBlocks::open(&path, &key, complex()).err().unwrap();
        assert!(error.to_string().contains("basis.tvfb"), "{error}");
        error
    };
    let error = refused(&bytes[..bytes.len() - 100]);
    assert!(matches!(error, BasisFileError::Truncated { .. }), "{error}");
    let mut flipped = bytes.clone();
    let at = flipped.len() - 200;
    flipped[at] ^= 0x01;
    let error = refused(&flipped);
    assert!(matches!(error, BasisFileError::Checksum { .. }), "{error}");
    let mut not_finite = bytes.clone();
    // Stored values end where the checksum starts.
    let at = not_finite.len() - 8 - 8 * 20;
    not_finite[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
    reseal_payload(&mut not_finite);
    let error = refused(&not_finite);
    assert!(error.to_string().contains("not finite"), "{error}");

    // Opened, and then changed in place: the next product refuses it.
    std::fs::write(&path, &bytes).unwrap();
    let blocks = BasisFileBlocks::open(&path, &key, complex())
        .unwrap()
        .unwrap();
    let mut longer = bytes.clone();
    longer.push(0);
    std::fs::write(&path, &longer).unwrap();
    let error = blocks
        .coefficients(&vec![1.0; blocks.field_dimension()])
        .unwrap_err();
    assert!(error.to_string().contains("basis.tvfb") && error.to_string().contains("changed"));

    let fields = dir.path().join("fields.tvfb");
    let (basis, _) =
        compute_eigenfunction_basis(complex().as_ref(), &BasisRequest::fields(20)).unwrap();
    let dense = tvf_spectral::SpectralBasis::new(
        basis.eigenvalues().to_vec(),
        basis.families().to_vec(),
        basis.dense_fields(complex().as_ref()),
        complex().m1().clone(),
    )
    .unwrap();
    save_basis(&fields, &dense, &key).unwrap();
    assert!(BasisFileBlocks::open(&fields, &key, complex())
        .unwrap()
        .is_none());
}
