//! Refinement of eigenpairs whose residual misses a target: one step of inverse iteration with
//! the factorization of the interval that found them, then a Rayleigh–Ritz against `A`.
//!
//! Why: for a pencil `A = Dᵀ W D` (a gradient `D`, a diagonal weight `W`; the potential and
//! co-potential problems of a Hodge complex are of this form), Lemma 1 of Brandt et al. maps an
//! eigenpair `(λ, x)` to the eigenfield `D x / √λ` of the Hodge–Laplacian, whose residual is
//! `√(sᵀ A s / λ)` with `s = M⁻¹ (A x − λ M x)` ([`field_residuals`]). The gradient amplifies the
//! high-frequency part of `r = A x − λ M x` (by about 1/h), so a Krylov pair converged to `1e-12`
//! in the shift-inverted metric can still show `1e-8` in the field. One step
//! `z = (A − σM)⁻¹ M x` at the interval's own shift σ (no new factorization) damps every component
//! of eigenvalue `λ_m` by `|λ − σ| / |λ_m − σ|`, tiny for high frequencies since σ lies within
//! half an interval of `λ`; the Rayleigh–Ritz on the interval's span then restores `A`- and
//! `M`-orthogonality inside clusters.

use super::rayleigh_ritz::rayleigh_ritz;
use super::tall_products::mass_inner;
use crate::error::SolverError;
use crate::sparse_ldlt::SparseLdlt;
use faer::sparse::linalg::matmul::sparse_dense_matmul;
use faer::sparse::SparseColMatRef;
use faer::{Accum, Mat, MatRef, Par};

/// Relative eigenfield residuals `√(sᵀ A s / λ) / λ`, `s = M⁻¹ (A x − λ M x)`, of the `n × s`
/// M-orthonormal `vectors` (see the module documentation), and the rounding floor of each: the
/// same expression for the rounding error of `s` itself, `δs_i ≈ ε (|A| |x|)_i / M_ii` with
/// random signs (`δsᵀ A δs ≈ Σ_i A_ii δs_i²`). On meshes with slivers (tiny `M_ii`) the floor
/// can exceed any target: no `f64` vector shows a smaller residual. Both are `0` for eigenvalues
/// at most `floor` (the kernel, which has no eigenfield).
pub(crate) fn field_residuals(
    a: SparseColMatRef<'_, usize, f64>,
    mass: &[f64],
    values: &[f64],
    vectors: MatRef<'_, f64>,
    floor: f64,
    par: Par,
) -> Vec<FieldResidual> {
    let (n, s) = (vectors.nrows(), vectors.ncols());
    let mut ax = Mat::<f64>::zeros(n, s);
    sparse_dense_matmul(ax.as_mut(), Accum::Replace, a, vectors, 1.0, par);
    // s = M⁻¹ A x − λ x, in place.
    for j in 0..s {
        for i in 0..n {
            ax[(i, j)] = ax[(i, j)] / mass[i] - values[j] * vectors[(i, j)];
        }
    }
    let mut as_ = Mat::<f64>::zeros(n, s);
    sparse_dense_matmul(as_.as_mut(), Accum::Replace, a, ax.as_ref(), 1.0, par);
    // |A| |x| and the diagonal of A, for the floor.
    let col_ptr = a.symbolic().col_ptr();
    let row_idx = a.symbolic().row_idx();
    let mut abs_ax = Mat::<f64>::zeros(n, s);
    let mut diagonal = vec![0.0; n];
    for c in 0..n {
        for p in col_ptr[c]..col_ptr[c + 1] {
            let (r, v) = (row_idx[p], a.val()[p]);
            if r == c {
                diagonal[c] = v;
            }
            for j in 0..s {
                abs_ax[(r, j)] += v.abs() * vectors[(c, j)].abs();
            }
        }
    }
    (0..s)
        .map(|j| {
            let lambda = values[j];
            if lambda <= floor {
                return FieldResidual::default();
            }
            let energy: f64 = (0..n).map(|i| ax[(i, j)] * as_[(i, j)]).sum();
            let noise: f64 = (0..n)
                .map(|i| {
                    let e =
                        f64::EPSILON * (abs_ax[(i, j)] / mass[i] + lambda * vectors[(i, j)].abs());
                    diagonal[i].max(0.0) * e * e
                })
                .sum();
            FieldResidual {
                residual: (energy.max(0.0) / lambda).sqrt() / lambda,
                floor: (noise / lambda).sqrt() / lambda,
            }
        })
        .collect()
}

