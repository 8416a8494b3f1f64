//! Basis files used in blocks ([`BasisFileBlocks`]): projections, syntheses, filters and
//! compression equal those of the basis loaded whole (to round-off: another summation order,
//! bounded here), and do not depend on the block size (bit for bit); the fields visited, the
//! basis id and the rows of `U` are the loaded basis's bit for bit (the co-integrable rows of a
//! non-diagonal `M1` to round-off: mass solves); a damaged file is refused before use, naming
//! it; a file in the fields layout is left to the whole load. The header, eigenvalues and
//! families of a file read without its fields (`read_basis_spectrum`).

use super::common::{header_length, relative_difference, reseal_payload};
use std::path::Path;
use std::sync::Mutex;
use tvf_core::discretization::HodgeOperators;
use tvf_core::generate::icosphere;
use tvf_discretizations::{BoxedComplex, Conforming, MassLumping, WhitneyGalerkin};
use tvf_spectral::{
    basis_id, compress_with_report, compute_eigenfunction_basis, field_basis_id, load_basis,
    read_basis_spectrum, save_basis, save_computed_basis, BasisFileBlocks, BasisFileError,
    BasisFileKey, BasisRequest, CoefficientCoding, FieldBasis, FieldCodec, FieldFamily,
    FourierAnalysis, FrequencyResponse, SpectralBasis, SpectralFilter,
};

/// A smooth field with a part outside any truncated basis (`n1` values).
fn test_field(n1: usize) -> Vec<f64> {
    (0..n1)
        .map(|i| (0.37 * i as f64).sin() + 0.2 * (1.9 * i as f64).cos())
        .collect()
}

/// Saves the basis of `request` for `complex` to `path` (streamed where it can be) and checks
/// that its blocks give the whole basis's coefficients, syntheses and filtered field to
/// `1e-13` relative — the synthesis bit for bit where `M1` is diagonal (the fields formed and
/// added as the loaded basis does) — and the same results with blocks of a few columns (bit for
/// bit where `M1` is diagonal; else to `1e-13`: the co-integrable fields through mass solves of
/// other blocks of columns).
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
    let diagonal = whole.field_mass().diagonal_values().is_some();
    let (expected, found) = (
        whole.reconstruct(&expected).unwrap(),
        blocks.reconstruct(&expected).unwrap(),
    );
    assert!(relative_difference(&found, &expected) < 1e-13);
    if diagonal {
        assert_eq!(
            found, expected,
            "the synthesis of a diagonal M1, bit for bit"
        );
    }

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

    assert!(blocks.forms_fields_as_loaded());
    compression_equals_whole(&whole, &blocks, &field);
    // A block of 3 columns or fewer: many blocks per family, the same arithmetic per column.
    let small = blocks.with_block_bytes(3 * 8 * 642);
    assert_eq!(small.forms_fields_as_loaded(), diagonal);
    let coefficients = small.coefficients(&field).unwrap();
    assert_eq!(coefficients, found.coefficients);
    let small_field = filter.apply(&small, &field).unwrap();
    if diagonal {
        assert_eq!(small_field.field, found.field);
    } else {
        assert!(relative_difference(&small_field.field, &found.field) < 1e-13);
    }
    fields_rows_and_id_equal_whole(&whole, &small);
}

/// Read in blocks of a few columns: the fields [`FieldBasis::visit_fields`] hands out, the basis
/// id and the rows of `U` are the loaded basis's bit for bit where `M1` is diagonal; with a
/// non-diagonal `M1` the co-integrable fields and rows come from mass solves of other blocks of
/// columns than the loaded basis's one solve, equal to `1e-13` of the largest entry (and so the
/// basis id differs).
fn fields_rows_and_id_equal_whole(whole: &SpectralBasis, blocks: &BasisFileBlocks) {
    let n1 = whole.field_dimension();
    let exact_cointegrable = whole.field_mass().diagonal_values().is_some();
    let visited = Mutex::new(vec![Vec::new(); whole.len()]);
    blocks
        .visit_fields(&|i, field| visited.lock().unwrap()[i] = field.to_vec())
        .unwrap();
    for (i, field) in visited.into_inner().unwrap().iter().enumerate() {
        let expected: Vec<f64> = whole.fields().col(i).iter().copied().collect();
        let family = whole.families()[i];
        if exact_cointegrable || family != FieldFamily::Cointegrable {
            let same = field.iter().zip(&expected);
            assert!(
                same.clone().all(|(a, b)| a.to_bits() == b.to_bits()),
                "field {i} ({family:?}) differs from the loaded one"
            );
        } else {
            assert!(relative_difference(field, &expected) < 1e-13, "field {i}");
        }
    }
    if exact_cointegrable {
        assert_eq!(field_basis_id(blocks).unwrap(), basis_id(whole));
    }
    assert_eq!(field_basis_id(whole).unwrap(), basis_id(whole));

    let rows = [0, 7, n1 / 2, n1 - 1];
    let (expected, found) = (whole.rows(&rows).unwrap(), blocks.rows(&rows).unwrap());
    let exact_cointegrable = whole.field_mass().diagonal_values().is_some();
    for (expected, found) in expected.iter().zip(&found) {
        let scale = expected.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (i, (a, b)) in found.iter().zip(expected).enumerate() {
            if exact_cointegrable || whole.families()[i] != FieldFamily::Cointegrable {
                assert_eq!(a, b, "entry {i} of a row");
            } else {
                assert!((a - b).abs() <= 1e-13 * scale, "entry {i}: {a} against {b}");
            }
        }
    }
    assert!(blocks.rows(&[n1]).is_err());
}

