//! Compression: lossless `f64` mode, the quantisation bound, file round trips, and refusal of
//! files for another mesh or basis and of damaged files.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::generate::torus;
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};
use tvf_spectral::{
    basis_id, compute_basis, BasisRequest, CoefficientCoding, CompressedFields, CompressionError,
    FieldCodec, FramePayload, SpectralBasis, UniformQuantizer,
};

const MESH: u64 = 0x1234_5678_9abc_def0;

fn random_field(dimension: usize, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..dimension)
        .map(|_| rng.random_range(-1.0..1.0))
        .collect()
}

fn complete_basis() -> (tvf_core::TriangleMesh, SpectralBasis) {
    let mesh = torus(1.0, 0.45, 9, 6).unwrap();
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let basis = compute_basis(&complex, &BasisRequest::complete()).unwrap();
    (mesh, basis)
}

/// Enough pairs to keep every field of the complete basis (each family is kept whole).
fn all_pairs(mesh: &tvf_core::TriangleMesh) -> usize {
    mesh.edge_count() - 1
}

#[test]
fn float64_mode_is_lossless() {
    let (mesh, basis) = complete_basis();
    let id = basis_id(&basis);
    let pairs = all_pairs(&mesh);
    let codec = FieldCodec::new(&basis, MESH, id, pairs, CoefficientCoding::Float64).unwrap();
    let field = random_field(basis.field_dimension(), 1);
    let coefficients = basis.coefficients(&field).unwrap();
    let file = codec.compress(std::slice::from_ref(&field)).unwrap();
    let parsed = CompressedFields::from_bytes(&file.to_bytes()).unwrap();
    assert_eq!(parsed, file);
    let decoder = FieldCodec::for_file(&basis, MESH, id, &parsed.header).unwrap();
    let decoded = decoder.decode_coefficients(&parsed.frames[0]).unwrap();
    for (i, value) in decoded.iter().enumerate() {
        if codec.selection().binary_search(&i).is_ok() {
            assert_eq!(
                value.to_bits(),
                coefficients[i].to_bits(),
                "coefficient {i} changed"
            );
        } else {
            assert_eq!(*value, 0.0);
        }
    }
    assert_eq!(codec.selection().len(), basis.len());
    let out = decoder.decode(&parsed.frames[0]).unwrap();
    assert_eq!(out, basis.reconstruct(&coefficients).unwrap());
    let error = tvf_spectral::relative_l2_error(basis.field_mass(), &field, &out);
    assert!(error < 1e-12, "relative error {error}");
}

#[test]
fn float64_mode_reconstructs_fields_in_the_span_of_the_kept_fields() {
    let (_, basis) = complete_basis();
    let id = basis_id(&basis);
    let codec = FieldCodec::new(&basis, MESH, id, 10, CoefficientCoding::Float64).unwrap();
    assert_eq!(codec.selection().len(), 2 * 10 + 2);
    let mut coefficients = vec![0.0; basis.len()];
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for &i in codec.selection() {
        coefficients[i] = rng.random_range(-1.0..1.0);
    }
    let field = basis.reconstruct(&coefficients).unwrap();
    let decoded = codec.decode(&codec.encode(&field).unwrap()).unwrap();
    let error = tvf_spectral::relative_l2_error(basis.field_mass(), &field, &decoded);
    assert!(error < 1e-12, "relative error {error}");
}

#[test]
fn quantised_mode_stays_within_the_quantisation_bound() {
    let (mesh, basis) = complete_basis();
    let id = basis_id(&basis);
    let pairs = all_pairs(&mesh);
    let field = random_field(basis.field_dimension(), 2);
    let coefficients = basis.coefficients(&field).unwrap();
    let exact_codec = FieldCodec::new(&basis, MESH, id, pairs, CoefficientCoding::Float64).unwrap();
    let projection = exact_codec
        .decode(&exact_codec.encode(&field).unwrap())
        .unwrap();
    let mut previous_size = usize::MAX;
    for bits in [32, 24, 16, 12, 8, 6, 4, 2] {
        let coding = CoefficientCoding::Quantized { bits };
        let codec = FieldCodec::new(&basis, MESH, id, pairs, coding).unwrap();
        let file = codec.compress(std::slice::from_ref(&field)).unwrap();
        let bytes = file.to_bytes();
        let parsed = CompressedFields::from_bytes(&bytes).unwrap();
        let FramePayload::Quantized { step, .. } = parsed.frames[0] else {
            panic!("quantised frame expected")
        };
        let quantizer = UniformQuantizer::with_step(step, bits).unwrap();
        let decoded = codec.decode_coefficients(&parsed.frames[0]).unwrap();
        for &i in codec.selection() {
            assert!(
                (decoded[i] - coefficients[i]).abs() <= quantizer.max_error() * (1.0 + 1e-12),
                "{bits} bits: coefficient {i} off by {} > step/2 = {}",
                (decoded[i] - coefficients[i]).abs(),
                quantizer.max_error()
            );
        }
        let field_out = codec.decode(&parsed.frames[0]).unwrap();
        let difference: Vec<f64> = field_out
            .iter()
            .zip(&projection)
            .map(|(a, b)| a - b)
            .collect();
        let bound = quantizer.max_error() * (codec.selection().len() as f64).sqrt();
        let error = basis.inner_product(&difference, &difference).sqrt();
        assert!(
            error <= bound * (1.0 + 1e-9),
            "{bits} bits: error {error} above bound {bound}"
        );
        assert!(
            bytes.len() <= previous_size,
            "{bits} bits: file grew to {}",
            bytes.len()
        );
        previous_size = bytes.len();
        if bits <= 16 {
            let f64_size = exact_codec
                .compress(std::slice::from_ref(&field))
                .unwrap()
                .to_bytes()
                .len();
            assert!(
                bytes.len() * 3 < f64_size,
                "{bits} bits: {} bytes vs {f64_size}",
                bytes.len()
            );
        }
    }
}

