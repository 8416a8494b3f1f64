//! Cross-discretization facts of `docs/conventions.md` that the per-discretization suite cannot
//! state alone: the published icosphere eigenvalues, the nonconforming Hodge–Laplacian having
//! the spectrum of the conforming one, and the wrapper complex's spectrum following its `M2`.

use tvf_conformance::dense::{free_eigenproblem, generalized_eigenvalues, split_zeros};
use tvf_conformance::scaled_co_potentials::ScaledCoPotentials;
use tvf_conformance::spectral_checks::{check_same_spectrum, hodge_spectrum};
use tvf_core::discretization::{Eigenproblem, HodgeComplex, HodgeOperators, NodeSpace};
use tvf_core::generate::{genus_surface, icosphere, torus};
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};

/// The eigenvalues of a scalar eigenproblem on the free nodes of its space (dense).
fn spectrum(problem: &Eigenproblem, nodes: &NodeSpace) -> Vec<f64> {
    let (a, m, _) = free_eigenproblem(problem, nodes);
    generalized_eigenvalues(&a, &m).expect("the dense eigenvalues")
}

/// `docs/conventions.md`: on the 320-face icosphere (barycentric lumping) the lowest three nonzero P1
/// eigenvalues are ≈ 2.000 and the lowest three Crouzeix–Raviart ones ≈ 2.046 (verified there
/// against libigl), so the lowest six of `L` are these.
#[test]
fn icosphere_320_lowest_eigenvalues_match_math_md() {
    let mesh = icosphere(2);
    assert_eq!(mesh.face_count(), 320);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).expect("builds");
    let (_, p1) = split_zeros(
        &spectrum(&complex.exact_eigenproblem(), complex.potential_nodes()),
        1e-9,
    );
    let (_, cr) = split_zeros(
        &spectrum(
            &complex.co_exact_eigenproblem(),
            complex.co_potential_nodes(),
        ),
        1e-9,
    );
    for &lambda in &p1[..3] {
        assert!((lambda - 2.000).abs() < 5e-4, "P1: {:?}", &p1[..3]);
    }
    for &lambda in &cr[..3] {
        assert!((lambda - 2.046).abs() < 5e-4, "CR: {:?}", &cr[..3]);
    }
    let (zeros, l) = split_zeros(&hodge_spectrum(&complex), 1e-9);
    assert_eq!(zeros, 0);
    let mut six: Vec<f64> = p1[..3].iter().chain(&cr[..3]).copied().collect();
    six.sort_by(f64::total_cmp);
    for (a, b) in l[..6].iter().zip(&six) {
        assert!((a - b).abs() < 1e-9, "L lowest {:?} vs {six:?}", &l[..6]);
    }
}

/// The nonconforming Hodge–Laplacian has the same spectrum as the conforming one (same lumping):
/// both are the union of the P1 and CR spectra plus `2g` zeros.
#[test]
fn nonconforming_spectrum_equals_conforming_spectrum() {
    for mesh in [
        icosphere(2),
        torus(1.0, 0.4, 16, 8).expect("valid torus"),
        genus_surface(2, 2),
    ] {
        for lumping in [MassLumping::Barycentric, MassLumping::Voronoi] {
            let a = Conforming::new(&mesh, lumping).expect("builds");
            let b = Nonconforming::new(&mesh, lumping).expect("builds");
            check_same_spectrum(&a, &b);
        }
    }
}

/// Scaling `M2⁻¹` by 2 halves the co-exact eigenvalues, leaves the exact ones, and the spectrum
/// of the wrapper's own `L` is the union of the inner P1 spectrum and the halved CR spectrum (a
/// wrapper that forwarded its inner complex's operator cache would keep the inner `L`).
#[test]
fn scaled_co_potentials_spectrum_follows_its_own_m2() {
    for (mesh, genus) in [
        (icosphere(2), 0),
        (torus(1.0, 0.4, 16, 8).expect("valid torus"), 1),
    ] {
        let inner = Conforming::new(&mesh, MassLumping::Barycentric).expect("builds");
        let nonzero = |problem: Eigenproblem, nodes: &NodeSpace| {
            split_zeros(&spectrum(&problem, nodes), 1e-9).1
        };
        let p1 = nonzero(inner.exact_eigenproblem(), inner.potential_nodes());
        let cr = nonzero(inner.co_exact_eigenproblem(), inner.co_potential_nodes());
        let inner_spectrum = hodge_spectrum(&inner);
        let scaled = ScaledCoPotentials::new(inner, 2.0).expect("positive masses");
        assert_eq!(
            nonzero(scaled.exact_eigenproblem(), scaled.potential_nodes()),
            p1
        );
        let scaled_cr = nonzero(scaled.co_exact_eigenproblem(), scaled.co_potential_nodes());
        let max = cr.last().copied().unwrap_or(0.0);
        for (k, (a, b)) in scaled_cr.iter().zip(&cr).enumerate() {
            assert!(
                (a - b / 2.0).abs() <= 1e-9 * max,
                "co-exact eigenvalue {k}: {a} vs {b}/2"
            );
        }
        let (zeros, l) = split_zeros(&hodge_spectrum(&scaled), 1e-9);
        assert_eq!(zeros, 2 * genus);
        let mut union: Vec<f64> = p1.iter().chain(&scaled_cr).copied().collect();
        union.sort_by(f64::total_cmp);
        assert_eq!(l.len(), union.len());
        let max = l.last().copied().unwrap_or(0.0);
        for (k, (a, b)) in l.iter().zip(&union).enumerate() {
            assert!(
                (a - b).abs() <= 1e-9 * max,
                "eigenvalue {k} of L: {a}, union {b}"
            );
        }
        let lowest_inner = inner_spectrum[2 * genus];
        assert!(
            l[0] < 0.75 * lowest_inner,
            "the halved CR eigenvalues must show in L: {} vs inner {lowest_inner}",
            l[0]
        );
    }
}
