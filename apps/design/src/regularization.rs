//! [`default_regularization`]: the screening weight `ε` of soft design, from the scale of the
//! Hodge–Laplacian's spectrum.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};

/// Random probes of the trace estimate of [`default_regularization`].
const TRACE_PROBES: usize = 8;
/// Seed of those probes.
const TRACE_SEED: u64 = 0x7472_6163_655f_6573;

/// `ε = 1e-10 · tr(M1⁻¹ S) / n1` (units 1/length²): ten orders of magnitude below the mean
/// eigenvalue of the Hodge–Laplacian, so it only matters on (near-)kernel directions left free by
/// the constraints.
///
/// Where `S` is a sparse matrix and `M1` diagonal the trace is exact. Otherwise it is estimated
/// from 8 seeded random sign vectors `z` as the mean of `zᵀ M1⁻¹ S z` (unbiased, with a relative
/// error that falls like `1/√n1`). Should that mean not be positive (possible only on tiny
/// meshes, where single probes are far off), the mean Rayleigh quotient `Σ zᵀ S z / Σ zᵀ M1 z` of
/// the same probes stands in, another estimate of the mean eigenvalue: only the scale of `ε`
/// depends on it.
pub fn default_regularization<H: HodgeComplex + ?Sized>(complex: &H) -> f64 {
    let (trace, n) = trace(complex);
    1e-10 * trace / n
}

/// The mean eigenvalue `tr(M1⁻¹ S) / n1` of the Hodge–Laplacian, as in
/// [`default_regularization`] (units 1/length²).
pub(crate) fn mean_eigenvalue<H: HodgeComplex + ?Sized>(complex: &H) -> f64 {
    let (trace, n) = trace(complex);
    trace / n
}

/// `tr(M1⁻¹ S)`, exact or estimated (see [`default_regularization`]), and `max(n1, 1)`.
fn trace<H: HodgeComplex + ?Sized>(complex: &H) -> (f64, f64) {
    let dirichlet = complex.dirichlet_energy();
    let n = dirichlet.rows().max(1) as f64;
    let trace: f64 = match (dirichlet.as_sparse(), complex.m1().diagonal_values()) {
        (Some(dirichlet), Some(mass)) => (0..dirichlet.rows())
            .map(|i| dirichlet.get(i, i).copied().unwrap_or(0.0) / mass[i].max(f64::MIN_POSITIVE))
            .sum(),
        _ => estimated_trace(complex),
    };
    (trace, n)
}

/// The probe estimate of `tr(M1⁻¹ S)` of [`default_regularization`] (`n1` times the mean
/// eigenvalue of the Hodge–Laplacian).
fn estimated_trace<H: HodgeComplex + ?Sized>(complex: &H) -> f64 {
    let dirichlet = complex.dirichlet_energy();
    let mut rng = ChaCha8Rng::seed_from_u64(TRACE_SEED);
    let (mut trace, mut energy, mut mass) = (0.0, 0.0, 0.0);
    for _ in 0..TRACE_PROBES {
        let z: Vec<f64> = (0..dirichlet.rows())
            .map(|_| if rng.random_bool(0.5) { 1.0 } else { -1.0 })
            .collect();
        let sz = dirichlet.apply(&z);
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        trace += dot(&z, &complex.m1().solve(&sz));
        energy += dot(&z, &sz);
        mass += complex.m1().inner(&z, &z);
    }
    let trace = trace / TRACE_PROBES as f64;
    if trace.is_finite() && trace > 0.0 {
        trace
    } else {
        dirichlet.rows() as f64 * energy / mass
    }
}
