//! [`basis_id`]: a 64-bit fingerprint of a [`SpectralBasis`], stored in compressed files so that
//! coefficients are never decoded with another basis; [`field_basis_id`]: the same of any
//! [`FieldBasis`] (a basis file read in blocks gets the id of the same file loaded whole).

use crate::basis::{FieldFamily, SpectralBasis};
use crate::{FieldBasis, SpectralBasisError};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};
use tvf_core::discretization::MassStorage;

/// Multiplier of the word mixing (a 64-bit odd constant from the golden ratio).
const MIX: u64 = 0x9E37_79B9_7F4A_7C15;

fn absorb(state: u64, word: u64) -> u64 {
    (state.rotate_left(23) ^ word).wrapping_mul(MIX)
}

/// The splitmix64 finaliser: every input bit affects every output bit.
fn finalize(mut x: u64) -> u64 {
    x ^= x >> 30;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 27;
    x = x.wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}

/// A fingerprint of everything that decoding depends on: the shape `n1 × d`, the eigenvalues,
/// the families, the field mass `M1` and every entry of the fields (bit patterns, so two bases that
/// differ only in the sign of one eigenfield get different ids). Columns are hashed in parallel.
pub fn basis_id(basis: &SpectralBasis) -> u64 {
    let fields = basis.fields();
    let column_hashes: Vec<u64> = (0..basis.len())
        .into_par_iter()
        .map(|j| column_hash(j, fields.col(j).iter().copied()))
        .collect();
    combined_id(basis, &column_hashes)
}

/// [`basis_id`] of any [`FieldBasis`], its fields visited once
/// ([`FieldBasis::visit_fields`]); equal to the id of the same basis loaded whole where the
/// fields are formed as the loaded basis forms them (for a basis file read in blocks:
/// [`crate::BasisFileBlocks::forms_fields_as_loaded`]).
pub fn field_basis_id(basis: &dyn FieldBasis) -> Result<u64, SpectralBasisError> {
    let column_hashes: Vec<AtomicU64> = (0..basis.len()).map(|_| AtomicU64::new(0)).collect();
    basis.visit_fields(&|j, field| {
        column_hashes[j].store(column_hash(j, field.iter().copied()), Ordering::Relaxed)
    })?;
    let column_hashes: Vec<u64> = column_hashes.into_iter().map(|h| h.into_inner()).collect();
    Ok(combined_id(basis, &column_hashes))
}

/// The hash of field `j` with the values `column`.
fn column_hash(j: usize, column: impl Iterator<Item = f64>) -> u64 {
    finalize(column.fold(absorb(MIX, j as u64), |state, value| {
        absorb(state, value.to_bits())
    }))
}

/// The id of `basis` with the hashes of its fields.
fn combined_id(basis: &dyn FieldBasis, column_hashes: &[u64]) -> u64 {
    let mut state = absorb(
        absorb(0, basis.field_dimension() as u64),
        basis.len() as u64,
    );
    for (&lambda, &family) in basis.eigenvalues().iter().zip(basis.families()) {
        let tag = match family {
            FieldFamily::Harmonic => 1,
            FieldFamily::Integrable => 2,
            FieldFamily::Cointegrable => 3,
        };
        state = absorb(absorb(state, lambda.to_bits()), tag);
    }
    match basis.field_mass().storage() {
        MassStorage::Diagonal(values) => {
            for &m in values {
                state = absorb(state, m.to_bits());
            }
        }
        MassStorage::Sparse(matrix) => {
            state = absorb(state, basis.field_mass().form() as u64 + 1);
            for (&m, (i, j)) in matrix.iter() {
                state = absorb(absorb(absorb(state, i as u64), j as u64), m.to_bits());
            }
        }
    }
    for &h in column_hashes {
        state = absorb(state, h);
    }
    finalize(state)
}
