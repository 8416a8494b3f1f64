//! [`MixedOperator`]: the stiffness `A = d1 W⁻¹ d1ᵀ` of a mixed pencil, applied without forming
//! it (it is dense): `A x = d1 (W⁻¹ (d1ᵀ x))` with a sparse Cholesky factorization of `W`.
//!
//! `W` (`n1 × n1`, sparse SPD: e.g. the Whitney 1-form mass on edges) is factored once; the
//! incidence `d1` (`n2 × n1`: e.g. faces × edges, entries ±1) is stored twice with its `n1`
//! side in the elimination order of that factorization, so the intermediate `d1ᵀ x` is formed
//! directly in that order and the triangular solves need no permutation.

use super::symmetric_products::{gather_times, gather_times_and_magnitudes, Row};
use crate::convert::{square_dimension, to_faer_csc, upper_triangle_csc};
use crate::error::SolverError;
use crate::sparse_ldlt::SparseLdlt;
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use faer::Mat;

/// `A = d1 W⁻¹ d1ᵀ` (`n2 × n2`, symmetric positive semidefinite), by its factors.
pub(crate) struct MixedOperator {
    /// `LDLᵀ = W`, all pivots positive, solved on one thread (intervals solve concurrently).
    w: SparseLdlt,
    /// `d1` (`n2 × n1`) with column `k` the column of the `k`-th unknown of `W`'s elimination
    /// order: column `k` gathers `(d1ᵀ x)_k`.
    by_edge: SparseColMat<usize, f64>,
    /// `d1ᵀ` (`n1 × n2`) with row `k` as in `by_edge`: column `f` gathers `(d1 u)_f`.
    by_face: SparseColMat<usize, f64>,
    /// `d1` (`n2 × n1`) in the input order of both sides.
    incidence: SparseColMat<usize, f64>,
}

/// `d1` stored for products both ways: `(by_edge, by_face)`, see [`ordered_incidence`].
pub(crate) type IncidenceBothWays = (SparseColMat<usize, f64>, SparseColMat<usize, f64>);

/// `d1` (`n2 × n1`) with its `n1` side renumbered by `position` (edge `e` becomes `position[e]`),
/// stored twice: `(by_edge, by_face)`, `by_edge` (`n2 × n1`) whose column `position[e]` gathers
/// `(d1ᵀ x)_e`, and `by_face` (`n1 × n2`) whose column `f` gathers `(d1 u)_f`.
pub(crate) fn ordered_incidence(
    incidence: SparseColMatRef<'_, usize, f64>,
    position: &[usize],
) -> Result<IncidenceBothWays, SolverError> {
    let (n2, n1) = (incidence.nrows(), incidence.ncols());
    let (col_ptr, row_idx) = (
        incidence.symbolic().col_ptr(),
        incidence.symbolic().row_idx(),
    );
    let mut by_edge = Vec::with_capacity(incidence.val().len());
    let mut by_face = Vec::with_capacity(incidence.val().len());
    for e in 0..n1 {
        for p in col_ptr[e]..col_ptr[e + 1] {
            let (f, v) = (row_idx[p], incidence.val()[p]);
            by_edge.push(Triplet::new(f, position[e], v));
            by_face.push(Triplet::new(position[e], f, v));
        }
    }
    let build = |rows, cols, triplets: &[Triplet<usize, usize, f64>]| {
        SparseColMat::try_new_from_triplets(rows, cols, triplets)
            .map_err(|e| SolverError::Factorization(format!("{e:?}")))
    };
    Ok((build(n2, n1, &by_edge)?, build(n1, n2, &by_face)?))
}

