//! Basis files (`.tvfb`): bit-exact round trips in both layouts, files of format versions 1 and
//! 2 (rewritten, and as tvf wrote them), and one typed error per kind of bad file.

use crate::common::downgrade;
use std::path::Path;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::generate::{icosphere, rigid_motion, torus};
use tvf_core::Hash64;
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};
use tvf_spectral::{
    compute_basis, compute_eigenfunction_basis, load_basis, read_basis_file, read_basis_header,
    save_basis, save_eigenfunction_basis, BasisFileError, BasisFileKey, BasisFileLayout,
    BasisRequest, BasisSize, SpectralBasis, StoredBasis, StoredFieldMass,
};

fn setup() -> (
    tvf_core::TriangleMesh,
    Conforming,
    SpectralBasis,
    BasisFileKey,
) {
    let mesh = icosphere(1);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let basis = compute_basis(&complex, &BasisRequest::pairs(17)).unwrap();
    let key = BasisFileKey::new(&mesh, &complex);
    (mesh, complex, basis, key)
}

fn bits(basis: &SpectralBasis) -> Vec<u64> {
    let u = basis.fields();
    let mut out: Vec<u64> = basis.eigenvalues().iter().map(|x| x.to_bits()).collect();
    out.extend(
        basis
            .field_mass()
            .diagonal_values()
            .unwrap()
            .iter()
            .map(|x| x.to_bits()),
    );
    for j in 0..u.ncols() {
        for i in 0..u.nrows() {
            out.push(u[(i, j)].to_bits());
        }
    }
    out
}

