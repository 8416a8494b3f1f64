//! Estimates of the spectrum of a pencil `(A, M)` whose mass is not diagonal or whose `A` is
//! only known as an operator: an upper bound by Lanczos ([`upper_bound_of`]), `‖A‖₂` by block
//! power iteration ([`block_power_norm`]) and `trace(A)` by Hutchinson's estimator
//! ([`hutchinson_trace`]).
//!
//!
//! For a diagonal `M` the Gershgorin bound `max_i Σ_j |A_ij| / M_ii` is rigorous and costs one
//! pass over `A`. For a sparse `M` it is not a bound at all (the consistent P1 mass has
//! `M_ii = Σ_{j≠i} |M_ij|`, so `M` is not diagonally dominant), and for a mixed pencil `A` is not
//! stored. There [`lanczos_upper_bound`] runs [`LANCZOS_STEPS`] steps of Lanczos on `M⁻¹ A` in
//! the M inner product (full reorthogonalisation) from a fixed pseudo-random start, takes the
//! largest Ritz value `θ` plus the norm `ρ` of its residual (an eigenvalue lies within `ρ` of
//! `θ`) and multiplies by [`SAFETY_FACTOR`]. Lanczos converges to the top of the spectrum first,
//! so after 40 steps `θ + ρ` is at or above `λ_max` unless the start vector is nearly orthogonal
//! to the top eigenvectors (probability negligible for a random start); the bound is an
//! inflated estimate, not a proof.

use super::stiffness::Stiffness;
use super::stored_mass::MassSolver;
use super::symmetric_products::{Row, CHUNK};
use faer::{Mat, Par};

/// Lanczos steps of the estimate.
pub(crate) const LANCZOS_STEPS: usize = 40;

/// Factor applied to `θ + ρ`.
pub(crate) const SAFETY_FACTOR: f64 = 1.05;

/// A map of vectors of the pencil (`A x`, `M x` or `M⁻¹ x`).
pub(crate) type VectorMap<'a> = &'a dyn Fn(&[f64]) -> Vec<f64>;