impl MixedOperator {
    /// Checks and factors `w` (`n1 × n1`, symmetric positive definite, full or upper storage)
    /// and stores `d1` (`n2 × n1`).
    ///
    /// Errors: [`SolverError::NotSquare`], [`SolverError::DimensionMismatch`] (`d1` does not
    /// have `n1` columns), [`SolverError::NonFinite`],
    /// [`SolverError::MatrixNotPositiveDefinite`] naming `W`.
    pub(crate) fn new(w: &sprs::CsMat<f64>, d1: &sprs::CsMat<f64>) -> Result<Self, SolverError> {
        let n1 = square_dimension(w)?;
        if d1.cols() != n1 {
            return Err(SolverError::DimensionMismatch {
                context: "columns of d1 (the rows of W)",
                expected: n1,
                actual: d1.cols(),
            });
        }
        let upper = upper_triangle_csc(w)?;
        let factor = SparseLdlt::positive_definite(upper.as_ref(), "W")?;
        let mut position = vec![0usize; n1];
        for k in 0..n1 {
            position[factor.original_index(k)] = k;
        }
        let incidence = to_faer_csc(d1)?;
        let (by_edge, by_face) = ordered_incidence(incidence.as_ref(), &position)?;
        Ok(Self {
            w: factor,
            by_edge,
            by_face,
            incidence,
        })
    }

    /// `n1`, the dimension of `W`.
    pub(crate) fn inner_dimension(&self) -> usize {
        self.by_edge.ncols()
    }

    /// `d1` (`n2 × n1`) in the input order of both sides.
    pub(crate) fn incidence(&self) -> SparseColMatRef<'_, usize, f64> {
        self.incidence.as_ref()
    }

    /// `n2`, the dimension of `A`.
    pub(crate) fn dimension(&self) -> usize {
        self.by_edge.nrows()
    }

    /// `out ← A x` for a packed chunk `x` (`n2` rows), with `work` (resized to `n1` rows) for
    /// `W⁻¹ d1ᵀ x`.
    pub(crate) fn times_rows(&self, x: &[Row], out: &mut [Row], work: &mut Vec<Row>) {
        self.solve_inner(x, work);
        gather_times(self.by_face.as_ref(), work, out);
    }

    /// [`Self::times_rows`] and `magnitudes ← |d1| |W⁻¹ d1ᵀ x|` (the scale of the rounding
    /// errors of the last product; those of the solve are not included).
    pub(crate) fn times_rows_and_magnitudes(
        &self,
        x: &[Row],
        out: &mut [Row],
        magnitudes: &mut [Row],
        work: &mut Vec<Row>,
    ) {
        self.solve_inner(x, work);
        gather_times_and_magnitudes(self.by_face.as_ref(), work, out, magnitudes);
    }

    /// `xᵀ A x = (d1ᵀ x)ᵀ W⁻¹ (d1ᵀ x)` for each column of the packed chunk `x` (`n2` rows),
    /// with `work` (resized to `n1` rows) for `d1ᵀ x`: the forward half of a solve with `W`
    /// (see [`SparseLdlt::inverse_energy_rows_in_elimination_order`]), not a solve and a product.
    pub(crate) fn energy_rows(&self, x: &[Row], work: &mut Vec<Row>) -> Row {
        work.resize(self.inner_dimension(), [0.0; 8]);
        gather_times(self.by_edge.as_ref(), x, work);
        self.w.inverse_energy_rows_in_elimination_order(work)
    }

    /// `work ← W⁻¹ d1ᵀ x` (rows in `W`'s elimination order).
    fn solve_inner(&self, x: &[Row], work: &mut Vec<Row>) {
        work.resize(self.inner_dimension(), [0.0; 8]);
        gather_times(self.by_edge.as_ref(), x, work);
        self.w.solve_rows_in_elimination_order(work);
    }

    /// An estimate of the diagonal of `A`: `A_ff ≈ Σ_e d1_fe² / W_ee` (`W⁻¹` replaced by the
    /// inverse of its diagonal; a mass matrix is within a small factor of its diagonal).
    pub(crate) fn diagonal_estimate(&self, w_diagonal: &[f64]) -> Vec<f64> {
        let (col_ptr, row_idx) = (
            self.by_face.symbolic().col_ptr(),
            self.by_face.symbolic().row_idx(),
        );
        (0..self.dimension())
            .map(|f| {
                (col_ptr[f]..col_ptr[f + 1])
                    .map(|p| {
                        let e = self.w.original_index(row_idx[p]);
                        self.by_face.val()[p].powi(2) / w_diagonal[e]
                    })
                    .sum()
            })
            .collect()
    }

    /// The dense `n2 × n2` matrix `A` (the dense path of small problems only).
    pub(crate) fn dense(&self) -> Mat<f64> {
        let n2 = self.dimension();
        let by_face = self.by_face.to_dense();
        let mut x = by_face.clone();
        self.w.solve_in_elimination_order(x.as_mut());
        let a = by_face.transpose() * &x;
        Mat::from_fn(n2, n2, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]))
    }
}

