//! Spectral checks (dense, small meshes) and intrinsic invariance.

use crate::check_cache::CheckCache;
use crate::check_outcome::{assert_outcomes, CheckOutcome};
use crate::corpus::CorpusMesh;
use crate::dense::{free_eigenproblem, generalized_eigenpairs, split_zeros};
use crate::reference_formulas::{assert_matrices_close, assert_operators_close};
use faer::Mat;
use tvf_core::discretization::{HodgeComplex, HodgeOperators, Mass, MassStorage};

/// Relative threshold (of the largest eigenvalue) below which an eigenvalue counts as zero.
const ZERO: f64 = 1e-9;

/// The spectrum of `L`, ascending: the generalized eigenvalues of the symmetric-definite pencil
/// `(S, M1)` (dense) on the free field nodes (every field node unless the complex fixes some,
/// as relative forms fix boundary edges).
/// Panics if it cannot be computed (the suite's use; [`measured_hodge_spectrum`] says why).
pub fn hodge_spectrum<H: HodgeComplex + ?Sized>(complex: &H) -> Vec<f64> {
    measured_hodge_spectrum(complex).unwrap_or_else(|e| panic!("the spectrum of L: {e}"))
}

/// [`hodge_spectrum`], or why it cannot be computed.
pub fn measured_hodge_spectrum<H: HodgeComplex + ?Sized>(complex: &H) -> Result<Vec<f64>, String> {
    CheckCache::new(complex)
        .hodge_spectrum()
        .map(<[f64]>::to_vec)
}

/// The nonzero spectrum of `L` is the union of the nonzero spectra of the exact pair
/// `(d0ᵀ M1 d0, M0)` and the co-exact pair `(d1 M1⁻¹ d1ᵀ, M2⁻¹)` (each dense, on the free nodes
/// of its space), entry for entry within `1e-9 · λ_max`; `L` has `harmonic_dimension` zeros, each scalar pair as many as its space's
/// kernel dimension; measured.
pub fn measure_spectrum_union<H: HodgeComplex + ?Sized>(
    complex: &H,
    harmonic_dimension: usize,
) -> Vec<CheckOutcome> {
    measure_spectrum_union_with(&CheckCache::new(complex), harmonic_dimension)
}

/// [`measure_spectrum_union`] on the spectra of `cache`.
pub fn measure_spectrum_union_with<H: HodgeComplex + ?Sized>(
    cache: &CheckCache<'_, H>,
    harmonic_dimension: usize,
) -> Vec<CheckOutcome> {
    let complex = cache.complex();
    let (potential_nodes, co_potential_nodes) =
        (complex.potential_nodes(), complex.co_potential_nodes());
    let spectra = || -> Result<_, String> {
        let l = cache.hodge_spectrum().map_err(|e| format!("L: {e}"))?;
        let e = cache
            .exact_spectrum()
            .map_err(|e| format!("the exact pair: {e}"))?;
        let c = cache
            .co_exact_spectrum()
            .map_err(|e| format!("the co-exact pair: {e}"))?;
        Ok((l, e, c))
    };
    let (l, e, c) = match spectra() {
        Ok(spectra) => spectra,
        Err(reason) => {
            let detail = format!("the spectra cannot be computed: {reason}");
            return vec![CheckOutcome::failed("spectrum union", detail)];
        }
    };
    let (l_zeros, l_rest) = split_zeros(l, ZERO);
    let (e_zeros, e_rest) = split_zeros(e, ZERO);
    let (c_zeros, c_rest) = split_zeros(c, ZERO);
    let mut outcomes = vec![
        CheckOutcome::count(
            "zeros of L",
            l_zeros,
            harmonic_dimension,
            format!("L has {l_zeros} zero eigenvalues, expected {harmonic_dimension}"),
        ),
        CheckOutcome::count(
            "zeros of the exact pair",
            e_zeros,
            potential_nodes.kernel_dimension(),
            format!(
                "the exact pair has {e_zeros} zero eigenvalues, expected {}",
                potential_nodes.kernel_dimension()
            ),
        ),
        CheckOutcome::count(
            "zeros of the co-exact pair",
            c_zeros,
            co_potential_nodes.kernel_dimension(),
            format!(
                "the co-exact pair has {c_zeros} zero eigenvalues, expected {}",
                co_potential_nodes.kernel_dimension()
            ),
        ),
    ];
    let mut union: Vec<f64> = e_rest.iter().chain(&c_rest).copied().collect();
    union.sort_by(f64::total_cmp);
    if union.len() != l_rest.len() {
        outcomes.push(CheckOutcome::count(
            "spectrum union",
            union.len(),
            l_rest.len(),
            format!(
                "{} nonzero eigenvalues of L, {} in the union",
                l_rest.len(),
                union.len()
            ),
        ));
        return outcomes;
    }
    let max = l_rest.last().copied().unwrap_or(0.0);
    let (worst, at) = l_rest
        .iter()
        .zip(&union)
        .enumerate()
        .map(|(k, (a, b))| ((a - b).abs(), k))
        .fold((0.0f64, 0), |best, x| if x.0 > best.0 { x } else { best });
    let detail = match l_rest.get(at) {
        Some(a) => format!(
            "nonzero eigenvalue {at}: L has {a}, the union {} (λ_max {max:e})",
            union[at]
        ),
        None => "no nonzero eigenvalues".to_string(),
    };
    outcomes.push(CheckOutcome::at_most(
        "spectrum union",
        worst,
        1e-9 * max,
        detail,
    ));
    outcomes
}

