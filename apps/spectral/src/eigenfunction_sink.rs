//! [`EigenfunctionSink`]: where a basis computation hands its eigenfunctions column by column,
//! as the eigensolver finishes them, instead of keeping them in memory (the streamed basis
//! file is one).

use crate::FieldFamily;

/// Where a basis computation hands the eigenfunctions as they are computed, instead of keeping
/// them (see [`crate::save_computed_basis`]).
pub(crate) trait EigenfunctionSink: Sync {
    /// Called once, before any column, with the number of integrable, co-integrable and
    /// harmonic columns that will come: the basis keeps the first ones of each family, at most
    /// that many (the exact harmonic count; the computation fails if it ends up with more);
    /// `false` declines the columns (they are then kept in memory).
    fn begin(&self, counts: (usize, usize, usize)) -> Result<bool, String>;

    /// Column `index` of `family`'s matrix of the in-memory basis
    /// ([`crate::eigenfunction_basis::EigenfunctionBasis`]): a potential (`n0` values) or a
    /// co-potential (`n2`), normalised as there, bit for bit. Each column comes once, in no
    /// particular order.
    fn column(&self, family: FieldFamily, index: usize, values: &[f64]) -> Result<(), String>;
}
