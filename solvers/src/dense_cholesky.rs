//! Dense Cholesky factorization `A = L Lᵀ` with O(n²) modifications: rank-one update and
//! downdate, and bordered updates (append or remove a row and column). Used by sessions that
//! grow or shrink a small SPD system one constraint at a time (splines, soft design).
//!
//! The arithmetic is faer's: its `LLᵀ` factorization, its rank update of the factor (for the
//! updates, the downdate and the removal of a row and column) and its triangular solves (for
//! the solves and the new row of a bordered factor, which faer 0.24 does not insert). This
//! type keeps the factor, checks its input, keeps the factor unchanged when an update fails,
//! and turns faer's failures into [`SolverError`]s.

use crate::error::SolverError;
use faer::linalg::cholesky::llt::factor::LltError;
use faer::linalg::cholesky::llt::update;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::reborrow::ReborrowMut;
use faer::{Col, Mat, MatMut, MatRef, Par, Side};

/// Lower-triangular Cholesky factor `L` of a dense symmetric positive-definite `n × n` matrix.
#[derive(Debug, Clone)]
pub struct DenseCholesky {
    l: Mat<f64>,
}

fn check_len(context: &'static str, expected: usize, actual: usize) -> Result<(), SolverError> {
    if expected == actual {
        Ok(())
    } else {
        Err(SolverError::DimensionMismatch {
            context,
            expected,
            actual,
        })
    }
}

fn check_finite(context: &'static str, v: &[f64]) -> Result<(), SolverError> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(row) => Err(SolverError::NonFinite {
            context,
            row,
            col: 0,
            value: v[row],
        }),
        None => Ok(()),
    }
}

impl DenseCholesky {
    /// Factors a dense symmetric positive-definite matrix (only the lower triangle is read).
    ///
    /// Errors: [`SolverError::NotSquare`], [`SolverError::NonFinite`],
    /// [`SolverError::NotPositiveDefinite`].
    pub fn new(a: MatRef<'_, f64>) -> Result<Self, SolverError> {
        let n = a.nrows();
        if a.ncols() != n {
            return Err(SolverError::NotSquare {
                rows: n,
                cols: a.ncols(),
            });
        }
        for j in 0..n {
            for i in j..n {
                if !a[(i, j)].is_finite() {
                    return Err(SolverError::NonFinite {
                        context: "dense matrix",
                        row: i,
                        col: j,
                        value: a[(i, j)],
                    });
                }
            }
        }
        if n == 0 {
            return Ok(Self {
                l: Mat::zeros(0, 0),
            });
        }
        let llt = a.llt(Side::Lower).map_err(|e| match e {
            LltError::NonPositivePivot { index } => SolverError::NotPositiveDefinite {
                pivot: index,
                value: f64::NAN,
            },
        })?;
        Ok(Self {
            l: llt.L().to_owned(),
        })
    }

    /// Dimension `n`.
    pub fn dimension(&self) -> usize {
        self.l.nrows()
    }

