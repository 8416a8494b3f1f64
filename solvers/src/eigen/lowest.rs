//! Driver of the generalized eigensolver: spectrum slicing with Sylvester inertia checks.
//!
//! With `EigenOptions::concurrent_slices ≥ 1` the spectrum is cut into intervals with exact
//! counts and solved concurrently ([`super::interval_slicing`]); if those intervals do not add
//! up (an eigenvalue within rounding of a boundary), or with `concurrent_slices = 0` (the
//! default), the sequential driver below is used (its dense products and blocked solves are
//! spread over `EigenOptions::parallelism` threads, see [`super::tall_products`]):
//!
//! Shifts σ₀ < σ₁ < … are visited from the bottom of the spectrum. At each shift, `A − σM`
//! is factored once (`LDLᵀ`); its negative-pivot count ν(σ) is the exact number of
//! eigenvalues below σ. The Krylov–Schur slice then finds every not-yet-known eigenvalue
//! below σ (so that the count matches ν(σ): everything below σ is *confirmed*) plus the
//! next `slice_size` eigenvalues above σ (tentative until the next shift confirms them).
//! Eigenvectors found earlier near the window are deflated, so nothing is found twice.
//! Each slice's locked vectors then go through a Rayleigh–Ritz with `A` itself
//! ([`super::rayleigh_ritz`]): the Krylov iteration resolves small `|θ|` only to `ε·max|θ|`,
//! which near a zero eigenvalue (first slice) is 10⁻¹⁰ relative and produced "ghost" copies in
//! degenerate clusters; the Rayleigh–Ritz against `A` restores full accuracy.
//! The next shift is placed just above the highest tentative eigenvalue; the last one in a
//! gap right above the k-th eigenvalue, where a factorization alone usually confirms
//! everything.

use super::interval_slicing::{factor_shifted, interval_sliced, SlicedResult, SpectrumScale};
use super::krylov_slice::{run_slice, ColumnStore, SliceProblem, SliceSettings};
use super::rayleigh_ritz::rayleigh_ritz;
use super::types::{EigenOptions, EigenProgress, Eigenpairs};
use crate::convert::{square_dimension, upper_triangle_csc};
use crate::dense_eigen::{check_mass, dense_generalized_eigen};
use crate::error::SolverError;
use crate::sparse_ldlt::SparseLdlt;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Accum, Mat, Par};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// The lowest `k` eigenpairs of `A x = λ M x`.
///
/// - `a`: `n × n` sparse symmetric positive-semidefinite matrix (e.g. a stiffness matrix,
///   integrated), full or upper-triangular storage, CSC or CSR. It may have several zero
///   eigenvalues (one per connected component for a Laplacian). Mildly negative eigenvalues
///   are found too (they lie below the first shift and are counted by its inertia).
/// - `mass_diagonal`: the `n` positive entries of the diagonal mass matrix `M`.
///
/// Returns every eigenvalue up to the k-th, in ascending order, with repeated eigenvalues
/// repeated: completeness is verified by Sylvester's law of inertia (the number of negative
/// pivots of `A − σM` for a shift σ above the k-th eigenvalue equals the number of computed
/// eigenvalues below σ). If a multiple eigenvalue straddles position `k`, the returned
/// vectors span part of its eigenspace. Small problems (`n ≤ options.dense_threshold` or
/// `3k ≥ n`) are solved densely.
///
/// Errors: [`SolverError::NotSquare`], [`SolverError::DimensionMismatch`],
/// [`SolverError::NonFinite`], [`SolverError::MassNotPositive`],
/// [`SolverError::TooManyEigenpairs`] (`k > n`), [`SolverError::NoConvergence`].
pub fn lowest_eigenpairs(
    a: &sprs::CsMat<f64>,
    mass_diagonal: &[f64],
    k: usize,
    options: &EigenOptions<'_>,
) -> Result<Eigenpairs, SolverError> {
    let n = square_dimension(a)?;
    if mass_diagonal.len() != n {
        return Err(SolverError::DimensionMismatch {
            context: "mass diagonal length",
            expected: n,
            actual: mass_diagonal.len(),
        });
    }
    check_mass(mass_diagonal)?;
    if k > n {
        return Err(SolverError::TooManyEigenpairs {
            requested: k,
            dimension: n,
        });
    }
    let full = symmetric_full(&upper_triangle_csc(a)?)?;
    if k == 0 {
        return Ok(Eigenpairs {
            values: Vec::new(),
            vectors: Mat::zeros(n, 0),
            residuals: Vec::new(),
            factorizations: 0,
            solves: 0,
        });
    }
    let (values, vectors, factorizations, solves) = if n <= options.dense_threshold || 3 * k >= n {
        let dense = full.to_dense();
        let (values, vectors) = dense_generalized_eigen(dense.as_ref(), mass_diagonal)?;
        (
            values[..k].to_vec(),
            vectors.as_ref().subcols(0, k).to_owned(),
            0,
            0,
        )
    } else {
        sliced(a, &full, mass_diagonal, k, options)?
    };
    let residuals = relative_residuals(&full, mass_diagonal, &values, &vectors);
    Ok(Eigenpairs {
        values,
        vectors,
        residuals,
        factorizations,
        solves,
    })
}

