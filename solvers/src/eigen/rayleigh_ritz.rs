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
//! components above), and re-extract eigenpairs from it with `A` itself: `Q = X L⁻ᵀ`
//! (M-orthonormal, `XᵀMX = L Lᵀ`), `T = Qᵀ A Q = L⁻¹ (Xᵀ A X) L⁻ᵀ` (`s × s`), `T = W Λ Wᵀ`,
//! `X ← Q W = X (L⁻ᵀ W)`. Rayleigh–Ritz against `A`
//! is accurate to `ε‖A‖` in the eigenvalues and has no `1/θ` amplification; within a cluster it
//! diagonalises `A` exactly, so degenerate eigenvalues come out equal to rounding. Its cost is one
//! sparse product `A X` and, per slice, the upper block triangles of `XᵀMX` and `XᵀAX` (half an
//! `n × s × s` product each) and the rotation (one).

use super::mass::Mass;
use super::stiffness::Stiffness;
use super::symmetric_products::{pack_into, CHUNK};
use super::tall_products::{mass_inner, tall_inner, tall_times_in_place};
use crate::error::SolverError;
use crate::symmetric_eigen::symmetric_eigen;
use faer::reborrow::Reborrow;
use faer::{Mat, MatMut, MatRef, Par};
use rayon::prelude::*;
use std::sync::{Mutex, PoisonError};

/// Rayleigh–Ritz of the `n × s` block `x` (columns nearly M-orthonormal) for `A y = λ M y`,
/// in place: `x` becomes the M-orthonormal Ritz vectors (spanning the same space), and no other
/// `n × s` matrix is allocated (`A X` is formed and projected [`PROJECTED_COLUMNS`] columns at a
/// time).
///
/// - `a`: the `n × n` symmetric `A` (sparse, or the mixed operator).
/// - `mass`: `M` (diagonal or sparse SPD).
/// - `scratch`: idle memory (stale values; a finished slice's Krylov basis) for the `n`-row
///   buffers of the product `A X`, [`GROUP_BUFFER_COLUMNS`] columns of `n` per group formed at
///   the same time; groups that find none left allocate their own. At a million faces the
///   allocated ones were 0.8 GB beside the slice's memory, at the peak of the run
///   (`docs/performance.md`).
///
/// Returns the `s` ascending Ritz values, in the order of the columns of `x`.
///
/// Errors: [`SolverError::NoConvergence`] if the columns of `x` are numerically dependent.
pub(crate) fn rayleigh_ritz(
    a: Stiffness<'_>,
    mass: Mass<'_>,
    x: MatMut<'_, f64>,
    scratch: &mut [f64],
    par: Par,
) -> Result<Vec<f64>, SolverError> {
    let s = x.ncols();
    if s == 0 {
        return Ok(Vec::new());
    }
    // Q = X L⁻ᵀ with XᵀMX = L Lᵀ is M-orthonormal (L is close to the identity for a nearly
    // orthonormal block, so its explicit inverse is accurate), and Qᵀ A Q = L⁻¹ (Xᵀ A X) L⁻ᵀ:
    // Q is never formed, and X is rotated once, by L⁻ᵀ W.
    let gram = mass_gram(x.rb(), mass, par);
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
    let t = &l_inverse * projected(a, x.rb(), scratch, par) * l_inverse.transpose();
    let t = Mat::from_fn(s, s, |i, j| 0.5 * (t[(i, j)] + t[(j, i)]));
    let (values, w) = symmetric_eigen(t.as_ref())?;
    let rotation = l_inverse.transpose() * &w;
    tall_times_in_place(x, rotation.as_ref(), par);
    Ok(values)
}

/// Columns of `A Q` formed at a time by [`projected`]: wide enough that `Qᵀ (A Q)` reads `Q`
/// once per 32 columns, not once per packed chunk of 8.
const PROJECTED_COLUMNS: usize = 4 * CHUNK;

/// `Xᵀ M X` (`s × s`) for the `n × s` block `x`, from its upper block triangle (see
/// [`symmetric_from_upper`]).
fn mass_gram(x: MatRef<'_, f64>, mass: Mass<'_>, par: Par) -> Mat<f64> {
    let s = x.ncols();
    let groups: Vec<usize> = (0..s).step_by(PROJECTED_COLUMNS).collect();
    let blocks = groups
        .iter()
        .map(|&first| {
            let width = PROJECTED_COLUMNS.min(s - first);
            let upper = x.subcols(0, first + width);
            (first, mass_inner(upper, mass, x.subcols(first, width), par))
        })
        .collect();
    symmetric_from_upper(s, blocks)
}