#[test]
fn round_trip_is_bit_exact() {
    let (_, complex, basis, key) = setup();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sphere.tvfb");
    save_basis(&path, &basis, &key).unwrap();
    let loaded = load_basis(&path, &key, &complex).unwrap();
    assert_eq!(loaded.families(), basis.families());
    assert_eq!(bits(&loaded), bits(&basis));
    let header = read_basis_header(&path).unwrap();
    assert_eq!(header.key, key);
    assert_eq!(header.version, 3);
    assert_eq!(header.key.matrix_hash, Some(complex.matrix_hash()));
    assert_eq!(header.field_count, 34);
    assert_eq!(header.integrable_count, 17);
    assert_eq!(header.layout, BasisFileLayout::Fields);
    assert_eq!(header.field_mass, StoredFieldMass::Diagonal);
    let (_, StoredBasis::Fields(again)) = read_basis_file(&path).unwrap() else {
        panic!("a dense basis is stored as fields");
    };
    assert_eq!(bits(&again), bits(&basis));
    // saving over an existing file leaves exactly one file
    save_basis(&path, &loaded, &key).unwrap();
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

/// A compact basis is saved as eigenfunctions, about half the bytes of its fields, and loads to
/// exactly the fields `compute_basis` gives (over more than one chunk of fields).
#[test]
fn compact_basis_is_stored_as_eigenfunctions_and_loads_to_the_dense_fields() {
    let mesh = icosphere(2);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let request = BasisRequest::pairs(70).with_seed(3);
    let key = BasisFileKey::new(&mesh, &complex);
    let dir = tempfile::tempdir().unwrap();
    let (compact, _) = compute_eigenfunction_basis(&complex, &request).unwrap();
    assert!(compact.len() > 128);
    let stored = dir.path().join("compact.tvfb");
    save_eigenfunction_basis(&stored, &compact, &complex, &key).unwrap();
    let dense_basis = compute_basis(&complex, &request).unwrap();
    let dense = dir.path().join("dense.tvfb");
    save_basis(&dense, &dense_basis, &key).unwrap();
    let header = read_basis_header(&stored).unwrap();
    assert_eq!(
        header.layout,
        BasisFileLayout::Eigenfunctions {
            potential_dimension: mesh.vertex_count(),
            co_potential_dimension: mesh.edge_count(),
        }
    );
    assert_eq!(header.field_mass, StoredFieldMass::FromComplex);
    let (compact_bytes, dense_bytes) = (
        std::fs::metadata(&stored).unwrap().len(),
        std::fs::metadata(&dense).unwrap().len(),
    );
    // V + E values per pair against 4F: about half the fields (0.50 here), plus the eigenvalues.
    assert!(
        (compact_bytes as f64) < 0.52 * dense_bytes as f64,
        "{compact_bytes} against {dense_bytes}"
    );
    let loaded = load_basis(&stored, &key, &complex).unwrap();
    assert_eq!(loaded.families(), dense_basis.families());
    assert_eq!(bits(&loaded), bits(&dense_basis));
    let (header, StoredBasis::Eigenfunctions(read)) = read_basis_file(&stored).unwrap() else {
        panic!("a compact basis is stored as eigenfunctions");
    };
    assert_eq!(header.field_count, compact.len());
    assert_eq!(read.eigenvalues(), compact.eigenvalues());
    assert_eq!(read.potentials(), compact.potentials());
    assert_eq!(read.co_potentials(), compact.co_potentials());
    assert_eq!(read.harmonic_fields(), compact.harmonic_fields());
    // the complex of another mesh does not fit the stored eigenfunctions
    let other = Conforming::new(&icosphere(1), MassLumping::Barycentric).unwrap();
    let (_, stored_basis) = read_basis_file(&stored).unwrap();
    assert!(stored_basis.into_fields(&other).is_err());
}

/// Where the eigenfunctions are not smaller (only harmonic fields), the fields are written,
/// formed while the file is written.
#[test]
fn harmonic_only_basis_is_stored_as_fields() {
    let mesh = torus(1.0, 0.4, 12, 8).unwrap();
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let request = BasisRequest::fields(2);
    let key = BasisFileKey::new(&mesh, &complex);
    let (compact, _) = compute_eigenfunction_basis(&complex, &request).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("harmonic.tvfb");
    save_eigenfunction_basis(&path, &compact, &complex, &key).unwrap();
    assert_eq!(
        read_basis_header(&path).unwrap().layout,
        BasisFileLayout::Fields
    );
    let loaded = load_basis(&path, &key, &complex).unwrap();
    assert_eq!(
        bits(&loaded),
        bits(&compute_basis(&complex, &request).unwrap())
    );
}

/// Files of format versions 1 (fields only, no layout words in the header) and 2 (no matrix
/// hash, no field mass words) still load, bit-exact, in both layouts; their header carries no
/// matrix hash.
#[test]
fn version_one_and_two_files_load() {
    let (_, complex, basis, key) = setup();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sphere.tvfb");
    save_basis(&path, &basis, &key).unwrap();
    let current = std::fs::read(&path).unwrap();
    let (compact, _) = compute_eigenfunction_basis(&complex, &BasisRequest::pairs(17)).unwrap();
    let compact_path = dir.path().join("compact.tvfb");
    save_eigenfunction_basis(&compact_path, &compact, &complex, &key).unwrap();
    let compact_current = std::fs::read(&compact_path).unwrap();
    for (version, bytes) in [
        (1, downgrade(&current, 1)),
        (2, downgrade(&current, 2)),
        (2, downgrade(&compact_current, 2)),
    ] {
        std::fs::write(&path, &bytes).unwrap();
        let read = read_basis_header(&path).unwrap();
        assert_eq!(read.version, version);
        assert_eq!(read.key.matrix_hash, None);
        assert_eq!(
            read.key,
            BasisFileKey {
                matrix_hash: None,
                ..key.clone()
            }
        );
        let loaded = load_basis(&path, &key, &complex).unwrap();
        assert_eq!(bits(&loaded), bits(&basis));
    }
}

/// Files of format version 2 as tvf wrote them (`tvf basis`, conforming-barycentric, seed 0)
/// load: an octahedron's 6 lowest fields (eigenfunctions layout) and a square-frame torus's 2
/// harmonic fields (fields layout), the same eigenvalues as computed now and `M1`-orthonormal.
#[test]
fn version_two_files_written_by_tvf_load() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    for (name, fields, layout) in [
        (
            "octahedron",
            6,
            BasisFileLayout::Eigenfunctions {
                potential_dimension: 6,
                co_potential_dimension: 12,
            },
        ),
        ("frame-torus", 2, BasisFileLayout::Fields),
    ] {
        let mesh = tvf_core::io::load_mesh(data.join(format!("{name}.obj")))
            .unwrap()
            .mesh
            .into_triangles()
            .unwrap();
        let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
        let path = data.join(format!("{name}-v2.tvfb"));
        let header = read_basis_header(&path).unwrap();
        assert_eq!((header.version, header.layout), (2, layout), "{name}");
        assert_eq!(header.key.matrix_hash, None);
        let loaded = load_basis(&path, &BasisFileKey::new(&mesh, &complex), &complex).unwrap();
        let computed =
            tvf_spectral::compute_basis_of_size(&complex, BasisSize::Fields(fields), None).unwrap();
        assert_eq!(loaded.families(), computed.families(), "{name}");
        for (a, b) in loaded.eigenvalues().iter().zip(computed.eigenvalues()) {
            assert!(
                (a - b).abs() <= 1e-12 * b.abs().max(1.0),
                "{name}: {a} vs {b}"
            );
        }
        for i in 0..fields {
            for j in 0..fields {
                let column =
                    |k: usize| -> Vec<f64> { loaded.fields().col(k).iter().copied().collect() };
                let inner = complex.m1().inner(&column(i), &column(j));
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!(
                    (inner - expected).abs() < 1e-10,
                    "{name}: ⟨u{i}, u{j}⟩ = {inner}"
                );
            }
        }
        assert_eq!(loaded.field_dimension(), complex.field_dimension());
    }
}

