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
//! sparse product `A Q` and three `n × s × s` dense products per slice.

use super::symmetric_products::{gather_times, map_column_chunks, CHUNK};
use super::tall_products::{mass_inner, tall_inner, tall_times_in_place};
use crate::dense_eigen::symmetric_eigen;
use crate::error::SolverError;
use faer::sparse::SparseColMatRef;
use faer::{Mat, MatRef, Par};

/// Rayleigh–Ritz of the `n × s` block `x` (columns nearly M-orthonormal) for `A y = λ M y`,
/// in place: `x` becomes the Ritz vectors, and no other `n × s` matrix is allocated (`A Q` is
/// formed and projected a chunk of columns at a time).
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
    mut x: Mat<f64>,
    par: Par,
) -> Result<(Vec<f64>, Mat<f64>), SolverError> {
    let s = x.ncols();
    if s == 0 {
        return Ok((Vec::new(), x));
    }
    // Q = X L⁻ᵀ with XᵀMX = L Lᵀ: exact M-orthonormalisation of a nearly orthonormal block
    // (L is close to the identity, so its explicit inverse is accurate).
    let gram = mass_inner(x.as_ref(), mass, x.as_ref(), par);
    let gram = Mat::from_fn(s, s, |i, j| 0.5 * (gram[(i, j)] + gram[(j, i)]));
    let llt = gram
        .as_ref()
        .llt(faer::Side::Lower)
        .map_err(|_| SolverError::NoConvergence {
            reason: "locked eigenvectors of a slice are linearly dependent".into(),
        })?;
    let mut l_inverse = Mat::<f64>::identity(s, s);
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(
        llt.L(),
        l_inverse.as_mut(),
        Par::Seq,
    );
    tall_times_in_place(x.as_mut(), l_inverse.transpose(), par);
    let t = projected(a, x.as_ref(), par);
    let t = Mat::from_fn(s, s, |i, j| 0.5 * (t[(i, j)] + t[(j, i)]));
    let (values, w) = symmetric_eigen(t.as_ref())?;
    tall_times_in_place(x.as_mut(), w.as_ref(), par);
    Ok((values, x))
}

/// `Qᵀ A Q` (`s × s`) for the `n × s` block `q`, a chunk of columns of `A Q` at a time.
fn projected(a: SparseColMatRef<'_, usize, f64>, q: MatRef<'_, f64>, par: Par) -> Mat<f64> {
    let n = q.nrows();
    let chunks = map_column_chunks(q, par, |first, width, rows| {
        let mut product = vec![[0.0; CHUNK]; n];
        gather_times(a, rows, &mut product);
        let aq = Mat::from_fn(n, width, |i, j| product[i][j]);
        (first, tall_inner(q, aq.as_ref(), Par::Seq))
    });
    let mut t = Mat::<f64>::zeros(q.ncols(), q.ncols());
    for (first, block) in chunks {
        t.as_mut()
            .subcols_mut(first, block.ncols())
            .copy_from(&block);
    }
    t
}