/// [`measure_spectrum_union`] with the corpus mesh's harmonic dimension, asserted.
pub fn check_spectrum_union<H: HodgeComplex + ?Sized, M>(complex: &H, mesh: &CorpusMesh<M>) {
    check_spectrum_union_with(&CheckCache::new(complex), mesh);
}

/// [`check_spectrum_union`] on the spectra of `cache`.
pub fn check_spectrum_union_with<H: HodgeComplex + ?Sized, M>(
    cache: &CheckCache<'_, H>,
    mesh: &CorpusMesh<M>,
) {
    assert_outcomes(&measure_spectrum_union_with(cache, mesh.harmonic_dimension));
}

/// The eigenfields of Lemma 1 with their eigenvalues: `d0 φ / √λ` for the nonzero eigenpairs
/// `(λ, φ)` of the exact pair, then `−M1⁻¹ d1ᵀ ψ / √μ` for those `(μ, ψ)` of the co-exact pair
/// (dense; `M0`- and `M2⁻¹`-orthonormal `φ`, `ψ`); panics if they cannot be computed (the
/// suite's use; [`measured_lemma1_eigenfields`] says why).
pub fn lemma1_eigenfields<H: HodgeComplex + ?Sized>(complex: &H) -> Vec<(f64, Vec<f64>)> {
    measured_lemma1_eigenfields(complex)
        .unwrap_or_else(|e| panic!("the eigenfields of Lemma 1: {e}"))
}

/// [`lemma1_eigenfields`] of `cache` (computed once for every check of its complex).
pub fn lemma1_eigenfields_of<'c, H: HodgeComplex + ?Sized>(
    cache: &'c CheckCache<'_, H>,
) -> &'c [(f64, Vec<f64>)] {
    cache
        .lemma1_eigenfields()
        .unwrap_or_else(|e| panic!("the eigenfields of Lemma 1: {e}"))
}

/// [`lemma1_eigenfields`], or why they cannot be computed.
pub fn measured_lemma1_eigenfields<H: HodgeComplex + ?Sized>(
    complex: &H,
) -> Result<Vec<(f64, Vec<f64>)>, String> {
    let mut fields = Vec::new();
    let exact = complex.exact_eigenproblem();
    let co_exact = complex.co_exact_eigenproblem();
    for (problem, nodes, integrable) in [
        (&exact, complex.potential_nodes(), true),
        (&co_exact, complex.co_potential_nodes(), false),
    ] {
        let (a, m, free) = free_eigenproblem(problem, nodes);
        let (values, restricted) = generalized_eigenpairs(&a, &m)?;
        let mut vectors = Mat::<f64>::zeros(nodes.len(), values.len());
        for (r, &i) in free.iter().enumerate() {
            for k in 0..values.len() {
                vectors[(i, k)] = restricted[(r, k)];
            }
        }
        let max = values.last().copied().unwrap_or(0.0);
        for (k, &lambda) in values.iter().enumerate() {
            if lambda <= ZERO * max {
                continue;
            }
            let scalar: Vec<f64> = vectors.col(k).iter().map(|x| x / lambda.sqrt()).collect();
            let field = if integrable {
                complex.gradient_field(&scalar)
            } else {
                complex.co_gradient_field(&scalar)
            };
            fields.push((lambda, field));
        }
    }
    Ok(fields)
}

/// Lemma 1: every eigenfield of [`lemma1_eigenfields`] has unit `M1` norm (to 1e-9) and
/// `‖L u − λ u‖_{M1} ≤ 1e-9 · λ_max`; measured as the worst of each.
pub fn measure_lemma1<H: HodgeComplex + ?Sized>(complex: &H) -> Vec<CheckOutcome> {
    measure_lemma1_with(&CheckCache::new(complex))
}