fn damaged(path: &Path, bytes: &[u8], key: &BasisFileKey, complex: &Conforming) -> BasisFileError {
    std::fs::write(path, bytes).unwrap();
    let error = load_basis(path, key, complex).unwrap_err();
    assert!(
        error.to_string().contains(&path.display().to_string()),
        "{error}"
    );
    error
}

#[test]
fn every_bad_file_gets_its_error() {
    let (mesh, complex, basis, key) = setup();
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
        load_basis(&path, &moved_key, &complex),
        Err(BasisFileError::WrongMesh { .. })
    ));
    let finer = icosphere(2);
    let finer_key = BasisFileKey::new(
        &finer,
        &Conforming::new(&finer, MassLumping::Barycentric).unwrap(),
    );
    assert!(matches!(
        load_basis(&path, &finer_key, &complex),
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
        let error = load_basis(&path, &other, &complex).unwrap_err();
        assert!(
            matches!(error, BasisFileError::WrongDiscretization { .. }),
            "{error}"
        );
    }
    // a newer format
    let mut newer = good.clone();
    newer[8..12].copy_from_slice(&4u32.to_le_bytes());
    assert!(matches!(
        damaged(&bad, &newer, &key, &complex),
        BasisFileError::NewerFormat {
            found: 4,
            supported: 3,
            ..
        }
    ));
    // not a basis file at all
    assert!(matches!(
        damaged(&bad, b"v 0 0 0\n", &key, &complex),
        BasisFileError::NotABasisFile { .. }
    ));
    assert!(matches!(
        damaged(&bad, &[], &key, &complex),
        BasisFileError::NotABasisFile { .. }
    ));
    // truncated in the payload, in the header
    assert!(matches!(
        damaged(&bad, &good[..good.len() - 100], &key, &complex),
        BasisFileError::Truncated { .. }
    ));
    assert!(matches!(
        damaged(&bad, &good[..40], &key, &complex),
        BasisFileError::Truncated { .. }
    ));
    // trailing garbage
    let mut longer = good.clone();
    longer.extend_from_slice(&[0; 8]);
    assert!(matches!(
        damaged(&bad, &longer, &key, &complex),
        BasisFileError::Invalid { .. }
    ));
    // one flipped bit in the header, in the eigenvalues, in the fields, in the checksum
    let header_length = u32::from_le_bytes(good[12..16].try_into().unwrap()) as usize;
    let mut flip = good.clone();
    flip[20] ^= 0x04;
    assert!(matches!(
        damaged(&bad, &flip, &key, &complex),
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
                damaged(&bad, &flip, &key, &complex),
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
        load_basis(&dir.path().join("missing.tvfb"), &key, &complex),
        Err(BasisFileError::Io { .. })
    ));
    // a basis that does not fit the key is refused at save time
    assert!(matches!(
        save_basis(&bad, &basis, &finer_key),
        Err(BasisFileError::Invalid { .. })
    ));
}

/// A non-finite value behind valid checksums (a file written by a faulty tool) is refused, in
/// both layouts, naming the file.
#[test]
fn non_finite_values_behind_valid_checksums_are_refused() {
    let mesh = icosphere(1);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let request = BasisRequest::pairs(17);
    let key = BasisFileKey::new(&mesh, &complex);
    let dir = tempfile::tempdir().unwrap();
    let dense = dir.path().join("dense.tvfb");
    save_basis(&dense, &compute_basis(&complex, &request).unwrap(), &key).unwrap();
    let compact = dir.path().join("compact.tvfb");
    let (eigenfunctions, _) = compute_eigenfunction_basis(&complex, &request).unwrap();
    save_eigenfunction_basis(&compact, &eigenfunctions, &complex, &key).unwrap();
    // Loading forms the fields of the compact file, so both name a field; reading the compact
    // file as it is names the stored co-potential.
    for (path, stored) in [(&dense, "field"), (&compact, "co-potential")] {
        let mut bytes = std::fs::read(path).unwrap();
        let header_length = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        let end = bytes.len() - 8;
        // the last stored value, then the payload checksum recomputed
        bytes[end - 8..end].copy_from_slice(&f64::NAN.to_le_bytes());
        let checksum = Hash64::of(&bytes[header_length..end]);
        bytes[end..].copy_from_slice(&checksum.to_le_bytes());
        std::fs::write(path, &bytes).unwrap();
        let error = load_basis(path, &key, &complex).unwrap_err();
        assert!(matches!(error, BasisFileError::Invalid { .. }), "{error}");
        let message = error.to_string();
        assert!(message.contains(&path.display().to_string()), "{message}");
        assert!(
            message.contains("field") && message.contains("non-finite"),
            "{message}"
        );
        let message = read_basis_file(path).unwrap_err().to_string();
        assert!(
            message.contains(stored) && message.contains("non-finite"),
            "{message}"
        );
    }
}