    /// The lower-triangular factor `L` (`n × n`, `A = L Lᵀ`).
    pub fn factor(&self) -> MatRef<'_, f64> {
        self.l.as_ref()
    }

    /// Replaces the factored matrix `A` by `A + v vᵀ` (always SPD). O(n²).
    ///
    /// Errors: [`SolverError::DimensionMismatch`], [`SolverError::NonFinite`].
    pub fn rank_one_update(&mut self, v: &[f64]) -> Result<(), SolverError> {
        check_len("rank_one_update vector", self.dimension(), v.len())?;
        check_finite("rank_one_update vector", v)?;
        let mut l = self.l.clone();
        rank_one_update(l.as_mut(), v, 1.0)?;
        self.l = l;
        Ok(())
    }

    /// Replaces `A` by `A − v vᵀ`. O(n²). Fails, leaving the factorization unchanged, if the
    /// result would not be positive definite (`vᵀ A⁻¹ v ≥ 1`).
    ///
    /// Errors: [`SolverError::DimensionMismatch`], [`SolverError::NonFinite`],
    /// [`SolverError::NotPositiveDefinite`].
    pub fn rank_one_downdate(&mut self, v: &[f64]) -> Result<(), SolverError> {
        let n = self.dimension();
        check_len("rank_one_downdate vector", n, v.len())?;
        check_finite("rank_one_downdate vector", v)?;
        let mut p = v.to_vec();
        self.forward_substitute(&mut p);
        let norm2: f64 = p.iter().map(|x| x * x).sum();
        if norm2 >= 1.0 - 1e-14 {
            return Err(SolverError::NotPositiveDefinite {
                pivot: n.saturating_sub(1),
                value: 1.0 - norm2,
            });
        }
        let mut l = self.l.clone();
        rank_one_update(l.as_mut(), v, -1.0)?;
        self.l = l;
        Ok(())
    }

    /// Borders `A` with a new last row and column: `column` has length `n + 1` and holds the
    /// new column including its diagonal entry (last). O(n²).
    ///
    /// Errors: [`SolverError::DimensionMismatch`], [`SolverError::NonFinite`],
    /// [`SolverError::NotPositiveDefinite`] (pivot `n`) if the bordered matrix is not SPD.
    pub fn append(&mut self, column: &[f64]) -> Result<(), SolverError> {
        let n = self.dimension();
        check_len("append column (n + 1 entries)", n + 1, column.len())?;
        check_finite("append column", column)?;
        // The new row of L is L⁻¹ a (a: the column above its diagonal), its diagonal entry
        // √(a_nn − ‖L⁻¹ a‖²).
        let mut row = column[..n].to_vec();
        self.forward_substitute(&mut row);
        let d2 = column[n] - row.iter().map(|x| x * x).sum::<f64>();
        if d2 <= 0.0 {
            return Err(SolverError::NotPositiveDefinite {
                pivot: n,
                value: d2,
            });
        }
        let diagonal = d2.sqrt();
        self.l
            .resize_with(n + 1, n + 1, |i, j| match (i == n, j == n) {
                (true, true) => diagonal,
                (true, false) => row[j],
                _ => 0.0,
            });
        Ok(())
    }

    /// Removes row and column `index` from `A`: the factor of the remaining matrix is `L`
    /// without them, its trailing block updated by the removed column's part below the
    /// diagonal. O((n − index)²) plus a copy.
    ///
    /// Errors: [`SolverError::DimensionMismatch`] if `index ≥ n`.
    pub fn remove(&mut self, index: usize) -> Result<(), SolverError> {
        let n = self.dimension();
        if index >= n {
            return Err(SolverError::DimensionMismatch {
                context: "remove index (must be < n)",
                expected: n,
                actual: index,
            });
        }
        let keep = |i: usize| if i < index { i } else { i + 1 };
        let mut l = Mat::from_fn(n - 1, n - 1, |i, j| self.l[(keep(i), keep(j))]);
        let removed: Vec<f64> = (index + 1..n).map(|i| self.l[(i, index)]).collect();
        let trailing = n - 1 - index;
        rank_one_update(
            l.as_mut().submatrix_mut(index, index, trailing, trailing),
            &removed,
            1.0,
        )?;
        self.l = l;
        Ok(())
    }

    /// Solves `A x = rhs`.
    ///
    /// Errors: [`SolverError::DimensionMismatch`].
    pub fn solve(&self, rhs: &[f64]) -> Result<Vec<f64>, SolverError> {
        let mut x = rhs.to_vec();
        self.solve_in_place(&mut x)?;
        Ok(x)
    }

    /// Overwrites `rhs` with `A⁻¹ rhs`.
    ///
    /// Errors: [`SolverError::DimensionMismatch`].
    pub fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), SolverError> {
        let n = self.dimension();
        check_len("solve right-hand side", n, rhs.len())?;
        let mut x = MatMut::from_column_major_slice_mut(rhs, n, 1);
        solve_lower_triangular_in_place(self.l.as_ref(), x.rb_mut(), Par::Seq);
        solve_upper_triangular_in_place(self.l.transpose(), x, Par::Seq);
        Ok(())
    }

    /// `x ← L⁻¹ x`.
    fn forward_substitute(&self, x: &mut [f64]) {
        let n = self.dimension();
        let x = MatMut::from_column_major_slice_mut(x, n, 1);
        solve_lower_triangular_in_place(self.l.as_ref(), x, Par::Seq);
    }
}

/// `L ← chol(L Lᵀ + alpha · v vᵀ)` in place (faer's rank-one update of a Cholesky factor).
///
/// Errors: [`SolverError::NotPositiveDefinite`] when rounding leaves a pivot that is not
/// positive (`L` is then clobbered: callers update a copy).
fn rank_one_update(l: MatMut<'_, f64>, v: &[f64], alpha: f64) -> Result<(), SolverError> {
    let mut w = Mat::from_fn(v.len(), 1, |i, _| v[i]);
    let mut alpha = Col::from_fn(1, |_| alpha);
    update::rank_r_update_clobber(l, w.as_mut(), alpha.as_mut().as_diagonal_mut()).map_err(|e| {
        match e {
            LltError::NonPositivePivot { index } => SolverError::NotPositiveDefinite {
                pivot: index,
                value: f64::NAN,
            },
        }
    })
}
