//! Spectral analysis: the coefficient energies of each family agree with the exact Hodge
//! decomposition when the basis is complete, and the rest field carries the remainder when not.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use tvf_core::discretization::HodgeOperators;
use tvf_core::generate::torus;
use tvf_discretizations::{Conforming, HodgeDecomposer, MassLumping};
use tvf_spectral::{compute_basis, BasisRequest, EnergySplit, FieldFamily, SpectralAnalysis};

fn random_field(dimension: usize, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..dimension)
        .map(|_| rng.random_range(-1.0..1.0))
        .collect()
}

#[test]
fn family_energies_match_the_hodge_decomposition_with_a_complete_basis() {
    let mesh = torus(1.0, 0.45, 9, 6).unwrap();
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let basis = compute_basis(&complex, &BasisRequest::complete()).unwrap();
    let decomposer = HodgeDecomposer::new(&complex).unwrap();
    let s = complex.dirichlet_energy();
    for seed in 0..3 {
        let field = random_field(basis.field_dimension(), seed);
        let analysis = SpectralAnalysis::new(&basis, &field).unwrap();
        let exact =
            EnergySplit::of_hodge_parts(&decomposer.decompose(&field).unwrap(), basis.field_mass());
        let total = analysis.field_energy;
        assert!((analysis.energy.total() - total).abs() < 1e-10 * total);
        assert!(analysis.energy.rest < 1e-10 * total);
        assert!((analysis.energy.integrable - exact.integrable).abs() < 1e-9 * total);
        assert!((analysis.energy.cointegrable - exact.cointegrable).abs() < 1e-9 * total);
        assert!((analysis.energy.harmonic - exact.harmonic).abs() < 1e-9 * total);
        assert!(analysis.energy.harmonic > 0.0);
        let dirichlet: f64 = s.apply(&field).iter().zip(&field).map(|(a, b)| a * b).sum();
        assert!((analysis.represented_dirichlet_energy - dirichlet).abs() < 1e-9 * dirichlet);
        assert_eq!(analysis.entries.len(), basis.len());
        assert!(analysis
            .entries
            .windows(2)
            .all(|w| w[0].frequency <= w[1].frequency));
        assert_eq!(
            analysis.family(FieldFamily::Integrable).count(),
            mesh.vertex_count() - 1
        );
        assert_eq!(
            analysis.family(FieldFamily::Cointegrable).count(),
            mesh.edge_count() - 1
        );
    }
}

#[test]
fn a_truncated_basis_puts_the_remainder_into_the_rest_field() {
    let mesh = torus(1.0, 0.45, 9, 6).unwrap();
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let basis = compute_basis(&complex, &BasisRequest::pairs(10)).unwrap();
    let field = random_field(basis.field_dimension(), 9);
    let analysis = SpectralAnalysis::new(&basis, &field).unwrap();
    let total = analysis.field_energy;
    assert!((analysis.energy.total() - total).abs() < 1e-10 * total);
    assert!(analysis.relative_rest_norm() > 0.5);
    let exact = EnergySplit::of_hodge_parts(
        &HodgeDecomposer::new(&complex)
            .unwrap()
            .decompose(&field)
            .unwrap(),
        basis.field_mass(),
    );
    // The represented part of each family is at most its exact energy; the harmonic part is
    // represented completely.
    assert!(analysis.energy.integrable <= exact.integrable * (1.0 + 1e-10));
    assert!(analysis.energy.cointegrable <= exact.cointegrable * (1.0 + 1e-10));
    assert!((analysis.energy.harmonic - exact.harmonic).abs() < 1e-9 * total);
}
