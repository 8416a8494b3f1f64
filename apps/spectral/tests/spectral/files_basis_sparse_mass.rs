//! Basis files of a complex whose field mass `M1` is a sparse matrix: bit-exact round trips in
//! both layouts (the fields layout stores `M1` in compressed sparse rows), the same basis id, and
//! a clear error, naming the file, for every kind of damaged or hostile mass section.

use crate::common::{
    coupled_field_mass, header_length, reseal_header, reseal_payload, WithFieldMass, FIELD_MASS_AT,
};
use std::path::Path;
use tvf_core::discretization::{HodgeComplex, Mass, MassStorage};
use tvf_core::generate::{icosphere, torus};
use tvf_core::TriangleMesh;
use tvf_discretizations::{Conforming, MassLumping};
use tvf_spectral::{
    basis_id, compute_basis, compute_eigenfunction_basis, load_basis, read_basis_file,
    read_basis_header, save_basis, save_eigenfunction_basis, BasisFileError, BasisFileKey,
    BasisFileLayout, BasisRequest, SpectralBasis, StoredBasis, StoredFieldMass,
};

/// The conforming complex of `mesh` with its two coefficients per face coupled in `M1`.
fn coupled(mesh: &TriangleMesh) -> WithFieldMass<Conforming> {
    let inner = Conforming::new(mesh, MassLumping::Barycentric).unwrap();
    let m1 = coupled_field_mass(inner.m1(), 0.3);
    WithFieldMass::new(inner, m1)
}

/// Every bit of a basis: eigenvalues, `M1` (form and stored matrix) and fields.
fn bits(basis: &SpectralBasis) -> Vec<u64> {
    let mass = basis.field_mass();
    let mut out: Vec<u64> = basis.eigenvalues().iter().map(|x| x.to_bits()).collect();
    out.push(mass.form() as u64);
    match mass.storage() {
        MassStorage::Diagonal(values) => out.extend(values.iter().map(|x| x.to_bits())),
        MassStorage::Sparse(matrix) => {
            out.extend(matrix.indptr().raw_storage().iter().map(|&i| i as u64));
            out.extend(matrix.indices().iter().map(|&j| j as u64));
            out.extend(matrix.data().iter().map(|x| x.to_bits()));
        }
    }
    let u = basis.fields();
    for j in 0..u.ncols() {
        out.extend(u.col(j).iter().map(|x| x.to_bits()));
    }
    out
}

fn same_mass(a: &Mass, b: &Mass) -> bool {
    a.storage() == b.storage() && a.form() == b.form()
}

#[test]
fn a_sparse_field_mass_round_trips_bit_exact_in_both_layouts() {
    let mesh = icosphere(1);
    let complex = coupled(&mesh);
    let key = BasisFileKey::new(&mesh, &complex);
    let n1 = 2 * mesh.face_count();
    let request = BasisRequest::pairs(17);
    let dir = tempfile::tempdir().unwrap();

    // Dense fields: the fields layout, with M1 in compressed sparse rows.
    let dense = compute_basis(&complex, &request).unwrap();
    let path = dir.path().join("dense.tvfb");
    save_basis(&path, &dense, &key).unwrap();
    let header = read_basis_header(&path).unwrap();
    assert_eq!(header.layout, BasisFileLayout::Fields);
    assert_eq!(header.field_mass, StoredFieldMass::Sparse { nnz: 2 * n1 });
    let loaded = load_basis(&path, &key, &complex).unwrap();
    assert_eq!(bits(&loaded), bits(&dense));
    assert!(same_mass(loaded.field_mass(), complex.m1()));
    assert_eq!(basis_id(&loaded), basis_id(&dense));
    let (_, StoredBasis::Fields(read)) = read_basis_file(&path).unwrap() else {
        panic!("dense fields are stored as fields");
    };
    assert_eq!(bits(&read), bits(&dense));
    // The basis id (of compressed files) sees the sparse M1: the same fields with another M1
    // are another basis.
    let lumped = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let other_mass = coupled_field_mass(lumped.m1(), 0.31);
    let other = SpectralBasis::new(
        dense.eigenvalues().to_vec(),
        dense.families().to_vec(),
        dense.fields().to_owned(),
        other_mass,
    )
    .unwrap();
    assert_ne!(basis_id(&other), basis_id(&dense));

    // Eigenfunctions: no mass in the file, M1 from the complex, the same fields.
    let (compact, _) = compute_eigenfunction_basis(&complex, &request).unwrap();
    let path = dir.path().join("compact.tvfb");
    save_eigenfunction_basis(&path, &compact, &complex, &key).unwrap();
    let header = read_basis_header(&path).unwrap();
    assert!(matches!(
        header.layout,
        BasisFileLayout::Eigenfunctions { .. }
    ));
    assert_eq!(header.field_mass, StoredFieldMass::FromComplex);
    let loaded = load_basis(&path, &key, &complex).unwrap();
    assert_eq!(bits(&loaded), bits(&dense));
    assert_eq!(basis_id(&loaded), basis_id(&dense));
}

