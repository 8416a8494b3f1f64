//! Spectral checks (dense, small meshes) and intrinsic invariance.

use crate::dense::{generalized_eigenvalues, split_zeros};
use crate::reference_formulas::assert_matrices_close;
use tvf_core::discretization::{FunctionSpace, HodgeComplex, HodgeOperators};

fn hodge_spectrum<H: HodgeComplex>(complex: &H) -> Vec<f64> {
    generalized_eigenvalues(&complex.dirichlet_energy(), complex.m1())
}

/// The nonzero spectrum of `L` is the union of the nonzero spectra of the exact pair
/// `(d0ᵀ M1 d0, M0)` and the co-exact pair (`(Sc, M)` and `(S*c, M*)` for P1/CR), entry for
/// entry within `1e-9 · λ_max`; the zeros number `2g`, `#components` and `#components`.
pub fn check_spectrum_union<H: HodgeComplex>(complex: &H, genus: usize) {
    let (l_zeros, l_rest) = split_zeros(&hodge_spectrum(complex), 1e-9);
    let exact = complex.exact_eigenproblem();
    let co_exact = complex.co_exact_eigenproblem();
    let (e_zeros, e_rest) = split_zeros(
        &generalized_eigenvalues(&exact.stiffness, &exact.mass),
        1e-9,
    );
    let (c_zeros, c_rest) = split_zeros(
        &generalized_eigenvalues(&co_exact.stiffness, &co_exact.mass),
        1e-9,
    );
    let components = complex.component_count();
    assert_eq!(l_zeros, 2 * genus, "zeros of L");
    assert_eq!(e_zeros, components, "zeros of the exact pair");
    assert_eq!(c_zeros, components, "zeros of the co-exact pair");
    let mut union: Vec<f64> = e_rest.iter().chain(&c_rest).copied().collect();
    union.sort_by(f64::total_cmp);
    assert_eq!(union.len(), l_rest.len(), "number of nonzero eigenvalues");
    let max = l_rest.last().copied().unwrap_or(0.0);
    for (k, (a, b)) in l_rest.iter().zip(&union).enumerate() {
        assert!(
            (a - b).abs() <= 1e-9 * max,
            "eigenvalue {k}: L has {a}, the union {b}"
        );
    }
}

/// Two complexes have the same Hodge–Laplacian spectrum (e.g. conforming vs nonconforming with
/// the same lumping), within `1e-9 · λ_max`.
pub fn check_same_spectrum<A: HodgeComplex, B: HodgeComplex>(a: &A, b: &B) {
    let sa = hodge_spectrum(a);
    let sb = hodge_spectrum(b);
    assert_eq!(sa.len(), sb.len());
    let max = sa.last().copied().unwrap_or(0.0);
    for (k, (x, y)) in sa.iter().zip(&sb).enumerate() {
        assert!(
            (x - y).abs() <= 1e-9 * max,
            "eigenvalue {k}: {} has {x}, {} has {y}",
            a.name(),
            b.name()
        );
    }
}

/// On a unit icosphere the smooth spectrum starts `0 (none), 2 (×3 per family), 6, ...`: the
/// lowest six eigenvalues of `L` lie in `[1.9, 2.1]` and the seventh above 5.
pub fn check_sphere_spectrum<H: HodgeComplex>(complex: &H) {
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

/// Two complexes on rigidly moved copies of one mesh have the same stiffness matrices, masses and
/// (if `dense`) the same Hodge–Laplacian spectrum.
pub fn check_rigid_motion_invariance<H: HodgeComplex>(original: &H, moved: &H, dense: bool) {
    assert_matrices_close(
        "potential stiffness after a rigid motion",
        &moved.potential_stiffness(),
        &original.potential_stiffness(),
    );
    assert_matrices_close(
        "co-potential stiffness after a rigid motion",
        &moved.co_potential_stiffness(),
        &original.co_potential_stiffness(),
    );
    for (what, a, b) in [
        ("M0", moved.m0(), original.m0()),
        ("M1", moved.m1(), original.m1()),
        (
            "M_co",
            moved.co_potentials().mass(),
            original.co_potentials().mass(),
        ),
    ] {
        for (x, y) in a.iter().zip(b) {
            assert!(
                (x - y).abs() <= 1e-10 * y.abs(),
                "{what} changed under a rigid motion"
            );
        }
    }
    if dense {
        check_same_spectrum(original, moved);
    }
}