/// [`measure_lemma1`] on the eigenfields of `cache`.
pub fn measure_lemma1_with<H: HodgeComplex + ?Sized>(
    cache: &CheckCache<'_, H>,
) -> Vec<CheckOutcome> {
    let complex = cache.complex();
    let laplacian = complex.hodge_laplacian();
    let fields = match cache.lemma1_eigenfields() {
        Ok(fields) => fields,
        Err(reason) => {
            let detail = format!("the eigenfields cannot be computed: {reason}");
            return vec![CheckOutcome::failed("Lemma 1: eigenfields of L", detail)];
        }
    };
    let max = fields.iter().fold(0.0f64, |m, (l, _)| m.max(*l));
    let (mut worst_norm, mut norm_at) = (0.0f64, 0);
    let (mut worst_residual, mut residual_at) = (0.0f64, 0);
    // `L u` of every field at once: one block solve with a sparse `M1` instead of one per field.
    let n1 = complex.field_dimension();
    let block = Mat::<f64>::from_fn(n1, fields.len(), |i, k| fields[k].1[i]);
    let applied = laplacian.apply_block(block.as_ref());
    for (k, (lambda, u)) in fields.iter().enumerate() {
        let norm = complex.field_inner(u, u).sqrt();
        if (norm - 1.0).abs() > worst_norm || norm.is_nan() {
            (worst_norm, norm_at) = ((norm - 1.0).abs(), k);
        }
        let residual: Vec<f64> = applied
            .col(k)
            .iter()
            .zip(u)
            .map(|(lu, x)| lu - lambda * x)
            .collect();
        let error = complex.field_inner(&residual, &residual).sqrt();
        if error > worst_residual || error.is_nan() {
            (worst_residual, residual_at) = (error, k);
        }
    }
    let lambda = |k: usize| fields.get(k).map_or(0.0, |f| f.0);
    vec![
        CheckOutcome::at_most(
            "Lemma 1: unit eigenfields",
            worst_norm,
            1e-9,
            format!("eigenfield {norm_at} (λ = {}): M1 norm off by {worst_norm:e}", lambda(norm_at)),
        ),
        CheckOutcome::at_most(
            "Lemma 1: eigenfields of L",
            worst_residual,
            1e-9 * max,
            format!("eigenfield {residual_at}: |L u − λ u| = {worst_residual:e} (λ = {}, λ_max {max:e})", lambda(residual_at)),
        ),
    ]
}

/// [`measure_lemma1`], asserted.
pub fn check_lemma1<H: HodgeComplex + ?Sized>(complex: &H) {
    assert_outcomes(&measure_lemma1(complex));
}

/// [`check_lemma1`] on the eigenfields of `cache`.
pub fn check_lemma1_with<H: HodgeComplex + ?Sized>(cache: &CheckCache<'_, H>) {
    assert_outcomes(&measure_lemma1_with(cache));
}

/// Lemma 2: the eigenfields of both scalar problems and an `M1`-orthonormal harmonic basis
/// together are as many fields as there are free field nodes (`n1` unless the complex fixes
/// some), with `Uᵀ M1 U = I` (max deviation ≤ 1e-9): a complete orthonormal basis of the fields.
pub fn check_basis_orthonormal<H: HodgeComplex + ?Sized>(complex: &H, seed: u64) {
    check_basis_orthonormal_with(&CheckCache::new(complex), seed);
}

/// [`check_basis_orthonormal`] with the eigenfields and the decomposer of `cache`.
pub fn check_basis_orthonormal_with<H: HodgeComplex + ?Sized>(
    cache: &CheckCache<'_, H>,
    seed: u64,
) {
    let complex = cache.complex();
    let mut basis: Vec<Vec<f64>> = lemma1_eigenfields_of(cache)
        .iter()
        .map(|(_, u)| u.clone())
        .collect();
    let harmonic = cache
        .decomposer()
        .unwrap_or_else(|e| panic!("decomposer factors: {e}"))
        .harmonic_basis(seed)
        .expect("harmonic basis");
    basis.extend(harmonic);
    let (n, free) = (
        complex.field_dimension(),
        complex.field_nodes().free_count(),
    );
    assert_eq!(
        basis.len(),
        free,
        "eigenfields + harmonic fields = free field nodes"
    );
    let fields = Mat::<f64>::from_fn(n, free, |i, j| basis[j][i]);
    let gram = fields.transpose() * complex.m1().apply_block(fields.as_ref());
    for i in 0..free {
        for j in 0..free {
            let expected = if i == j { 1.0 } else { 0.0 };
            assert!(
                (gram[(i, j)] - expected).abs() <= 1e-9,
                "basis Gram ({i},{j}) = {:e}",
                gram[(i, j)]
            );
        }
    }
}