/// Full symmetric storage of the matrix whose upper triangle is `upper`.
fn symmetric_full(
    upper: &SparseColMat<usize, f64>,
) -> Result<SparseColMat<usize, f64>, SolverError> {
    let n = upper.nrows();
    let mut triplets = Vec::with_capacity(2 * upper.val().len());
    let col_ptr = upper.symbolic().col_ptr();
    let row_idx = upper.symbolic().row_idx();
    for j in 0..n {
        for p in col_ptr[j]..col_ptr[j + 1] {
            let i = row_idx[p];
            triplets.push(Triplet::new(i, j, upper.val()[p]));
            if i != j {
                triplets.push(Triplet::new(j, i, upper.val()[p]));
            }
        }
    }
    SparseColMat::try_new_from_triplets(n, n, &triplets)
        .map_err(|e| SolverError::Factorization(format!("{e:?}")))
}

/// `‖A x − λ M x‖₂ / (‖A‖₁ ‖x‖₂)` per column.
fn relative_residuals(
    full: &SparseColMat<usize, f64>,
    mass: &[f64],
    values: &[f64],
    vectors: &Mat<f64>,
) -> Vec<f64> {
    let n = full.nrows();
    let k = values.len();
    let mut ax = Mat::<f64>::zeros(n, k);
    faer::sparse::linalg::matmul::sparse_dense_matmul(
        ax.as_mut(),
        Accum::Replace,
        full.as_ref(),
        vectors.as_ref(),
        1.0,
        Par::Seq,
    );
    let col_ptr = full.symbolic().col_ptr();
    let norm_a = (0..n)
        .map(|j| {
            full.val()[col_ptr[j]..col_ptr[j + 1]]
                .iter()
                .map(|v| v.abs())
                .sum::<f64>()
        })
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    (0..k)
        .map(|j| {
            let mut r2 = 0.0;
            let mut x2 = 0.0;
            for i in 0..n {
                let x = vectors[(i, j)];
                let r = ax[(i, j)] - values[j] * mass[i] * x;
                r2 += r * r;
                x2 += x * x;
            }
            r2.sqrt() / (norm_a * x2.sqrt().max(f64::MIN_POSITIVE))
        })
        .collect()
}