#[test]
fn files_round_trip_through_the_file_system() {
    let (_, basis) = complete_basis();
    let id = basis_id(&basis);
    let codec = FieldCodec::new(
        &basis,
        MESH,
        id,
        20,
        CoefficientCoding::Quantized { bits: 10 },
    )
    .unwrap();
    let fields: Vec<Vec<f64>> = (0..3)
        .map(|s| random_field(basis.field_dimension(), s))
        .collect();
    let file = codec.compress(&fields).unwrap();
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("field.tvfc");
    let written = file.write_atomic(&path).unwrap();
    assert_eq!(written, std::fs::metadata(&path).unwrap().len() as usize);
    let read = CompressedFields::read(&path).unwrap();
    assert_eq!(read, file);
    // Only the file itself is in the folder: the temporary file was renamed.
    assert_eq!(std::fs::read_dir(folder.path()).unwrap().count(), 1);
}

#[test]
fn files_for_another_mesh_or_basis_are_refused() {
    let (mesh, basis) = complete_basis();
    let id = basis_id(&basis);
    let codec = FieldCodec::new(&basis, MESH, id, 15, CoefficientCoding::Float64).unwrap();
    let file = codec
        .compress(&[random_field(basis.field_dimension(), 3)])
        .unwrap();
    let error = FieldCodec::for_file(&basis, MESH ^ 1, id, &file.header).unwrap_err();
    assert!(
        matches!(error, CompressionError::MeshMismatch { .. }),
        "{error}"
    );
    assert!(error.to_string().contains("another mesh"));

    // The other decomposition's basis on the same mesh has another id.
    let other_complex = Nonconforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let other = compute_basis(&other_complex, &BasisRequest::complete()).unwrap();
    let other_id = basis_id(&other);
    assert_ne!(other_id, id);
    let error = FieldCodec::for_file(&other, MESH, other_id, &file.header).unwrap_err();
    assert!(
        matches!(error, CompressionError::BasisMismatch { .. }),
        "{error}"
    );

    // Flipping the sign of one eigenfield (an equally valid basis) changes the id too.
    let mut fields = basis.fields().to_owned();
    for i in 0..fields.nrows() {
        fields[(i, 7)] = -fields[(i, 7)];
    }
    let flipped = SpectralBasis::new(
        basis.eigenvalues().to_vec(),
        basis.families().to_vec(),
        fields,
        basis.field_mass().clone(),
    )
    .unwrap();
    assert_ne!(basis_id(&flipped), id);

    // Too few fields for the pairs asked for.
    let error = FieldCodec::new(
        &basis,
        MESH,
        id,
        mesh.edge_count(),
        CoefficientCoding::Float64,
    )
    .unwrap_err();
    assert!(
        matches!(error, CompressionError::NotEnoughFields { .. }),
        "{error}"
    );
}

#[test]
fn damaged_and_truncated_files_are_refused() {
    let (_, basis) = complete_basis();
    let id = basis_id(&basis);
    for coding in [
        CoefficientCoding::Float64,
        CoefficientCoding::Quantized { bits: 12 },
    ] {
        let codec = FieldCodec::new(&basis, MESH, id, 12, coding).unwrap();
        let file = codec
            .compress(&[random_field(basis.field_dimension(), 4)])
            .unwrap();
        let bytes = file.to_bytes();
        for position in 0..bytes.len() {
            for flip in [0x01u8, 0x80] {
                let mut damaged = bytes.clone();
                damaged[position] ^= flip;
                let error = CompressedFields::from_bytes(&damaged)
                    .expect_err("a flipped bit must be detected");
                match error {
                    CompressionError::NotTvfc
                    | CompressionError::UnsupportedVersion { .. }
                    | CompressionError::ChecksumMismatch { .. }
                    | CompressionError::Truncated { .. }
                    | CompressionError::TrailingBytes { .. } => {}
                    other => panic!("byte {position}: unexpected error {other}"),
                }
            }
        }
        for length in 0..bytes.len() {
            let error = CompressedFields::from_bytes(&bytes[..length]).expect_err("truncated");
            assert!(
                matches!(
                    error,
                    CompressionError::NotTvfc | CompressionError::Truncated { .. }
                ),
                "length {length}: {error}"
            );
        }
        let mut longer = bytes.clone();
        longer.push(0);
        assert!(matches!(
            CompressedFields::from_bytes(&longer),
            Err(CompressionError::TrailingBytes { extra: 1 })
        ));
        let mut newer = bytes.clone();
        newer[8] = 9;
        assert!(matches!(
            CompressedFields::from_bytes(&newer),
            Err(CompressionError::UnsupportedVersion { found: 9, .. })
        ));
    }
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("damaged.tvfc");
    std::fs::write(&path, b"TVFC\r\n\x1a\n\x01\x00").unwrap();
    let error = CompressedFields::read(&path).unwrap_err();
    assert!(error.to_string().contains("damaged.tvfc"), "{error}");
    assert!(error.to_string().contains("truncated"), "{error}");
}