/// A small mixed pencil's matrices for tests: `W` (`n1 × n1`, SPD, a banded diagonal with
/// off-diagonal entries) and `d1` (`n2 × n1`, face `f` on the edges `s·f`, `s·f + 1` and
/// `s·f + 3` modulo `n1` for the `stride` `s`), with `A = d1 W⁻¹ d1ᵀ` formed densely.
#[cfg(test)]
pub(crate) fn small_mixed_matrices(
    n1: usize,
    n2: usize,
    stride: usize,
) -> (sprs::CsMat<f64>, sprs::CsMat<f64>, Mat<f64>) {
    let mut w = sprs::TriMat::new((n1, n1));
    for i in 0..n1 {
        w.add_triplet(i, i, 3.0 + i as f64 / 3.0);
        if i + 2 < n1 {
            w.add_triplet(i, i + 2, 0.7);
            w.add_triplet(i + 2, i, 0.7);
        }
    }
    let mut d1 = sprs::TriMat::new((n2, n1));
    for f in 0..n2 {
        for (e, sign) in [
            (stride * f, 1.0),
            (stride * f + 1, -1.0),
            (stride * f + 3, 1.0),
        ] {
            d1.add_triplet(f, e % n1, sign);
        }
    }
    let (w, d1) = (w.to_csc(), d1.to_csc());
    let dense = |m: &sprs::CsMat<f64>| {
        let mut d = Mat::<f64>::zeros(m.rows(), m.cols());
        for (v, (i, j)) in m.iter() {
            d[(i, j)] += *v;
        }
        d
    };
    let (wd, dd) = (dense(&w), dense(&d1));
    let w_inverse = faer::linalg::solvers::DenseSolveCore::inverse(
        &wd.as_ref().llt(faer::Side::Lower).expect("SPD"),
    );
    let a = &dd * &w_inverse * dd.transpose();
    (w, d1, a)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `A x` by the operator equals `d1 W⁻¹ d1ᵀ x` formed densely, and a `W` with a negative
    /// eigenvalue is rejected by name.
    #[test]
    fn operator_is_d1_w_inverse_d1_transposed() {
        let (n1, n2) = (7, 4);
        let (w, d1, expected) = small_mixed_matrices(n1, n2, 1);
        let operator = MixedOperator::new(&w, &d1).expect("W is SPD");
        assert!((operator.dense() - &expected).norm_max() <= 1e-13 * expected.norm_max());
        let x: Vec<Row> = (0..n2)
            .map(|i| std::array::from_fn(|j| ((i * 3 + j) % 5) as f64 - 2.0))
            .collect();
        let (mut out, mut work) = (vec![[0.0; 8]; n2], Vec::new());
        operator.times_rows(&x, &mut out, &mut work);
        for i in 0..n2 {
            for j in 0..8 {
                let e: f64 = (0..n2).map(|k| expected[(i, k)] * x[k][j]).sum();
                assert!((out[i][j] - e).abs() <= 1e-12 * expected.norm_max());
            }
        }
        let mut bad = sprs::TriMat::new((n1, n1));
        for i in 0..n1 {
            bad.add_triplet(i, i, if i == 3 { -1.0 } else { 1.0 });
        }
        match MixedOperator::new(&bad.to_csc(), &d1) {
            Err(SolverError::MatrixNotPositiveDefinite { matrix: "W", .. }) => {}
            other => panic!("expected W to be rejected, got {:?}", other.err()),
        }
    }
}
