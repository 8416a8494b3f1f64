//! [`BorderedCholesky`]: a small dense Cholesky factor `K = L Lᵀ` that grows and shrinks by one
//! row and column at a time (the Schur complement `C D⁻¹ Cᵀ` of a spline session).

use faer::linalg::cholesky::llt::update::rank_r_update_clobber;
use faer::{Col, Mat};

/// Result of trying to append a row and column to the factor.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Append {
    /// Appended.
    Added,
    /// Not appended: the new row is (numerically) a combination of the existing ones.
    /// `coefficients` solve `K y = b` (the new row ≈ `Σ y_i row_i`), `relative_pivot` is
    /// `(γ − |l|²)/γ`.
    Dependent {
        coefficients: Vec<f64>,
        relative_pivot: f64,
    },
}

/// Lower-triangular `L` (`n × n`) with `K = L Lᵀ`; `n` changes by bordered appends (`O(n²)`)
/// and removals (a rank-one update of the trailing block, `O((n−j)²)`); never refactored.
#[derive(Debug, Clone)]
pub(crate) struct BorderedCholesky {
    factor: Mat<f64>,
}

impl Default for BorderedCholesky {
    fn default() -> Self {
        Self {
            factor: Mat::zeros(0, 0),
        }
    }
}

impl BorderedCholesky {
    pub(crate) fn len(&self) -> usize {
        self.factor.nrows()
    }

    /// Appends the row/column `[bᵀ, γ]` to `K` (`b` has `n` entries, `γ > 0`): solves `L l = b`,
    /// new pivot `√(γ − |l|²)`. Rejects the append when `γ − |l|² ≤ tolerance · γ`.
    pub(crate) fn append(&mut self, b: &[f64], gamma: f64, tolerance: f64) -> Append {
        let n = self.len();
        debug_assert_eq!(b.len(), n);
        let mut l = b.to_vec();
        for i in 0..n {
            let mut s = l[i];
            for (k, lk) in l.iter().enumerate().take(i) {
                s -= self.factor[(i, k)] * lk;
            }
            l[i] = s / self.factor[(i, i)];
        }
        let square = gamma - l.iter().map(|x| x * x).sum::<f64>();
        let relative_pivot = square / gamma;
        if !(gamma > 0.0 && relative_pivot > tolerance) {
            let mut y = l;
            self.back_substitute(&mut y);
            return Append::Dependent {
                coefficients: y,
                relative_pivot: relative_pivot.max(0.0),
            };
        }
        let mut grown = Mat::zeros(n + 1, n + 1);
        grown.as_mut().submatrix_mut(0, 0, n, n).copy_from(self.factor.as_ref());
        for (k, lk) in l.iter().enumerate() {
            grown[(n, k)] = *lk;
        }
        grown[(n, n)] = square.sqrt();
        self.factor = grown;
        Append::Added
    }

    /// Removes row and column `j` of `K`: `L33' L33'ᵀ = L33 L33ᵀ + l32 l32ᵀ` (rank-one update).
    pub(crate) fn remove(&mut self, j: usize) {
        let n = self.len();
        debug_assert!(j < n);
        let keep: Vec<usize> = (0..n).filter(|&i| i != j).collect();
        let mut shrunk = Mat::from_fn(n - 1, n - 1, |r, c| {
            if c <= r {
                self.factor[(keep[r], keep[c])]
            } else {
                0.0
            }
        });
        let tail = n - 1 - j;
        if tail > 0 {
            let mut w = Mat::from_fn(tail, 1, |r, _| self.factor[(j + 1 + r, j)]);
            let mut alpha = Col::from_fn(1, |_| 1.0);
            let trailing = shrunk.as_mut().submatrix_mut(j, j, tail, tail);
            // A positive rank-one update of a valid factor cannot fail.
            let _ = rank_r_update_clobber(trailing, w.as_mut(), alpha.as_mut().as_diagonal_mut());
        }
        self.factor = shrunk;
    }

    /// Solves `K y = rhs` in place.
    pub(crate) fn solve(&self, rhs: &mut [f64]) {
        let n = self.len();
        for i in 0..n {
            let mut s = rhs[i];
            for (k, rk) in rhs.iter().enumerate().take(i) {
                s -= self.factor[(i, k)] * rk;
            }
            rhs[i] = s / self.factor[(i, i)];
        }
        self.back_substitute(rhs);
    }

    /// Solves `Lᵀ y = rhs` in place.
    fn back_substitute(&self, rhs: &mut [f64]) {
        let n = self.len();
        for i in (0..n).rev() {
            let mut s = rhs[i];
            for (k, rk) in rhs.iter().enumerate().skip(i + 1) {
                s -= self.factor[(k, i)] * rk;
            }
            rhs[i] = s / self.factor[(i, i)];
        }
    }
}