/// `(θ + ρ) · SAFETY_FACTOR` for the largest eigenvalue of `A x = λ M x` (`n` unknowns), with
/// `apply_a(x) = A x`, and `metric = Some((M x, M⁻¹ x))` or `None` for `M = I` (see the module
/// documentation). Returns 0 for `n = 0`.
pub(crate) fn lanczos_upper_bound(
    n: usize,
    apply_a: VectorMap<'_>,
    metric: Option<(VectorMap<'_>, VectorMap<'_>)>,
) -> f64 {
    if n == 0 {
        return 0.0;
    }
    let times_m = |x: &[f64]| metric.map_or_else(|| x.to_vec(), |(m, _)| m(x));
    let solve_m = |x: &[f64]| metric.map_or_else(|| x.to_vec(), |(_, inverse)| inverse(x));
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
    let mut q: Vec<f64> = (0..n)
        .map(|i| {
            let h = (i as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15);
            ((h >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        })
        .collect();
    let mut mq = times_m(&q);
    let norm = dot(&q, &mq).sqrt();
    q.iter_mut().for_each(|v| *v /= norm);
    mq.iter_mut().for_each(|v| *v /= norm);
    let (mut basis, mut weighted) = (vec![q], vec![mq]);
    let (mut alpha, mut beta) = (Vec::new(), Vec::new());
    let steps = LANCZOS_STEPS.min(n);
    let mut last_beta = 0.0;
    for j in 0..steps {
        let aq = apply_a(&basis[j]);
        alpha.push(dot(&basis[j], &aq));
        let mut w = solve_m(&aq);
        for _pass in 0..2 {
            for (qi, mqi) in basis.iter().zip(&weighted) {
                let c = dot(mqi, &w);
                w.iter_mut().zip(qi).for_each(|(x, q)| *x -= c * q);
            }
        }
        let mw = times_m(&w);
        last_beta = dot(&w, &mw).max(0.0).sqrt();
        let scale = alpha.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        if j + 1 == steps || last_beta <= 1e-12 * scale {
            if last_beta <= 1e-12 * scale {
                last_beta = 0.0;
            }
            break;
        }
        beta.push(last_beta);
        basis.push(w.iter().map(|v| v / last_beta).collect());
        weighted.push(mw.iter().map(|v| v / last_beta).collect());
    }
    let m = alpha.len();
    let t = faer::Mat::from_fn(m, m, |i, k| {
        if i == k {
            alpha[i]
        } else if i.abs_diff(k) == 1 {
            beta[i.min(k)]
        } else {
            0.0
        }
    });
    let Ok((values, vectors)) = crate::symmetric_eigen::symmetric_eigen(t.as_ref()) else {
        return f64::INFINITY;
    };
    let top = values[m - 1];
    let residual = last_beta * vectors[(m - 1, m - 1)].abs();
    (top + residual).max(0.0) * SAFETY_FACTOR
}

/// The Lanczos bound of `(A, M)` (see `spectrum_bound.rs`).
pub(crate) fn upper_bound_of(stiffness: Stiffness<'_>, mass: MassSolver<'_>, n: usize) -> f64 {
    let apply_a = |x: &[f64]| {
        let column = faer::MatRef::from_column_major_slice(x, n, 1);
        let mut out = Mat::<f64>::zeros(n, 1);
        stiffness.times(out.as_mut(), column, Par::Seq);
        (0..n).map(|i| out[(i, 0)]).collect()
    };
    let times_m = |x: &[f64]| mass.apply(x);
    let solve_m = |x: &[f64]| mass.solve(x);
    lanczos_upper_bound(n, &apply_a, Some((&times_m, &solve_m)))
}

/// Block power steps of the norm estimate of a mixed `A`.
const POWER_STEPS: usize = 12;

/// `λ_max(A)` of the symmetric positive semidefinite `A` (`n × n`) estimated by [`POWER_STEPS`]
/// steps of block power iteration on eight pseudo-random vectors (one packed product each):
/// the largest Rayleigh quotient of the last block, at least the smallest positive number.
pub(crate) fn block_power_norm(stiffness: Stiffness<'_>, n: usize) -> f64 {
    let mut x: Vec<Row> = (0..n)
        .map(|i| {
            std::array::from_fn(|j| {
                let h = ((i * CHUNK + j) as u64 + 3).wrapping_mul(0x9e37_79b9_7f4a_7c15);
                (h >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
        })
        .collect();
    let (mut ax, mut work) = (vec![[0.0; CHUNK]; n], Vec::new());
    let mut largest = f64::MIN_POSITIVE;
    for _ in 0..POWER_STEPS {
        stiffness.times_rows(&x, &mut ax, &mut work);
        let (mut xx, mut xax, mut yy) = ([0.0; CHUNK], [0.0; CHUNK], [0.0; CHUNK]);
        for (a, b) in x.iter().zip(&ax) {
            for j in 0..CHUNK {
                xx[j] += a[j] * a[j];
                xax[j] += a[j] * b[j];
                yy[j] += b[j] * b[j];
            }
        }
        largest = (0..CHUNK)
            .filter(|&j| xx[j] > 0.0)
            .map(|j| xax[j] / xx[j])
            .fold(largest, f64::max);
        let norms: Row = std::array::from_fn(|j| yy[j].sqrt());
        if norms.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
            break;
        }
        for (a, b) in x.iter_mut().zip(&ax) {
            *a = std::array::from_fn(|j| b[j] / norms[j]);
        }
    }
    largest
}

/// Hutchinson's estimate of `trace(A)`: the mean of `zᵀ A z` over eight vectors `z` of
/// pseudo-random signs (one packed product).
pub(crate) fn hutchinson_trace(stiffness: Stiffness<'_>, n: usize) -> f64 {
    let z: Vec<Row> = (0..n)
        .map(|i| {
            std::array::from_fn(|j| {
                let h = ((i * CHUNK + j) as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15);
                if h >> 63 == 0 {
                    1.0
                } else {
                    -1.0
                }
            })
        })
        .collect();
    let (mut az, mut work) = (vec![[0.0; CHUNK]; n], Vec::new());
    stiffness.times_rows(&z, &mut az, &mut work);
    let sum: f64 = z
        .iter()
        .zip(&az)
        .map(|(x, y)| (0..CHUNK).map(|j| x[j] * y[j]).sum::<f64>())
        .sum();
    sum / CHUNK as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a pencil with a dense, non-diagonally-dominant mass the estimate lies above the
    /// largest eigenvalue and within the safety factor (plus the residual) of it.
    #[test]
    fn lanczos_bound_is_above_the_top_eigenvalue() {
        let n = 120;
        let a = faer::Mat::from_fn(n, n, |i, j| match i.abs_diff(j) {
            0 => 2.0 + (i % 7) as f64,
            1 => -1.0,
            _ => 0.0,
        });
        let m = faer::Mat::from_fn(n, n, |i, j| match i.abs_diff(j) {
            0 => 1.0,
            1 => 0.45,
            _ => 0.0,
        });
        let l = m.as_ref().llt(faer::Side::Lower).expect("SPD");
        let apply = |matrix: &faer::Mat<f64>, x: &[f64]| {
            (0..n)
                .map(|i| (0..n).map(|j| matrix[(i, j)] * x[j]).sum())
                .collect::<Vec<f64>>()
        };
        let times_a = |x: &[f64]| apply(&a, x);
        let times_m = |x: &[f64]| apply(&m, x);
        let solve_m = |x: &[f64]| {
            let b = faer::Mat::from_fn(n, 1, |i, _| x[i]);
            let s = faer::linalg::solvers::Solve::solve(&l, &b);
            (0..n).map(|i| s[(i, 0)]).collect::<Vec<f64>>()
        };
        let bound = lanczos_upper_bound(n, &times_a, Some((&times_m, &solve_m)));
        // L⁻¹ A L⁻ᵀ has the spectrum of (A, M).
        let mut y = a.clone();
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(
            l.L(),
            y.as_mut(),
            faer::Par::Seq,
        );
        let mut reduced = y.transpose().to_owned();
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(
            l.L(),
            reduced.as_mut(),
            faer::Par::Seq,
        );
        let (values, _) = crate::symmetric_eigen::symmetric_eigen(reduced.as_ref()).expect("eigen");
        let top = values[n - 1];
        assert!(bound >= top, "bound {bound} below λ_max {top}");
        assert!(bound <= 1.2 * top, "bound {bound} far above λ_max {top}");
        let identity_bound = lanczos_upper_bound(n, &times_a, None);
        let (a_values, _) = crate::symmetric_eigen::symmetric_eigen(a.as_ref()).expect("eigen");
        assert!(identity_bound >= a_values[n - 1]);
    }
}
