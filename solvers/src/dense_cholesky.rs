//! Dense Cholesky factorization `A = L Lᵀ` with O(n²) modifications: rank-one update and
//! downdate, and bordered updates (append or remove a row and column). Used by sessions that
//! grow or shrink a small SPD system one constraint at a time (splines, soft design).

use crate::error::SolverError;
use faer::{Mat, MatRef, Side};

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
            faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
                SolverError::NotPositiveDefinite {
                    pivot: index,
                    value: f64::NAN,
                }
            }
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
        update_in_place(&mut self.l, 0, v.to_vec());
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
        let mut x = v.to_vec();
        for k in 0..n {
            let lkk = self.l[(k, k)];
            let r2 = lkk * lkk - x[k] * x[k];
            if r2 <= 0.0 {
                // excluded by the check above except for rounding at the very edge
                return Err(SolverError::NotPositiveDefinite {
                    pivot: k,
                    value: r2,
                });
            }
            let r = r2.sqrt();
            let c = r / lkk;
            let s = x[k] / lkk;
            self.l[(k, k)] = r;
            for i in k + 1..n {
                let lik = (self.l[(i, k)] - s * x[i]) / c;
                x[i] = c * x[i] - s * lik;
                self.l[(i, k)] = lik;
            }
        }
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
        let mut row = column[..n].to_vec();
        self.forward_substitute(&mut row);
        let d2 = column[n] - row.iter().map(|x| x * x).sum::<f64>();
        if d2 <= 0.0 {
            return Err(SolverError::NotPositiveDefinite {
                pivot: n,
                value: d2,
            });
        }
        let mut l = Mat::<f64>::zeros(n + 1, n + 1);
        l.as_mut().submatrix_mut(0, 0, n, n).copy_from(&self.l);
        for (j, value) in row.iter().enumerate() {
            l[(n, j)] = *value;
        }
        l[(n, n)] = d2.sqrt();
        self.l = l;
        Ok(())
    }

    /// Removes row and column `index` from `A` (the factor of the remaining matrix is obtained
    /// with a rank-one update of the trailing block). O((n − index)²) plus a copy.
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
        let v: Vec<f64> = (index + 1..n).map(|i| self.l[(i, index)]).collect();
        update_in_place(&mut l, index, v);
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
        self.forward_substitute(rhs);
        for i in (0..n).rev() {
            let mut sum = rhs[i];
            for k in i + 1..n {
                sum -= self.l[(k, i)] * rhs[k];
            }
            rhs[i] = sum / self.l[(i, i)];
        }
        Ok(())
    }

    /// `x ← L⁻¹ x`.
    fn forward_substitute(&self, x: &mut [f64]) {
        let n = self.dimension();
        for j in 0..n {
            x[j] /= self.l[(j, j)];
            let xj = x[j];
            for i in j + 1..n {
                x[i] -= self.l[(i, j)] * xj;
            }
        }
    }
}

/// Rank-one update `L Lᵀ + v vᵀ` of the trailing block `L[start.., start..]`, where `v` has
/// length `n − start` (Givens-like hyperbolic-free update, always stable).
fn update_in_place(l: &mut Mat<f64>, start: usize, mut x: Vec<f64>) {
    let n = l.nrows();
    for k in start..n {
        let xk = x[k - start];
        let lkk = l[(k, k)];
        let r = lkk.hypot(xk);
        let c = r / lkk;
        let s = xk / lkk;
        l[(k, k)] = r;
        for i in k + 1..n {
            let lik = (l[(i, k)] + s * x[i - start]) / c;
            x[i - start] = c * x[i - start] - s * lik;
            l[(i, k)] = lik;
        }
    }
}