/// Only harmonic fields: the eigenfunctions are not smaller, so the fields are written, with the
/// sparse `M1` (before version 3 such a basis could only be saved as eigenfunctions).
#[test]
fn a_harmonic_basis_with_a_sparse_mass_is_stored_as_fields() {
    let mesh = torus(1.0, 0.4, 12, 8).unwrap();
    let complex = coupled(&mesh);
    let key = BasisFileKey::new(&mesh, &complex);
    let request = BasisRequest::fields(2);
    let (compact, _) = compute_eigenfunction_basis(&complex, &request).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("harmonic.tvfb");
    save_eigenfunction_basis(&path, &compact, &complex, &key).unwrap();
    let header = read_basis_header(&path).unwrap();
    assert_eq!(header.layout, BasisFileLayout::Fields);
    assert!(matches!(header.field_mass, StoredFieldMass::Sparse { .. }));
    let loaded = load_basis(&path, &key, &complex).unwrap();
    assert_eq!(
        bits(&loaded),
        bits(&compute_basis(&complex, &request).unwrap())
    );
}

/// Reads `bytes` as the file `path` and returns the error, which must name the file.
fn refused(path: &Path, bytes: &[u8]) -> BasisFileError {
    std::fs::write(path, bytes).unwrap();
    let error = read_basis_file(path).unwrap_err();
    let message = error.to_string();
    assert!(message.contains(&path.display().to_string()), "{message}");
    error
}

#[track_caller]
fn assert_invalid(error: BasisFileError, words: &[&str]) {
    let message = error.to_string();
    assert!(matches!(error, BasisFileError::Invalid { .. }), "{message}");
    for word in words {
        assert!(message.contains(word), "{message} lacks {word:?}");
    }
}

#[test]
fn damaged_and_hostile_sparse_masses_are_refused_clearly() {
    let mesh = icosphere(1);
    let complex = coupled(&mesh);
    let key = BasisFileKey::new(&mesh, &complex);
    let basis = compute_basis(&complex, &BasisRequest::fields(6)).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sparse.tvfb");
    save_basis(&path, &basis, &key).unwrap();
    let good = std::fs::read(&path).unwrap();
    let bad = dir.path().join("bad.tvfb");
    let (n1, d) = (2 * mesh.face_count(), basis.len());
    let h = header_length(&good);
    // The mass section: after the eigenvalues and the padded family codes.
    let indptr_at = h + 8 * d + d.div_ceil(8) * 8;
    let indices_at = indptr_at + 8 * (n1 + 1);
    let data_at = indices_at + 8 * 2 * n1;

    // Cut inside the mass section.
    assert!(matches!(
        refused(&bad, &good[..indices_at + 5]),
        BasisFileError::Truncated { .. }
    ));
    // A flipped bit in the stored matrix.
    let mut flip = good.clone();
    flip[data_at + 8 * 3 + 2] ^= 0x10;
    assert!(matches!(
        refused(&bad, &flip),
        BasisFileError::Checksum {
            part: "payload",
            ..
        }
    ));

    // Hostile header words behind a valid header checksum.
    let with_mass_words = |words: [u64; 3]| {
        let mut bytes = good.clone();
        for (i, word) in words.iter().enumerate() {
            let at = FIELD_MASS_AT + 8 * i;
            bytes[at..at + 8].copy_from_slice(&word.to_le_bytes());
        }
        reseal_header(&mut bytes);
        bytes
    };
    // An entry count the file cannot hold: refused before anything is allocated for it.
    assert!(matches!(
        refused(&bad, &with_mass_words([2, 0, 1 << 40])),
        BasisFileError::Truncated { .. }
    ));
    assert_invalid(
        refused(&bad, &with_mass_words([2, 0, u64::MAX])),
        &["overflow"],
    );
    assert_invalid(
        refused(&bad, &with_mass_words([7, 0, 0])),
        &["storage code 7"],
    );
    assert_invalid(
        refused(&bad, &with_mass_words([2, 1, 2 * n1 as u64])),
        &["form"],
    );
    assert_invalid(
        refused(&bad, &with_mass_words([1, 0, 2 * n1 as u64])),
        &["not sparse"],
    );
    assert_invalid(
        refused(&bad, &with_mass_words([0, 0, 0])),
        &["does not fit the layout"],
    );

    // Inconsistent arrays behind a valid payload checksum.
    let with_word = |at: usize, word: u64| {
        let mut bytes = good.clone();
        bytes[at..at + 8].copy_from_slice(&word.to_le_bytes());
        reseal_payload(&mut bytes);
        bytes
    };
    let data = |k: usize| {
        let at = data_at + 8 * k;
        f64::from_le_bytes(good[at..at + 8].try_into().unwrap())
    };
    assert_invalid(refused(&bad, &with_word(indptr_at, 1)), &["row starts"]);
    assert_invalid(
        refused(&bad, &with_word(indices_at, n1 as u64)),
        &["sparse structure"],
    );
    // Row 0 holds (0, 0) and (0, 1): swapping its columns unsorts them.
    assert_invalid(
        refused(&bad, &with_word(indices_at, 1)),
        &["sparse structure"],
    );
    assert_invalid(
        refused(&bad, &with_word(data_at + 8, f64::NAN.to_bits())),
        &["not finite"],
    );
    // Entry (0, 1) against (1, 0): clearly asymmetric, or symmetric to round-off (then averaged
    // and so no longer the M1 the header's hash names).
    assert_invalid(
        refused(&bad, &with_word(data_at + 8, (2.0 * data(1)).to_bits())),
        &["symmetric"],
    );
    assert_invalid(
        refused(&bad, &with_word(data_at + 8, data(1).to_bits() + 1)),
        &["matrix hash"],
    );
}
