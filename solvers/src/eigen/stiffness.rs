//! [`Stiffness`]: the matrix `A` of a pencil as the eigensolver's products see it: a sparse
//! symmetric matrix (standard pencils) or the mixed operator `d1 W⁻¹ d1ᵀ`
//! ([`MixedOperator`]), applied to packed chunks of vectors in the pencil's input order.

use super::mixed_operator::MixedOperator;
use super::symmetric_products::{
    gather_times, gather_times_and_magnitudes, symmetric_times, times_by_chunks, Row,
};
use faer::sparse::SparseColMatRef;
use faer::{MatMut, MatRef, Par};

/// The stiffness `A` (`n × n`, symmetric) of a pencil.
#[derive(Clone, Copy)]
pub(crate) enum Stiffness<'a> {
    /// `A` in full symmetric CSC storage.
    Sparse(SparseColMatRef<'a, usize, f64>),
    /// `A = d1 W⁻¹ d1ᵀ`, never formed.
    Mixed(&'a MixedOperator),
}

impl Stiffness<'_> {
    /// `out ← A x` for the packed chunk `x` (`n` rows); `work` is scratch space for the mixed
    /// operator (resized as needed, contents unspecified).
    #[inline(always)]
    pub(crate) fn times_rows(self, x: &[Row], out: &mut [Row], work: &mut Vec<Row>) {
        match self {
            Stiffness::Sparse(a) => gather_times(a, x, out),
            Stiffness::Mixed(operator) => operator.times_rows(x, out, work),
        }
    }

    /// [`Self::times_rows`] and the magnitudes of the products (`|A| |x|` for a sparse `A`;
    /// see [`MixedOperator::times_rows_and_magnitudes`]).
    pub(crate) fn times_rows_and_magnitudes(
        self,
        x: &[Row],
        out: &mut [Row],
        magnitudes: &mut [Row],
        work: &mut Vec<Row>,
    ) {
        match self {
            Stiffness::Sparse(a) => gather_times_and_magnitudes(a, x, out, magnitudes),
            Stiffness::Mixed(operator) => {
                operator.times_rows_and_magnitudes(x, out, magnitudes, work)
            }
        }
    }

    /// `xᵀ A x` for each column of the packed chunk `x` (`n` rows); `out` and `work` are
    /// scratch space (`out`: `n` rows, contents unspecified afterwards). For the mixed operator
    /// without forming `A x` ([`MixedOperator::energy_rows`]).
    pub(crate) fn energy_rows(self, x: &[Row], out: &mut [Row], work: &mut Vec<Row>) -> Row {
        if let Stiffness::Mixed(operator) = self {
            return operator.energy_rows(x, work);
        }
        self.times_rows(x, out, work);
        let mut energy = [0.0; 8];
        for (x, ax) in x.iter().zip(out.iter()) {
            for j in 0..8 {
                energy[j] += x[j] * ax[j];
            }
        }
        energy
    }

    /// `out ← A x` (`n × s`), in parallel over chunks of columns under `par`.
    pub(crate) fn times(self, out: MatMut<'_, f64>, x: MatRef<'_, f64>, par: Par) {
        let operator = match self {
            Stiffness::Sparse(a) => return symmetric_times(out, a, x, par),
            Stiffness::Mixed(operator) => operator,
        };
        times_by_chunks(out, x, par, |rows, product| {
            operator.times_rows(rows, product, &mut Vec::new());
        });
    }
}