/// The symmetric `s × s` matrix whose columns `first..first + width` have the rows
/// `0..first + width` given in `blocks` (`(first, (first + width) × width)`): every entry on and
/// above the diagonal is in a block, the ones below are mirrored (the block products of a
/// symmetric projection cost half as much).
fn symmetric_from_upper(s: usize, blocks: Vec<(usize, Mat<f64>)>) -> Mat<f64> {
    let mut t = Mat::<f64>::zeros(s, s);
    for (first, block) in blocks {
        t.as_mut()
            .submatrix_mut(0, first, block.nrows(), block.ncols())
            .copy_from(&block);
    }
    for j in 0..s {
        for i in j + 1..s {
            t[(i, j)] = t[(j, i)];
        }
    }
    t
}

/// Values of `n` rows one group of [`projected`] works in: its columns of `A Q`, the product
/// of one packed chunk and the chunk itself.
const GROUP_BUFFER_COLUMNS: usize = PROJECTED_COLUMNS + 2 * CHUNK;

/// `Qᵀ A Q` (`s × s`) for the `n × s` block `q`, [`PROJECTED_COLUMNS`] columns of `A Q` at a
/// time (gathered a packed chunk at a time), each projected onto the columns of `q` up to its
/// own ([`symmetric_from_upper`]); each group's buffers are taken from `scratch` while it has
/// room (see [`rayleigh_ritz`]).
fn projected(a: Stiffness<'_>, q: MatRef<'_, f64>, scratch: &mut [f64], par: Par) -> Mat<f64> {
    let (n, s) = (q.nrows(), q.ncols());
    let groups: Vec<usize> = (0..s).step_by(PROJECTED_COLUMNS).collect();
    let buffer_len = n * GROUP_BUFFER_COLUMNS;
    let free: Vec<&mut [f64]> = if buffer_len == 0 {
        Vec::new()
    } else {
        scratch.chunks_exact_mut(buffer_len).collect()
    };
    let free = Mutex::new(free);
    let one = |&first: &usize| {
        let width = PROJECTED_COLUMNS.min(s - first);
        let mut taken = free.lock().unwrap_or_else(PoisonError::into_inner).pop();
        let mut own = Vec::new();
        let buffer: &mut [f64] = match taken.as_deref_mut() {
            Some(buffer) => buffer,
            None => {
                own.resize(buffer_len, 0.0);
                &mut own
            }
        };
        let (aq, rest) = buffer.split_at_mut(n * PROJECTED_COLUMNS);
        let (product, packed) = rest.split_at_mut(n * CHUNK);
        let (product, packed) = (product.as_chunks_mut().0, packed.as_chunks_mut().0);
        let mut aq = MatMut::from_column_major_slice_mut(&mut aq[..n * width], n, width);
        let mut work = Vec::new();
        for offset in (0..width).step_by(CHUNK) {
            let chunk = CHUNK.min(width - offset);
            pack_into(q, first + offset, chunk, packed);
            a.times_rows(packed, product, &mut work);
            for j in 0..chunk {
                for (i, row) in product.iter().enumerate() {
                    aq[(i, offset + j)] = row[j];
                }
            }
        }
        let upper = q.subcols(0, first + width);
        let block = (first, tall_inner(upper, aq.rb(), Par::Seq));
        if let Some(buffer) = taken {
            free.lock()
                .unwrap_or_else(PoisonError::into_inner)
                .push(buffer);
        }
        block
    };
    // The last groups are the largest: started first, they do not end the parallel loop alone.
    let blocks: Vec<(usize, Mat<f64>)> = if par.degree() > 1 {
        groups.par_iter().rev().map(one).collect()
    } else {
        groups.iter().map(one).collect()
    };
    symmetric_from_upper(s, blocks)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Gram matrix from its upper block triangle equals the full product, for a width that
    /// is not a multiple of the column groups.
    #[test]
    fn gram_from_the_upper_blocks_is_the_full_product() {
        let (n, s) = (500, 45);
        let x = Mat::from_fn(n, s, |i, j| ((i * 13 + j * 29) % 97) as f64 / 48.0 - 1.0);
        let mass: Vec<f64> = (0..n).map(|i| 0.25 + (i % 5) as f64).collect();
        let full = mass_inner(x.as_ref(), Mass::Diagonal(&mass), x.as_ref(), Par::Seq);
        let gram = mass_gram(x.as_ref(), Mass::Diagonal(&mass), Par::Seq);
        assert!((&gram - &full).norm_max() <= 1e-12 * full.norm_max());
        assert_eq!(gram, gram.transpose().to_owned());
    }
}
