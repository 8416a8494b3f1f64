//! Shared helpers of the basis file and basis store tests: a catalog complex with its field mass
//! `M1` replaced, under the same id — what a changed assembly of a catalog entry looks like to
//! basis files and the cache —, basis files rewritten as earlier format versions wrote them, and the
//! largest relative difference of two results.

use sprs::TriMat;
use tvf_core::discretization::{ComplexParts, HodgeComplex, Mass};
use tvf_core::Hash64;

/// `inner` with `M1` replaced (same id, mesh and every other matrix).
pub struct WithFieldMass<H> {
    _inner: H,
    parts: ComplexParts,
}

impl<H: HodgeComplex> WithFieldMass<H> {
    /// `inner` with the field mass `m1` (`n1 × n1`, positive definite on the free field nodes).
    pub fn new(inner: H, m1: Mass) -> Self {
        let p = inner.parts();
        let parts = ComplexParts::new(
            p.id(),
            p.d0().clone(),
            p.d1().clone(),
            [p.m0().clone(), m1, p.m2().clone()],
            [
                p.potential_nodes().clone(),
                p.field_nodes().clone(),
                p.co_potential_nodes().clone(),
            ],
            *p.topology(),
        )
        .unwrap();
        Self {
            _inner: inner,
            parts,
        }
    }
}

impl<H: HodgeComplex> HodgeComplex for WithFieldMass<H> {
    fn parts(&self) -> &ComplexParts {
        &self.parts
    }
}

/// A sparse SPD field mass from the diagonal `m1`: nodes `2k` and `2k + 1` (the two
/// coefficients of face `k` for face fields) coupled by `coupling · √(m_2k m_2k+1)`,
/// `|coupling| < 1`; exactly symmetric.
pub fn coupled_field_mass(m1: &Mass, coupling: f64) -> Mass {
    let m = m1.diagonal_values().unwrap();
    let mut t = TriMat::new((m.len(), m.len()));
    for (i, &value) in m.iter().enumerate() {
        t.add_triplet(i, i, value);
    }
    for k in 0..m.len() / 2 {
        let c = coupling * (m[2 * k] * m[2 * k + 1]).sqrt();
        t.add_triplet(2 * k, 2 * k + 1, c);
        t.add_triplet(2 * k + 1, 2 * k, c);
    }
    Mass::sparse("M1 (coupled)", t.to_csr()).unwrap()
}

/// The diagonal `m1` with entry `index` scaled by `factor`.
pub fn changed_diagonal(m1: &Mass, index: usize, factor: f64) -> Mass {
    let mut m = m1.diagonal_values().unwrap().to_vec();
    m[index] *= factor;
    Mass::diagonal("M1 (changed)", m).unwrap()
}

/// Offset of the matrix hash words in a version-3 header (after magic, version, length,
/// fingerprint, six counts and three layout words).
pub const MATRIX_HASH_AT: usize = 96;
/// Offset of the field mass words in a version-3 header.
pub const FIELD_MASS_AT: usize = 144;

/// The header length `H` of a basis file.
pub fn header_length(bytes: &[u8]) -> usize {
    u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize
}

/// Recomputes the header checksum (the 8 bytes before the payload).
pub fn reseal_header(bytes: &mut [u8]) {
    let h = header_length(bytes);
    let checksum = Hash64::of(&bytes[..h - 8]);
    bytes[h - 8..h].copy_from_slice(&checksum.to_le_bytes());
}

/// Recomputes the payload checksum (the last 8 bytes).
pub fn reseal_payload(bytes: &mut [u8]) {
    let (h, end) = (header_length(bytes), bytes.len() - 8);
    let checksum = Hash64::of(&bytes[h..end]);
    bytes[end..].copy_from_slice(&checksum.to_le_bytes());
}

/// A version-3 file with a diagonal `M1` (or in the eigenfunctions layout) rewritten as
/// `version` (2, or 1 for the fields layout) wrote it: the same payload under a header without
/// the matrix hash and field mass words (and, for version 1, the layout words).
pub fn downgrade(v3: &[u8], version: u32) -> Vec<u8> {
    let h = header_length(v3);
    let kept = if version == 1 { 72 } else { MATRIX_HASH_AT };
    let mut out = v3[..kept].to_vec();
    out.extend_from_slice(&v3[FIELD_MASS_AT + 24..h - 8]);
    out[8..12].copy_from_slice(&version.to_le_bytes());
    let length = out.len() + 8;
    out[12..16].copy_from_slice(&(length as u32).to_le_bytes());
    let checksum = Hash64::of(&out);
    out.extend_from_slice(&checksum.to_le_bytes());
    out.extend_from_slice(&v3[h..]);
    out
}

/// Largest difference of `a` and `b` relative to the largest magnitude of `b`.
pub fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let worst = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    worst / scale
}
