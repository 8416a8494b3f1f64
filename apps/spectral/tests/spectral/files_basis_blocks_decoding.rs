//! Decoding and rate–distortion curves with a basis file read in blocks: several syntheses in
//! one pass over the file ([`FieldBasis::reconstruct_many`]) equal one synthesis each, bit for
//! bit (and do not depend on the block size where `M1` is diagonal); a sequence decoded in
//! groups equals frame-by-frame decoding bit for bit and the loaded basis's decoding bit for bit
//! where `M1` is diagonal (the same fields added in the same order; else to `1e-13`: mass solves
//! of other blocks of columns); a rate–distortion curve in blocks has the loaded basis's file
//! sizes and its errors to `1e-12` relative (the projection `Uᵀ M1 v` sums in another order).

use super::common::relative_difference;
use std::path::Path;
use tvf_core::discretization::HodgeOperators;
use tvf_core::generate::icosphere;
use tvf_discretizations::{BoxedComplex, Conforming, MassLumping, WhitneyGalerkin};
use tvf_spectral::{
    compress_with_report, decompress_with_progress, field_basis_id, load_basis, rate_distortion,
    save_computed_basis, BasisFileBlocks, BasisFileKey, BasisRequest, CoefficientCoding,
    FieldBasis, FieldCodec, FileStamp,
};

/// Frame `t` of a smooth time-dependent field (`n1` values).
fn frame(n1: usize, t: usize) -> Vec<f64> {
    (0..n1)
        .map(|i| (0.37 * i as f64 + 0.1 * t as f64).sin() + 0.2 * (1.9 * i as f64).cos())
        .collect()
}

/// The checks of the module documentation for the basis of `complex` saved to `path`.
fn decoding_in_blocks_equals_whole(
    mesh: &tvf_core::TriangleMesh,
    complex: BoxedComplex,
    path: &Path,
) {
    let key = BasisFileKey::new(mesh, complex.as_ref());
    save_computed_basis(path, complex.as_ref(), &BasisRequest::fields(120), &key).unwrap();
    let whole = load_basis(path, &key, complex.as_ref()).unwrap();
    let diagonal = whole.field_mass().diagonal_values().is_some();
    let n1 = complex.field_dimension();
    let blocks = BasisFileBlocks::open(path, &key, complex).unwrap().unwrap();
    let id = field_basis_id(&blocks).unwrap();

    // 20 frames: two decoding groups.
    let frames: Vec<Vec<f64>> = (0..20).map(|t| frame(n1, t)).collect();
    let coding = CoefficientCoding::Quantized { bits: 12 };
    let codec = FieldCodec::new(&blocks, 7, id, 25, coding).unwrap();
    let (file, _) = compress_with_report(&codec, blocks.field_mass(), &frames, 642).unwrap();
    let grouped = decompress_with_progress(&codec, &file, &|_| {}).unwrap();
    assert_eq!(grouped.len(), frames.len());
    for (payload, decoded) in file.frames.iter().zip(&grouped) {
        assert_eq!(&codec.decode(payload).unwrap(), decoded, "grouped decoding");
    }
    let whole_codec = FieldCodec::new(&whole, 7, id, 25, coding).unwrap();
    let expected = decompress_with_progress(&whole_codec, &file, &|_| {}).unwrap();
    for (found, expected) in grouped.iter().zip(&expected) {
        if diagonal {
            assert_eq!(found, expected, "blocks against whole, diagonal M1");
        } else {
            assert!(relative_difference(found, expected) < 1e-13);
        }
    }
    // Several syntheses in one pass with blocks of 3 columns: each the single synthesis.
    let sets: Vec<Vec<f64>> = file
        .frames
        .iter()
        .take(3)
        .map(|payload| codec.decode_coefficients(payload).unwrap())
        .collect();
    let small = blocks.with_block_bytes(3 * 8 * 642);
    let views: Vec<&[f64]> = sets.iter().map(Vec::as_slice).collect();
    let many = small.reconstruct_many(&views).unwrap();
    for ((set, found), expected) in sets.iter().zip(&many).zip(&grouped) {
        assert_eq!(
            &small.reconstruct(set).unwrap(),
            found,
            "one pass, many sets"
        );
        if diagonal {
            assert_eq!(found, expected, "independent of the block size");
        } else {
            assert!(relative_difference(found, expected) < 1e-13);
        }
    }
    rate_distortion_equals_whole(&whole, &small, &frames[0], id);
}

/// The curve of `field` through `blocks` against the loaded basis's: the same points and file
/// sizes, errors to `1e-12` relative.
fn rate_distortion_equals_whole(
    whole: &dyn FieldBasis,
    blocks: &dyn FieldBasis,
    field: &[f64],
    id: u64,
) {
    let stamp = FileStamp {
        mesh_fingerprint: 7,
        basis_id: id,
        vertex_count: 642,
    };
    let codings = [
        CoefficientCoding::Float64,
        CoefficientCoding::Quantized { bits: 8 },
        CoefficientCoding::Quantized { bits: 16 },
    ];
    let pairs = [5, 20, 50];
    let expected = rate_distortion(whole, field, stamp, &pairs, &codings).unwrap();
    let found = rate_distortion(blocks, field, stamp, &pairs, &codings).unwrap();
    assert_eq!(found.len(), 9);
    for (found, expected) in found.iter().zip(&expected) {
        assert_eq!(
            (found.coding, found.pairs, found.bytes),
            (expected.coding, expected.pairs, expected.bytes)
        );
        let error = (found.relative_error - expected.relative_error).abs();
        assert!(
            error <= 1e-12 * expected.relative_error,
            "{found:?} {expected:?}"
        );
    }
    // More pairs, smaller error (the curve is real, not constant).
    assert!(found[2].relative_error < found[0].relative_error);
}

/// A lumped complex (diagonal `M1`) and the Galerkin masses (sparse `M1`).
#[test]
fn decoding_and_rate_distortion_in_blocks_equal_the_basis_loaded_whole() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(3);
    let lumped = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    decoding_in_blocks_equals_whole(&mesh, Box::new(lumped), &dir.path().join("lumped.tvfb"));
    let galerkin = WhitneyGalerkin::new(&mesh).unwrap();
    let path = dir.path().join("galerkin.tvfb");
    decoding_in_blocks_equals_whole(&mesh, Box::new(galerkin), &path);
}