/// A relative eigenfield residual and its rounding floor (see [`field_residuals`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct FieldResidual {
    pub residual: f64,
    pub floor: f64,
}

impl FieldResidual {
    /// Whether refinement could help: above `target` and clearly above the rounding floor.
    pub(crate) fn misses(&self, target: f64) -> bool {
        self.residual > target && self.residual > FLOOR_MARGIN * self.floor
    }
}

/// How far above its rounding floor a residual must be for refinement to be worth a solve.
const FLOOR_MARGIN: f64 = 10.0;

/// Refines the columns `which` of the `n × s` eigenvectors `vectors` (M-orthonormal, one
/// interval's) with `factor = LDLᵀ(A − σM)`: `z = (A − σM)⁻¹ M x`, M-normalised, replaces `x`,
/// and a Rayleigh–Ritz against `A` on the span of all `s` columns gives the new ascending values
/// and M-orthonormal vectors.
///
/// Errors: [`SolverError::NoConvergence`] if the refined columns become dependent.
pub(crate) fn refine_columns(
    a: SparseColMatRef<'_, usize, f64>,
    mass: &[f64],
    factor: &SparseLdlt,
    vectors: MatRef<'_, f64>,
    which: &[usize],
    par: Par,
) -> Result<(Vec<f64>, Mat<f64>), SolverError> {
    let n = vectors.nrows();
    let mut z = Mat::from_fn(n, which.len(), |i, j| mass[i] * vectors[(i, which[j])]);
    factor.solve_in_place(z.as_mut());
    let norms = mass_inner(z.as_ref(), mass, z.as_ref(), par);
    let mut refined = vectors.to_owned();
    for (j, &column) in which.iter().enumerate() {
        let norm = norms[(j, j)].sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return Err(SolverError::NoConvergence {
                reason: "an inverse-iteration step of the refinement lost its vector".into(),
            });
        }
        // Keep the sign of x (z ≈ x/(λ − σ) points either way).
        let sign = if mass_inner(
            vectors.subcols(column, 1),
            mass,
            z.as_ref().subcols(j, 1),
            Par::Seq,
        )[(0, 0)]
            < 0.0
        {
            -1.0
        } else {
            1.0
        };
        for i in 0..n {
            refined[(i, column)] = sign * z[(i, j)] / norm;
        }
    }
    rayleigh_ritz(a, mass, refined.as_ref(), par)
}

/// Whether an inverse-iteration step with `factor` halves the field residual `before` of column
/// `column` of `vectors`: one solve and no Rayleigh–Ritz, to find out before refining a whole
/// interval. On meshes with slivers the residual of every pair sits at the accuracy of the
/// solves themselves, which no step improves.
pub(crate) fn step_helps(
    a: SparseColMatRef<'_, usize, f64>,
    mass: &[f64],
    factor: &SparseLdlt,
    vectors: MatRef<'_, f64>,
    column: usize,
    before: f64,
    floor: f64,
) -> bool {
    let n = vectors.nrows();
    let mut z = Mat::from_fn(n, 1, |i, _| mass[i] * vectors[(i, column)]);
    factor.solve_in_place(z.as_mut());
    let norm = mass_inner(z.as_ref(), mass, z.as_ref(), Par::Seq)[(0, 0)].sqrt();
    if !(norm.is_finite() && norm > 0.0) {
        return false;
    }
    z.col_mut(0).iter_mut().for_each(|x| *x /= norm);
    let mut az = Mat::<f64>::zeros(n, 1);
    sparse_dense_matmul(az.as_mut(), Accum::Replace, a, z.as_ref(), 1.0, Par::Seq);
    let rayleigh: f64 = (0..n).map(|i| z[(i, 0)] * az[(i, 0)]).sum();
    let after = field_residuals(a, mass, &[rayleigh], z.as_ref(), floor, Par::Seq);
    after.first().is_some_and(|r| r.residual < 0.5 * before)
}