/// Two complexes have the same Hodge–Laplacian spectrum (e.g. conforming vs nonconforming with
/// the same lumping, or a mesh and a rigidly moved copy), within `1e-9 · λ_max`.
pub fn check_same_spectrum<A, B>(a: &A, b: &B)
where
    A: HodgeComplex + ?Sized,
    B: HodgeComplex + ?Sized,
{
    let sa = hodge_spectrum(a);
    let sb = hodge_spectrum(b);
    assert_eq!(sa.len(), sb.len(), "spectrum sizes");
    let max = sa.last().copied().unwrap_or(0.0);
    for (k, (x, y)) in sa.iter().zip(&sb).enumerate() {
        assert!(
            (x - y).abs() <= 1e-9 * max,
            "eigenvalue {k}: {} has {x}, {} has {y}",
            a.id(),
            b.id()
        );
    }
}

/// On a unit icosphere the smooth spectrum of the Hodge–Laplacian on fields starts
/// `2 (×3 per family), 6, ...`: the lowest six eigenvalues of `L` lie in `[1.9, 2.1]` and the
/// seventh is above 5.
pub fn check_sphere_spectrum<H: HodgeComplex + ?Sized>(complex: &H) {
    let spectrum = hodge_spectrum(complex);
    let low = &spectrum[..7];
    for &lambda in &low[..6] {
        assert!(
            (1.9..=2.1).contains(&lambda),
            "lowest six should be ≈ 2: {low:?}"
        );
    }
    assert!(low[6] > 5.0, "seventh should be ≈ 6: {low:?}");
}

/// Complexes on rigidly moved copies of one mesh have the same stiffness matrices and masses
/// (relative 1e-10) and, if `dense`, the same Hodge–Laplacian spectrum.
pub fn check_rigid_motion_invariance<A, B>(original: &A, moved: &B, dense: bool)
where
    A: HodgeComplex + ?Sized,
    B: HodgeComplex + ?Sized,
{
    assert_matrices_close(
        "potential stiffness after a rigid motion",
        moved.potential_stiffness(),
        original.potential_stiffness(),
    );
    assert_operators_close(
        "co-potential stiffness after a rigid motion",
        moved.co_potential_stiffness(),
        original.co_potential_stiffness(),
    );
    for (what, a, b) in [
        ("M0", moved.m0(), original.m0()),
        ("M1", moved.m1(), original.m1()),
        ("M2", moved.m2(), original.m2()),
    ] {
        assert_masses_close(what, a, b);
    }
    if dense {
        check_same_spectrum(original, moved);
    }
}

/// Two masses store the same matrix in the same form: diagonals entry for entry (relative
/// 1e-10 of each entry), sparse matrices within `1e-10 · max |entry|`.
fn assert_masses_close(what: &str, a: &Mass, b: &Mass) {
    assert_eq!(
        a.len(),
        b.len(),
        "{what}: size changed under a rigid motion"
    );
    assert_eq!(a.form(), b.form(), "{what}: stored form changed");
    match (a.storage(), b.storage()) {
        (MassStorage::Diagonal(x), MassStorage::Diagonal(y)) => {
            for (x, y) in x.iter().zip(y) {
                assert!(
                    (x - y).abs() <= 1e-10 * y.abs(),
                    "{what} changed under a rigid motion: {x} vs {y}"
                );
            }
        }
        (MassStorage::Sparse(x), MassStorage::Sparse(y)) => {
            assert_matrices_close(&format!("{what} after a rigid motion"), x, y)
        }
        _ => panic!("{what}: storage changed under a rigid motion"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check_outcome::CheckStatus;
    use tvf_core::generate::genus_surface;
    use tvf_discretizations::build_complex;

    /// Lemma 1 holds to round-off with mixed-Voronoi masses on the coarse genus-5 plate (416
    /// faces, angles 15.6°–112.5°), whose scalar pencils have eigenvalue pairs `1.4e-10 · λ_max`
    /// apart: the field residual was `2.7e-8 · λ_max` while the dense eigenpairs came from
    /// faer's divide and conquer alone.
    #[test]
    fn lemma1_holds_with_voronoi_masses_on_the_coarse_genus_5_plate() {
        let mesh = genus_surface(5, 2);
        for id in ["conforming-voronoi", "nonconforming-voronoi"] {
            let complex = build_complex(id, None, &mesh).expect("builds");
            for outcome in measure_lemma1(&*complex) {
                assert_eq!(outcome.status, CheckStatus::Passed, "{id}: {outcome:?}");
            }
        }
    }
}