fn sliced(
    a: &sprs::CsMat<f64>,
    full: &SparseColMat<usize, f64>,
    mass: &[f64],
    k: usize,
    options: &EigenOptions<'_>,
) -> Result<SlicedResult, SolverError> {
    let n = mass.len();
    let par = options.parallelism;
    let block = options.block_size.clamp(1, n / 8 + 1);
    let slice_size = options.slice_size.max(block);
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    // Gershgorin bound of the spectrum of M⁻¹A: the scale for shifts.
    let col_ptr = full.symbolic().col_ptr();
    let rho = (0..n)
        .map(|j| {
            full.val()[col_ptr[j]..col_ptr[j + 1]]
                .iter()
                .map(|v| v.abs())
                .sum::<f64>()
                / mass[j]
        })
        .fold(0.0, f64::max);
    let scale = if rho > 0.0 { rho } else { 1.0 };
    let margin = block.max(k / 64);

    let mut found_values: Vec<f64> = Vec::new();
    let mut found_vectors = ColumnStore::new(n, k + margin + slice_size);
    let mut factor: Option<SparseLdlt> = None;
    let (mut factorizations, mut solves, mut slices) = (0usize, 0usize, 0usize);
    let mut confirmed = 0usize;
    let mut lower_bound = f64::NEG_INFINITY;
    // First shift: slightly below zero, relative to the mean eigenvalue trace(A)/trace(M)
    // (robust to sliver triangles, unlike the Gershgorin bound, which can exceed the low
    // spectrum by many orders of magnitude and would make all wanted θ = 1/(λ − σ) alike).
    let trace_a: f64 = (0..n)
        .map(|j| {
            (col_ptr[j]..col_ptr[j + 1])
                .filter(|&p| full.symbolic().row_idx()[p] == j)
                .map(|p| full.val()[p])
                .sum::<f64>()
        })
        .sum();
    let mean_eigenvalue = trace_a / mass.iter().sum::<f64>();
    if options.concurrent_slices > 0 {
        let spectrum = SpectrumScale {
            mean_eigenvalue,
            scale,
        };
        if let Some(result) = interval_sliced(a, full, mass, k, options, &spectrum)? {
            return Ok(result);
        }
    }
    let mut sigma = -1e-7
        * if mean_eigenvalue > 0.0 {
            mean_eigenvalue
        } else {
            scale
        };

    loop {
        // factor A − σM, nudging σ upwards if it hits an eigenvalue exactly
        let (ldlt, used, count) = factor_shifted(a, mass, sigma, factor.take(), scale, par)?;
        sigma = used;
        factorizations += count;
        slices += 1;
        let nu = ldlt.inertia().negative;
        let known_below = found_values.iter().filter(|&&v| v < sigma).count();
        let known_above = found_values.len() - known_below;
        if known_below > nu {
            return Err(SolverError::NoConvergence {
                reason: format!("inertia count {nu} at shift {sigma:e} is below the {known_below} eigenvalues already found there"),
            });
        }
        let lower_needed = nu - known_below;
        let upper_target = if nu >= k {
            0
        } else {
            // The first slice's shift sits just below the (zero) bottom of the spectrum, so its
            // far Ritz values θ = 1/(λ − σ) crowd together and converge slowly; it only finds a
            // few blocks, and the next shift, placed from their spacing, centres a full slice.
            let budget = if lower_bound.is_finite() {
                slice_size
            } else {
                slice_size.min(4 * block)
            };
            budget.min((k + margin).saturating_sub(nu + known_above))
        };
        if lower_needed > 0 || upper_target > 0 {
            let window_floor = if lower_bound.is_finite() {
                lower_bound - 0.25 * (sigma - lower_bound)
            } else {
                f64::NEG_INFINITY
            };
            let window: Vec<usize> = (0..found_values.len())
                .filter(|&i| found_values[i] > window_floor)
                .collect();
            let all = found_vectors.view();
            let deflation = Mat::from_fn(n, window.len(), |i, j| all[(i, window[j])]);
            let problem = SliceProblem {
                factor: &ldlt,
                mass,
                sigma,
                lower_bound,
                deflation: deflation.as_ref(),
                lower_needed,
                upper_target,
                upper_bound: f64::INFINITY,
            };
            let wanted = (lower_needed + upper_target).min(2 * slice_size);
            let settings = SliceSettings {
                block_size: block,
                tolerance: options.tolerance,
                max_restarts: options.max_restarts,
                max_basis: 2 * wanted + 4 * block,
                parallelism: par,
            };
            let before = found_values.len();
            let solves_before = solves;
            let mut report = |locked: usize, slice_solves: usize| {
                if let Some(callback) = options.progress {
                    callback(&EigenProgress {
                        found: before + locked,
                        confirmed,
                        wanted: k,
                        slices,
                        factorizations,
                        solves: solves_before + slice_solves,
                    });
                }
            };
            let outcome = run_slice(&problem, &settings, &mut rng, &mut report)?;
            solves += outcome.solves;
            let (values, vectors) =
                rayleigh_ritz(full.as_ref(), mass, outcome.vectors.as_ref(), par)?;
            found_values.extend_from_slice(&values);
            found_vectors.append(vectors.as_ref());
        }
        confirmed = nu;
        lower_bound = sigma;
        factor = Some(ldlt);
        if let Some(callback) = options.progress {
            callback(&EigenProgress {
                found: found_values.len(),
                confirmed,
                wanted: k,
                slices,
                factorizations,
                solves,
            });
        }
        if confirmed >= k {
            break;
        }
        sigma = next_shift(&found_values, sigma, k, scale);
    }

    let mut order: Vec<usize> = (0..found_values.len()).collect();
    order.sort_by(|&i, &j| found_values[i].total_cmp(&found_values[j]));
    order.truncate(k);
    let all = found_vectors.view();
    let values = order.iter().map(|&i| found_values[i]).collect();
    let vectors = Mat::from_fn(n, k, |i, j| all[(i, order[j])]);
    Ok((values, vectors, factorizations, solves))
}

/// Next shift above `sigma`: in the gap right after the k-th found eigenvalue if at least
/// `k + 1` are known, otherwise half a mean spacing above the highest found eigenvalue.
fn next_shift(found: &[f64], sigma: f64, k: usize, scale: f64) -> f64 {
    let mut sorted: Vec<f64> = found.to_vec();
    sorted.sort_by(f64::total_cmp);
    let above: Vec<f64> = sorted.iter().copied().filter(|&v| v > sigma).collect();
    let separation = |v: f64| 1e-7 * v.abs().max(1e-6 * scale);
    if sorted.len() > k {
        for j in k - 1..sorted.len() - 1 {
            if sorted[j] > sigma && sorted[j + 1] - sorted[j] > 4.0 * separation(sorted[j + 1]) {
                return 0.5 * (sorted[j] + sorted[j + 1]);
            }
        }
    }
    let top = sorted.last().copied().unwrap_or(sigma).max(sigma);
    let count = above.len().max(1);
    let bottom = sorted
        .iter()
        .rev()
        .nth(count.min(sorted.len()).saturating_sub(1))
        .copied()
        .unwrap_or(sigma)
        .min(top);
    let spacing = if count > 1 {
        (top - bottom) / (count - 1) as f64
    } else {
        0.0
    };
    let spacing = spacing.max(top - sigma).max(2.0 * separation(top));
    top + 0.5 * spacing
}
