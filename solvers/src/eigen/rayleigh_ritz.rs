//! Final Rayleigh–Ritz of a slice's locked eigenvectors against the *original* pencil `(A, M)`.
//!
//! Why it is needed: the Krylov–Schur slice resolves the Ritz values `θ` of the shift-inverted
//! operator `OP = (A − σM)⁻¹M` only to an absolute accuracy of about `ε‖H‖ ≈ ε·max|θ|`
//! (dense eigen-decomposition of the projected `H`, Gram–Schmidt, and the dropped rounding-level
//! couplings `Dᵀ M OP V` with deflated/locked vectors all scale with the largest `|θ|` present).
//! When the slice holds an eigenvalue very close to σ — always the case in the first slice,
//! whose shift sits at `−10⁻⁷·trace(A)/trace(M)`, next to the zero eigenvalue(s) — `max|θ|` is
//! `10⁶`–`10⁷` times the `|θ|` of the slice's far end, so those Ritz vectors carry errors of
//! relative size `ε·max|θ|/|θ| ≈ 10⁻¹⁰` that the Krylov residual estimate `‖G y‖` cannot see (it
//! is evaluated for the computed `y`). In an exactly degenerate eigenspace (the icosahedral
//! triples/quintuples inside a sphere's `2l+1` cluster) this shows up as a "ghost" pair of
//! Rayleigh quotients `10⁻⁸` too high with true residuals `3·10⁻¹¹‖A‖‖x‖`, and the polluted
//! vectors then pollute the next slice through deflation.
//!
//! The cure is to take the *span* of the locked vectors, which is accurate (each locked vector
//! is an accurate member of the invariant subspace up to mixing inside it and the rounding-level
//! components above), and re-extract eigenpairs from it with `A` itself: `Q = X R⁻¹`
//! (M-orthonormal), `T = Qᵀ A Q` (`s × s`), `T = W Λ Wᵀ`, `X ← Q W`. Rayleigh–Ritz against `A`
//! is accurate to `ε‖A‖` in the eigenvalues and has no `1/θ` amplification; within a cluster it
//! diagonalises `A` exactly, so degenerate eigenvalues come out equal to rounding. Its cost is one
//! sparse product `A Q` and two `n × s × s` dense products per slice.

use super::symmetric_products::symmetric_times;
use super::tall_products::{mass_inner, tall_inner, tall_times};
use crate::dense_eigen::symmetric_eigen;
use crate::error::SolverError;
use faer::sparse::SparseColMatRef;
use faer::{Accum, Mat, MatRef, Par};

/// Rayleigh–Ritz of the `n × s` block `x` (columns nearly M-orthonormal) for `A y = λ M y`.
///
/// - `a`: `n × n` sparse symmetric matrix in full (both triangles) storage.
/// - `mass`: diagonal of `M` (`n` positive entries).
///
/// Returns `s` ascending Ritz values and the `n × s` M-orthonormal Ritz vectors (spanning the
/// same space as `x`).
///
/// Errors: [`SolverError::NoConvergence`] if the columns of `x` are numerically dependent.
pub(crate) fn rayleigh_ritz(
    a: SparseColMatRef<'_, usize, f64>,
    mass: &[f64],
    x: MatRef<'_, f64>,
    par: Par,
) -> Result<(Vec<f64>, Mat<f64>), SolverError> {
    let (n, s) = (x.nrows(), x.ncols());
    if s == 0 {
        return Ok((Vec::new(), Mat::zeros(n, 0)));
    }
    // Q = X L⁻ᵀ with XᵀMX = L Lᵀ: exact M-orthonormalisation of a nearly orthonormal block.
    let gram = mass_inner(x, mass, x, par);
    let gram = Mat::from_fn(s, s, |i, j| 0.5 * (gram[(i, j)] + gram[(j, i)]));
    let llt = gram
        .as_ref()
        .llt(faer::Side::Lower)
        .map_err(|_| SolverError::NoConvergence {
            reason: "locked eigenvectors of a slice are linearly dependent".into(),
        })?;
    let mut q_t = x.transpose().to_owned();
    // Lᵀ-solve from the left on Xᵀ: Qᵀ = L⁻¹ Xᵀ.
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(llt.L(), q_t.as_mut(), par);
    let q = q_t.transpose().to_owned();
    let mut aq = Mat::<f64>::zeros(n, s);
    symmetric_times(aq.as_mut(), a, q.as_ref(), par);
    let t = tall_inner(q.as_ref(), aq.as_ref(), par);
    let t = Mat::from_fn(s, s, |i, j| 0.5 * (t[(i, j)] + t[(j, i)]));
    let (values, w) = symmetric_eigen(t.as_ref())?;
    let mut vectors = Mat::<f64>::zeros(n, s);
    tall_times(
        vectors.as_mut(),
        Accum::Replace,
        q.as_ref(),
        w.as_ref(),
        1.0,
        par,
    );
    Ok((values, vectors))
}
