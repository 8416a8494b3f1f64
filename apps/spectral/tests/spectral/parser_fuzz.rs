//! Random-input smoke fuzzing of the spectral file readers, the stable-toolchain counterpart of
//! the `npy`, `tvfb` and `tvfc` targets in `core/fuzz`: random bytes and mutated valid files
//! never panic; whatever parses is consistent.
//!
//! Inputs per reader: 3000 by default; set `TVF_FUZZ_CASES` for a longer run.

use crate::common::{
    coupled_field_mass, downgrade, header_length, reseal_header, reseal_payload, WithFieldMass,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::discretization::HodgeComplex;
use tvf_core::generate::torus;
use tvf_discretizations::{Conforming, MassLumping};
use tvf_spectral::{
    basis_id, compute_basis, compute_eigenfunction_basis, read_basis_file, save_basis,
    save_eigenfunction_basis, BasisFileKey, BasisRequest, CoefficientCoding, CompressedFields,
    FieldCodec, NpyArray, NpyDtype,
};

fn cases() -> usize {
    std::env::var("TVF_FUZZ_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(3000)
}

/// `seed` changed by a few random edits: flipped, replaced, inserted or deleted bytes,
/// "interesting" values, truncation, duplicated ranges.
fn mutate(seed: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for _ in 0..rng.random_range(1..6) {
        let at = if bytes.is_empty() {
            0
        } else {
            rng.random_range(0..bytes.len())
        };
        match rng.random_range(0..7) {
            0 if !bytes.is_empty() => bytes[at] ^= 1 << rng.random_range(0..8),
            1 if !bytes.is_empty() => {
                bytes[at] = [0u8, 0xff, 0x7f, 0x80, b'9', b'-', b'"', b'{'][rng.random_range(0..8)]
            }
            2 => bytes.insert(at, rng.random()),
            3 if !bytes.is_empty() => {
                let end = (at + rng.random_range(1..64)).min(bytes.len());
                bytes.drain(at..end);
            }
            4 => bytes.truncate(at),
            5 if !bytes.is_empty() => {
                let end = (at + rng.random_range(1..64)).min(bytes.len());
                let copy = bytes[at..end].to_vec();
                let to = rng.random_range(0..=bytes.len());
                bytes.splice(to..to, copy);
            }
            _ if bytes.len() >= at + 8 => {
                let value: u64 = [0, 1, u32::MAX as u64, u64::MAX, 1 << 40][rng.random_range(0..5)];
                bytes[at..at + 8].copy_from_slice(&value.to_le_bytes());
            }
            _ => {}
        }
    }
    bytes
}

/// Random bytes or a mutation of one of `seeds`.
fn input(seeds: &[Vec<u8>], rng: &mut ChaCha8Rng) -> Vec<u8> {
    if rng.random_bool(0.2) {
        let length = rng.random_range(0..256);
        (0..length).map(|_| rng.random()).collect()
    } else {
        mutate(&seeds[rng.random_range(0..seeds.len())], rng)
    }
}

#[test]
fn npy_parser_survives_random_and_mutated_files() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let seeds: Vec<Vec<u8>> = [
        (vec![4, 3], NpyDtype::F64),
        (vec![5], NpyDtype::F32),
        (vec![2, 3, 2], NpyDtype::F64),
    ]
    .into_iter()
    .map(|(shape, dtype)| {
        let count: usize = shape.iter().product();
        let data = (0..count).map(|k| k as f64 * 0.5).collect();
        NpyArray { shape, data, dtype }.to_bytes()
    })
    .collect();
    let mut parsed = 0;
    for _ in 0..cases() {
        let bytes = input(&seeds, &mut rng);
        let _ = NpyArray::data_start(&bytes);
        if let Ok(array) = NpyArray::from_bytes(&bytes) {
            parsed += 1;
            assert_eq!(array.shape.iter().product::<usize>(), array.data.len());
        }
    }
    println!("npy: {} inputs, {parsed} parsed", cases());
}

/// Recomputes both checksums of a basis file where its header length allows, so that mutated
/// contents reach the checks behind the checksums.
fn resealed(bytes: &mut [u8]) {
    if bytes.len() >= 16 {
        let h = header_length(bytes);
        if (8..=bytes.len() - 8).contains(&h) {
            reseal_header(bytes);
            reseal_payload(bytes);
        }
    }
}

#[test]
fn basis_and_compressed_file_readers_survive_mutated_files() {
    let mesh = torus(1.0, 0.45, 9, 6).unwrap();
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let basis = compute_basis(&complex, &BasisRequest::fields(12)).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("seed.tvfb");
    let key = BasisFileKey {
        discretization: "conforming-barycentric".into(),
        mesh_fingerprint: 7,
        face_count: mesh.face_count(),
        field_dimension: 2 * mesh.face_count(),
        matrix_hash: Some(complex.matrix_hash()),
    };
    save_basis(&path, &basis, &key).unwrap();
    let (compact, _) = compute_eigenfunction_basis(&complex, &BasisRequest::fields(12)).unwrap();
    let compact_path = dir.path().join("compact.tvfb");
    save_eigenfunction_basis(&compact_path, &compact, &complex, &key).unwrap();
    let sparse = {
        let inner = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
        let m1 = coupled_field_mass(inner.m1(), 0.3);
        WithFieldMass::new(inner, m1)
    };
    let sparse_path = dir.path().join("sparse.tvfb");
    let sparse_basis = compute_basis(&sparse, &BasisRequest::fields(4)).unwrap();
    save_basis(
        &sparse_path,
        &sparse_basis,
        &BasisFileKey::new(&mesh, &sparse),
    )
    .unwrap();
    // Both layouts: the dense fields (with a diagonal and a sparse M1) and the eigenfunctions;
    // and a file of format version 2.
    let dense = std::fs::read(&path).unwrap();
    let tvfb_seeds = [
        downgrade(&dense, 2),
        dense,
        std::fs::read(&compact_path).unwrap(),
        std::fs::read(&sparse_path).unwrap(),
    ];
    let field: Vec<f64> = (0..basis.field_dimension())
        .map(|k| (k as f64).sin())
        .collect();
    let tvfc_seeds: Vec<Vec<u8>> = [
        CoefficientCoding::Float64,
        CoefficientCoding::Quantized { bits: 8 },
    ]
    .into_iter()
    .map(|coding| {
        let codec = FieldCodec::new(&basis, 7, basis_id(&basis), 4, coding).unwrap();
        codec
            .compress(std::slice::from_ref(&field))
            .unwrap()
            .to_bytes()
    })
    .collect();

    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let (mut tvfb_parsed, mut tvfc_parsed) = (0, 0);
    let fuzz_path = dir.path().join("fuzz.tvfb");
    for _ in 0..cases() {
        let mut bytes = input(&tvfb_seeds, &mut rng);
        if rng.random_bool(0.5) {
            resealed(&mut bytes);
        }
        std::fs::write(&fuzz_path, &bytes).unwrap();
        match read_basis_file(&fuzz_path) {
            Ok((header, basis)) => {
                tvfb_parsed += 1;
                assert_eq!(header.field_count, basis.len());
            }
            Err(error) => assert!(error.to_string().contains("fuzz.tvfb"), "{error}"),
        }
        let bytes = input(&tvfc_seeds, &mut rng);
        if let Ok(file) = CompressedFields::from_bytes(&bytes) {
            tvfc_parsed += 1;
            assert!(CompressedFields::from_bytes(&file.to_bytes()).is_ok());
        }
    }
    println!(
        "tvfb: {} inputs, {tvfb_parsed} parsed; tvfc: {} inputs, {tvfc_parsed} parsed",
        cases(),
        cases()
    );
}