/// A field compressed with the basis in blocks (one block: with a non-diagonal `M1` the
/// co-integrable fields are then formed by the loaded basis's one mass solve): the same basis
/// id, so a file made with either decodes with the other; coefficients and decoded fields equal
/// to round-off (`1e-13`).
fn compression_equals_whole(whole: &SpectralBasis, blocks: &BasisFileBlocks, field: &[f64]) {
    let id = basis_id(whole);
    let coding = CoefficientCoding::Float64;
    let whole_codec = FieldCodec::new(whole, 1, id, 20, coding).unwrap();
    let blocks_codec = FieldCodec::new(blocks, 1, field_basis_id(blocks).unwrap(), 20, coding);
    let blocks_codec = blocks_codec.unwrap();
    assert_eq!(whole_codec.header(), blocks_codec.header());
    assert_eq!(whole_codec.selection(), blocks_codec.selection());
    let fields = [field.to_vec()];
    let (expected, expected_report) =
        compress_with_report(&whole_codec, whole.field_mass(), &fields, 642).unwrap();
    let (found, found_report) =
        compress_with_report(&blocks_codec, blocks.field_mass(), &fields, 642).unwrap();
    let relative_error = found_report.relative_errors[0];
    assert!((relative_error - expected_report.relative_errors[0]).abs() <= 1e-13);
    let decoded = whole_codec.decompress(&found).unwrap();
    let expected_field = blocks_codec.decompress(&expected).unwrap();
    assert!(relative_difference(&decoded[0], &expected_field[0]) < 1e-13);
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

/// What a basis file says without its fields ([`read_basis_spectrum`]): the header, the
/// eigenvalues and families of the file's basis, the file's size; a truncated file and one whose
/// eigenvalues are damaged (resealed, so that only their order tells) refused naming the file.
#[test]
fn the_spectrum_of_a_basis_file_is_read_without_its_fields() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(2);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let key = BasisFileKey::new(&mesh, &complex);
    let path = dir.path().join("spectrum.tvfb");
    save_computed_basis(&path, &complex, &BasisRequest::fields(30), &key).unwrap();
    let whole = load_basis(&path, &key, &complex).unwrap();
    let spectrum = read_basis_spectrum(&path).unwrap();
    assert_eq!(spectrum.eigenvalues, whole.eigenvalues());
    assert_eq!(spectrum.families, whole.families());
    assert_eq!(spectrum.header.key, key);
    assert_eq!(spectrum.header.field_count, 30);
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(spectrum.file_bytes, bytes.len() as u64);

    std::fs::write(&path, &bytes[..bytes.len() - 8]).unwrap();
    let error = read_basis_spectrum(&path).unwrap_err();
    assert!(matches!(error, BasisFileError::Truncated { .. }), "{error}");
    assert!(error.to_string().contains("spectrum.tvfb"), "{error}");
    // The first eigenvalue made larger than the last: no longer ascending.
    let header_length = header_length(&bytes);
    let mut unordered = bytes.clone();
    unordered[header_length..header_length + 8].copy_from_slice(&1e9f64.to_le_bytes());
    reseal_payload(&mut unordered);
    std::fs::write(&path, &unordered).unwrap();
    let error = read_basis_spectrum(&path).unwrap_err();
    assert!(
        error
            .to_string()
            .contains("spectrum.tvfb: invalid basis file"),
        "{error}"
    );
}
