//! Block Gram–Schmidt in the inner product `⟨x, y⟩_M = xᵀ M y` with a diagonal or sparse `M`
//! ([`Mass`]),
//! written with dense matrix products so that orthogonalising a block of `r` vectors against a
//! basis of `p` vectors costs two `p × n × r` products per pass (in the Krylov expansion, the
//! fused row sweeps of `tall_products.rs`, which read the basis once per pass).

use super::mass::Mass;
use super::sparse_mass_products::sparse_squared_norms;
use super::tall_products::{mass_inner, sweep, tall_times, tall_times_in_place};
use crate::error::SolverError;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// A second Gram–Schmidt pass is made when a column's norm drops below this fraction.
const SECOND_PASS_RATIO: f64 = 0.7;

/// Relative norm below which a column is treated as linearly dependent on the basis.
const DEPENDENCE_THRESHOLD: f64 = 1e-10;

/// Largest `‖Z‖ / min R_jj` (growth of rounding-level components along the bases when a block is
/// normalised) for which the block is accepted without a further Gram–Schmidt pass.
const AMPLIFICATION_LIMIT: f64 = 1e3;

/// Removes from `z` its `M`-projection onto each (M-orthonormal) basis in `bases` with block
/// classical Gram–Schmidt. One pass leaves components of relative size `ε·κ` along the bases,
/// where `κ = ‖z_before‖/‖z_after‖` is the cancellation factor; in shift-invert those are
/// amplified by `θ_max/θ` in the next step (huge near a zero eigenvalue), so a second pass is
/// made unless every column kept 70% of its norm (Daniel–Gragg–Kaufman–Stewart criterion),
/// and a third one if the second pass cancelled that much again (rare: a nearly dependent block).
/// A relaxed criterion (second pass only for `κ > 1000`) was tried and stalls convergence.
/// Returns, per basis, the summed coefficients `Bᵀ M z` (`p × r`).
pub(crate) fn project_out(
    mut z: MatMut<'_, f64>,
    bases: &[MatRef<'_, f64>],
    mass: Mass<'_>,
    par: Par,
) -> Vec<Mat<f64>> {
    let mut total: Vec<Mat<f64>> = bases
        .iter()
        .map(|b| Mat::zeros(b.ncols(), z.ncols()))
        .collect();
    let mut before = mass_column_norms(mass, z.rb());
    for _pass in 0..3 {
        for (b, sum) in bases.iter().zip(total.iter_mut()) {
            if b.ncols() == 0 {
                continue;
            }
            let c = mass_inner(*b, mass, z.rb(), par);
            tall_times(z.rb_mut(), Accum::Add, *b, c.as_ref(), -1.0, par);
            *sum += &c;
        }
        let after = mass_column_norms(mass, z.rb());
        if after
            .iter()
            .zip(&before)
            .all(|(a, b)| *a > SECOND_PASS_RATIO * *b)
        {
            break;
        }
        before = after;
    }
    total
}

/// [`project_out`] of `z − K C` without forming it first: `z ← z − K C` for the basis `K`
/// (`n × p`, one of `bases` or spanned by them) and coefficients `C` (`p × r`) known in
/// advance (in the Krylov–Schur expansion they follow from the Krylov relation), then the
/// Gram–Schmidt pass against `bases`, both as two fused sweeps over the rows (see [`sweep`]):
/// the update by `K` with the inner products against `bases`, then the update by `bases` with the
/// column norms. The same DGKS criterion as [`project_out`] decides on further passes (rare),
/// which [`project_out`] makes. Returns, per basis, the coefficients `Bᵀ M (z − K C)` (`C` is
/// not included), and `zᵀ M z` of the result when the second sweep could form it (at most
/// eight columns, no further pass).
pub(crate) fn project_out_after_known(
    mut z: MatMut<'_, f64>,
    known: MatRef<'_, f64>,
    known_coefficients: MatRef<'_, f64>,
    bases: &[MatRef<'_, f64>],
    mass: Mass<'_>,
    par: Par,
) -> (Vec<Mat<f64>>, Option<Mat<f64>>) {
    // Only the rows of C with a nonzero entry take part (in the Krylov expansion, those of the
    // last block and of the block itself, except after a restart): the other columns of K are
    // still read for the inner products, but not multiplied.
    let nonzero =
        |k: &usize| (0..known_coefficients.ncols()).any(|j| known_coefficients[(*k, j)] != 0.0);
    let rows = 0..known_coefficients.nrows();
    let first_row = rows.clone().find(nonzero).unwrap_or(0);
    let end_row = rows.rev().find(nonzero).map_or(first_row, |k| k + 1);
    let active = (
        known.subcols(first_row, end_row - first_row),
        known_coefficients.subrows(first_row, end_row - first_row),
    );
    let first = sweep(z.rb_mut(), &[active], bases, mass, false, par);
    let subtract: Vec<(MatRef<'_, f64>, MatRef<'_, f64>)> = bases
        .iter()
        .zip(&first.inner)
        .map(|(b, c)| (*b, c.as_ref()))
        .collect();
    let second = sweep(z.rb_mut(), &subtract, &[], mass, true, par);
    let mut total = first.inner;
    let kept_norm = second
        .squared_norms
        .iter()
        .zip(&first.squared_norms)
        .all(|(after, before)| *after > SECOND_PASS_RATIO * SECOND_PASS_RATIO * *before);
    if !kept_norm {
        for (sum, more) in total.iter_mut().zip(project_out(z, bases, mass, par)) {
            *sum += &more;
        }
        return (total, None);
    }
    (total, second.gram)
}

/// M-norms of the columns of `z`.
pub(crate) fn mass_column_norms(mass: Mass<'_>, z: MatRef<'_, f64>) -> Vec<f64> {
    let mass = match mass {
        Mass::Diagonal(mass) => mass,
        Mass::Sparse(m) => {
            return sparse_squared_norms(m, z)
                .iter()
                .map(|s| s.sqrt())
                .collect();
        }
    };
    (0..z.ncols())
        .map(|j| {
            (0..z.nrows())
                .map(|i| mass[i] * z[(i, j)] * z[(i, j)])
                .sum::<f64>()
                .sqrt()
        })
        .collect()
}

/// Fills `z` with uniform random entries in `[-1, 1)`.
pub(crate) fn fill_random(mut z: MatMut<'_, f64>, rng: &mut ChaCha8Rng) {
    for j in 0..z.ncols() {
        for i in 0..z.nrows() {
            z[(i, j)] = rng.random_range(-1.0..1.0);
        }
    }
}

/// Upper-triangular Cholesky factor `R` (`SᵀS`-style: `S = RᵀR`) of a small SPD matrix, or
/// `None` if a pivot is not positive or the factor is too ill-conditioned for CholeskyQR.
fn small_cholesky(s: MatRef<'_, f64>) -> Option<Mat<f64>> {
    let r = s.nrows();
    let mut u = Mat::<f64>::zeros(r, r);
    for j in 0..r {
        for i in 0..=j {
            let mut sum = s[(i, j)];
            for p in 0..i {
                sum -= u[(p, i)] * u[(p, j)];
            }
            if i == j {
                if sum <= 0.0 || !sum.is_finite() {
                    return None;
                }
                u[(j, j)] = sum.sqrt();
            } else {
                u[(i, j)] = sum / u[(i, i)];
            }
        }
    }
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for j in 0..r {
        lo = lo.min(u[(j, j)]);
        hi = hi.max(u[(j, j)]);
    }
    (lo > 1e-6 * hi).then_some(u)
}

/// Inverse of a small nonsingular upper-triangular matrix.
fn upper_inverse(u: MatRef<'_, f64>) -> Mat<f64> {
    let r = u.nrows();
    let mut inv = Mat::<f64>::zeros(r, r);
    for j in 0..r {
        inv[(j, j)] = 1.0 / u[(j, j)];
        for i in (0..j).rev() {
            let mut sum = 0.0;
            for p in i + 1..=j {
                sum += u[(i, p)] * inv[(p, j)];
            }
            inv[(i, j)] = -sum / u[(i, i)];
        }
    }
    inv
}

/// M-orthonormalises the columns of `z` (`n × r`, already M-orthogonal to `bases`) in place
/// and returns the `r × r` upper-triangular `B` with `Z_in = Z_out · B` (up to the parts
/// removed): CholeskyQR2 when the block is well conditioned, column-wise Gram–Schmidt
/// otherwise. `gram` is `zᵀ M z` if the caller has formed it already (else it is computed).
/// Columns that are numerically dependent (norm below `1e-10` of `reference_norms`) are
/// replaced by random vectors orthogonalised against `bases` and the previous columns; their
/// columns of `B` are zero (what was left of them is rounding noise), so the Krylov relation is
/// unaffected.
///
/// Errors: [`SolverError::NoConvergence`] if no independent direction is left (the bases span
/// the whole space).
pub(crate) fn orthonormalize_block(
    mut z: MatMut<'_, f64>,
    gram: Option<Mat<f64>>,
    reference_norms: &[f64],
    bases: &[MatRef<'_, f64>],
    mass: Mass<'_>,
    rng: &mut ChaCha8Rng,
    par: Par,
) -> Result<Mat<f64>, SolverError> {
    let gram = match gram {
        Some(gram) => symmetrized(&gram),
        None => mass_gram(z.rb(), mass, par),
    };
    let well_scaled = (0..z.ncols())
        .all(|j| gram[(j, j)].sqrt() > 1e-4 * reference_norms[j].max(f64::MIN_POSITIVE));
    let first = match well_scaled
        .then(|| cholesky_qr2(z.rb_mut(), gram, bases, mass, rng, par))
        .transpose()?
        .flatten()
    {
        Some(coefficients) => coefficients,
        None => column_gram_schmidt(z.rb_mut(), reference_norms, bases, mass, rng, par)?,
    };
    // Normalising a nearly dependent block (Q = Z R⁻¹ with ill-conditioned R) amplifies the
    // rounding-level components that Z kept along `bases` by up to ‖R⁻¹‖‖Z‖ ≈ growth below.
    // Left there, they break the Krylov relation. When the growth is large (or a column was
    // replaced by a random one, which has a zero diagonal in R), the components are removed once
    // more (they are rounding noise, not part of the relation) and the block re-normalised; the
    // extra triangular factor is folded into R. For a well-conditioned block (the usual case)
    // this third Gram–Schmidt pass over all bases would cost a third of the orthogonalisation
    // for nothing, so it is skipped.
    let largest_reference = reference_norms.iter().copied().fold(0.0f64, f64::max);
    let smallest_pivot = (0..first.ncols())
        .map(|j| first[(j, j)].abs())
        .fold(f64::INFINITY, f64::min);
    if smallest_pivot > 0.0 && largest_reference <= AMPLIFICATION_LIMIT * smallest_pivot {
        return Ok(first);
    }
    project_out(z.rb_mut(), bases, mass, par);
    let gram = mass_gram(z.rb(), mass, par);
    match cholesky_qr2(z, gram, bases, mass, rng, par)? {
        Some(second) => Ok(&second * &first),
        None => Err(SolverError::NoConvergence {
            reason: "Krylov block lost its rank during reorthogonalisation".into(),
        }),
    }
}

/// `Zᵀ M Z` (`r × r`), symmetrised.
fn mass_gram(z: MatRef<'_, f64>, mass: Mass<'_>, par: Par) -> Mat<f64> {
    symmetrized(&mass_inner(z, mass, z, par))
}

/// `(S + Sᵀ) / 2` of a square `s`.
fn symmetrized(s: &Mat<f64>) -> Mat<f64> {
    Mat::from_fn(s.nrows(), s.ncols(), |i, j| 0.5 * (s[(i, j)] + s[(j, i)]))
}

/// Two CholeskyQR passes over `z` in place, the first with `gram = Zᵀ M Z`: returns `B` with
/// `Z_in = Z_out · B`, or `None` with `z` untouched when the first pass finds the block too
/// ill-conditioned for CholeskyQR. After a first pass that succeeded (condition below 10⁶)
/// the second cannot fail in exact arithmetic; if rounding makes it fail anyway, column-wise
/// Gram–Schmidt finishes the block and its factor is folded in.
fn cholesky_qr2(
    mut z: MatMut<'_, f64>,
    gram: Mat<f64>,
    bases: &[MatRef<'_, f64>],
    mass: Mass<'_>,
    rng: &mut ChaCha8Rng,
    par: Par,
) -> Result<Option<Mat<f64>>, SolverError> {
    let Some(first) = small_cholesky(gram.as_ref()) else {
        return Ok(None);
    };
    tall_times_in_place(z.rb_mut(), upper_inverse(first.as_ref()).as_ref(), par);
    let second = match small_cholesky(mass_gram(z.rb(), mass, par).as_ref()) {
        Some(second) => {
            tall_times_in_place(z.rb_mut(), upper_inverse(second.as_ref()).as_ref(), par);
            second
        }
        None => {
            let unit = vec![1.0; z.ncols()];
            column_gram_schmidt(z, &unit, bases, mass, rng, par)?
        }
    };
    Ok(Some(&second * &first))
}

/// Column-wise Gram–Schmidt of `z` in place (see [`orthonormalize_block`]): returns the
/// upper-triangular `B` with `Z_in = Z_out · B`, zero rows for replaced columns.
fn column_gram_schmidt(
    mut z: MatMut<'_, f64>,
    reference_norms: &[f64],
    bases: &[MatRef<'_, f64>],
    mass: Mass<'_>,
    rng: &mut ChaCha8Rng,
    par: Par,
) -> Result<Mat<f64>, SolverError> {
    let (n, r) = (z.nrows(), z.ncols());
    let mut coefficients = Mat::<f64>::zeros(r, r);
    for j in 0..r {
        let mut replaced = false;
        for attempt in 0..4 {
            let (done, mut rest) = z.rb_mut().split_at_col_mut(j);
            let mut col = rest.rb_mut().subcols_mut(0, 1);
            let before = if replaced {
                mass_column_norms(mass, col.rb())[0]
            } else {
                reference_norms[j]
            };
            if replaced {
                project_out(col.rb_mut(), bases, mass, par);
            }
            let c = project_out(col.rb_mut(), &[done.rb()], mass, par);
            let norm = mass_column_norms(mass, col.rb())[0];
            if norm > DEPENDENCE_THRESHOLD * before.max(f64::MIN_POSITIVE) && norm > 0.0 {
                if !replaced {
                    for i in 0..j {
                        coefficients[(i, j)] = c[0][(i, 0)];
                    }
                    coefficients[(j, j)] = norm;
                }
                for i in 0..n {
                    col[(i, 0)] /= norm;
                }
                break;
            }
            if attempt == 3 {
                return Err(SolverError::NoConvergence {
                    reason: "Krylov basis spans the whole space; no independent direction left"
                        .into(),
                });
            }
            replaced = true;
            fill_random(col.rb_mut(), rng);
        }
    }
    Ok(coefficients)
}

/// A fresh `n × r` random block, M-orthonormal and M-orthogonal to `bases`.
pub(crate) fn random_orthonormal_block(
    n: usize,
    r: usize,
    bases: &[MatRef<'_, f64>],
    mass: Mass<'_>,
    rng: &mut ChaCha8Rng,
    par: Par,
) -> Result<Mat<f64>, SolverError> {
    let mut z = Mat::zeros(n, r);
    fill_random(z.as_mut(), rng);
    let reference = mass_column_norms(mass, z.as_ref());
    project_out(z.as_mut(), bases, mass, par);
    orthonormalize_block(z.as_mut(), None, &reference, bases, mass, rng, par)?;
    Ok(z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    fn sample(n: usize, c: usize, seed: usize) -> Mat<f64> {
        Mat::from_fn(n, c, |i, j| {
            ((i * 31 + j * 17 + seed * 7) % 101) as f64 / 50.0 - 1.0
        })
    }

    /// The block comes out M-orthonormal and M-orthogonal to the bases, in place, with the
    /// triangular factor of the Krylov relation (`Z_in = Z_out · B`); a dependent column is
    /// replaced by a random direction whose column of `B` is zero.
    #[test]
    fn orthonormalize_block_in_place_keeps_the_relation() {
        let n = 300;
        let mass: Vec<f64> = (0..n).map(|i| 0.5 + (i % 7) as f64 / 3.0).collect();
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let basis = random_orthonormal_block(n, 10, &[], Mass::Diagonal(&mass), &mut rng, Par::Seq)
            .expect("a random block has full rank");
        for dependent in [false, true] {
            let mut z = sample(n, 6, 1);
            if dependent {
                let first = z.col(0).to_owned();
                z.col_mut(5).copy_from(&first);
            }
            let reference = mass_column_norms(Mass::Diagonal(&mass), z.as_ref());
            project_out(
                z.as_mut(),
                &[basis.as_ref()],
                Mass::Diagonal(&mass),
                Par::Seq,
            );
            let before = z.clone();
            let b = orthonormalize_block(
                z.as_mut(),
                None,
                &reference,
                &[basis.as_ref()],
                Mass::Diagonal(&mass),
                &mut rng,
                Par::Seq,
            )
            .expect("orthonormalised");
            let gram = mass_inner(z.as_ref(), Mass::Diagonal(&mass), z.as_ref(), Par::Seq);
            let identity = Mat::<f64>::identity(6, 6);
            assert!((&gram - &identity).norm_max() < 1e-13, "{dependent}");
            let along = mass_inner(basis.as_ref(), Mass::Diagonal(&mass), z.as_ref(), Par::Seq);
            assert!(along.norm_max() < 1e-13, "{dependent}");
            let rebuilt = &z * &b;
            let kept = if dependent { 5 } else { 6 };
            let difference =
                (rebuilt.as_ref().subcols(0, kept) - before.as_ref().subcols(0, kept)).norm_max();
            assert!(difference < 1e-12 * before.norm_max(), "{dependent}");
            for i in 1..6 {
                for j in 0..i {
                    assert_eq!(b[(i, j)], 0.0, "B is upper triangular");
                }
            }
            if dependent {
                assert!(
                    b.col(5).iter().all(|&v| v == 0.0),
                    "a replaced column of B is zero"
                );
            }
        }
    }
}
