//! Basis files (`.tvfb`): bit-exact round trip and one typed error per kind of bad file.

use std::path::Path;
use tvf_core::generate::{icosphere, rigid_motion};
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};
use tvf_spectral::{
    compute_basis, compute_eigenfunction_basis, load_basis, read_basis_file, read_basis_header,
    save_basis, save_eigenfunction_basis, BasisFileError, BasisFileKey, BasisRequest,
    SpectralBasis,
};

fn setup() -> (tvf_core::SurfaceMesh, SpectralBasis, BasisFileKey) {
    let mesh = icosphere(1);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let basis = compute_basis(&complex, &BasisRequest::pairs(17)).unwrap();
    let key = BasisFileKey::new(&mesh, &complex);
    (mesh, basis, key)
}

fn bits(basis: &SpectralBasis) -> Vec<u64> {
    let u = basis.fields();
    let mut out: Vec<u64> = basis.eigenvalues().iter().map(|x| x.to_bits()).collect();
    out.extend(basis.field_mass().iter().map(|x| x.to_bits()));
    for j in 0..u.ncols() {
        for i in 0..u.nrows() {
            out.push(u[(i, j)].to_bits());
        }
    }
    out
}

#[test]
fn round_trip_is_bit_exact() {
    let (_, basis, key) = setup();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sphere.tvfb");
    save_basis(&path, &basis, &key).unwrap();
    let loaded = load_basis(&path, &key).unwrap();
    assert_eq!(loaded.families(), basis.families());
    assert_eq!(bits(&loaded), bits(&basis));
    let header = read_basis_header(&path).unwrap();
    assert_eq!(header.key, key);
    assert_eq!(header.field_count, 34);
    assert_eq!(header.integrable_count, 17);
    let (_, again) = read_basis_file(&path).unwrap();
    assert_eq!(bits(&again), bits(&basis));
    // saving over an existing file leaves exactly one file
    save_basis(&path, &loaded, &key).unwrap();
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

/// The streaming writer (fields formed from the eigenfunctions while the file is written) writes
/// the same bytes as the writer of the dense basis, over more than one chunk of fields.
#[test]
fn streamed_compact_basis_is_the_dense_basis_file() {
    let mesh = icosphere(2);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let request = BasisRequest::pairs(70).with_seed(3);
    let key = BasisFileKey::new(&mesh, &complex);
    let dir = tempfile::tempdir().unwrap();
    let (compact, _) = compute_eigenfunction_basis(&complex, &request).unwrap();
    assert!(compact.len() > 128);
    let streamed = dir.path().join("streamed.tvfb");
    save_eigenfunction_basis(&streamed, &compact, &complex, &key).unwrap();
    let dense = dir.path().join("dense.tvfb");
    save_basis(&dense, &compute_basis(&complex, &request).unwrap(), &key).unwrap();
    assert_eq!(
        std::fs::read(&streamed).unwrap(),
        std::fs::read(&dense).unwrap()
    );
    let loaded = load_basis(&streamed, &key).unwrap();
    assert_eq!(loaded.eigenvalues(), compact.eigenvalues());
}

fn damaged(path: &Path, bytes: &[u8], key: &BasisFileKey) -> BasisFileError {
    std::fs::write(path, bytes).unwrap();
    let error = load_basis(path, key).unwrap_err();
    assert!(
        error.to_string().contains(&path.display().to_string()),
        "{error}"
    );
    error
}

#[test]
fn every_bad_file_gets_its_error() {
    let (mesh, basis, key) = setup();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("good.tvfb");
    save_basis(&path, &basis, &key).unwrap();
    let good = std::fs::read(&path).unwrap();
    let bad = dir.path().join("bad.tvfb");

    // another mesh: the same sphere rigidly moved (same counts, other coordinates)
    let moved = rigid_motion(&mesh, [0.3, -0.2, 0.9], 0.7, [1.0, 2.0, 3.0]).unwrap();
    let moved_key = BasisFileKey::new(
        &moved,
        &Conforming::new(&moved, MassLumping::Barycentric).unwrap(),
    );
    assert!(matches!(
        load_basis(&path, &moved_key),
        Err(BasisFileError::WrongMesh { .. })
    ));
    let finer = icosphere(2);
    let finer_key = BasisFileKey::new(
        &finer,
        &Conforming::new(&finer, MassLumping::Barycentric).unwrap(),
    );
    assert!(matches!(
        load_basis(&path, &finer_key),
        Err(BasisFileError::WrongMesh {
            found_faces: 80,
            expected_faces: 320,
            ..
        })
    ));
    // another discretization, another mass lumping
    for other in [
        BasisFileKey::new(
            &mesh,
            &Nonconforming::new(&mesh, MassLumping::Barycentric).unwrap(),
        ),
        BasisFileKey::new(
            &mesh,
            &Conforming::new(&mesh, MassLumping::Voronoi).unwrap(),
        ),
    ] {
        let error = load_basis(&path, &other).unwrap_err();
        assert!(
            matches!(error, BasisFileError::WrongDiscretization { .. }),
            "{error}"
        );
    }
    // a newer format
    let mut newer = good.clone();
    newer[8..12].copy_from_slice(&2u32.to_le_bytes());
    assert!(matches!(
        damaged(&bad, &newer, &key),
        BasisFileError::NewerFormat {
            found: 2,
            supported: 1,
            ..
        }
    ));
    // not a basis file at all
    assert!(matches!(
        damaged(&bad, b"v 0 0 0\n", &key),
        BasisFileError::NotABasisFile { .. }
    ));
    assert!(matches!(
        damaged(&bad, &[], &key),
        BasisFileError::NotABasisFile { .. }
    ));
    // truncated in the payload, in the header
    assert!(matches!(
        damaged(&bad, &good[..good.len() - 100], &key),
        BasisFileError::Truncated { .. }
    ));
    assert!(matches!(
        damaged(&bad, &good[..40], &key),
        BasisFileError::Truncated { .. }
    ));
    // trailing garbage
    let mut longer = good.clone();
    longer.extend_from_slice(&[0; 8]);
    assert!(matches!(
        damaged(&bad, &longer, &key),
        BasisFileError::Invalid { .. }
    ));
    // one flipped bit in the header, in the eigenvalues, in the fields, in the checksum
    let header_length = u32::from_le_bytes(good[12..16].try_into().unwrap()) as usize;
    let mut flip = good.clone();
    flip[20] ^= 0x04;
    assert!(matches!(
        damaged(&bad, &flip, &key),
        BasisFileError::Checksum { part: "header", .. }
    ));
    for position in [
        header_length + 3,
        good.len() / 2,
        good.len() - 9,
        good.len() - 1,
    ] {
        let mut flip = good.clone();
        flip[position] ^= 0x80;
        assert!(
            matches!(
                damaged(&bad, &flip, &key),
                BasisFileError::Checksum {
                    part: "payload",
                    ..
                }
            ),
            "flip at {position}"
        );
    }
    // missing file
    assert!(matches!(
        load_basis(&dir.path().join("missing.tvfb"), &key),
        Err(BasisFileError::Io { .. })
    ));
    // a basis that does not fit the key is refused at save time
    assert!(matches!(
        save_basis(&bad, &basis, &finer_key),
        Err(BasisFileError::Invalid { .. })
    ));
}
