//! Spectral filters: identity, energy decrease of low-pass filters, family separation, and the
//! SPEC grammar. Complete bases on a small torus (genus 1: two harmonic fields) so every
//! property can be checked against the exact Hodge decomposition.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use tvf_core::discretization::{HodgeComplex, HodgeOperators, LinearOperator};
use tvf_core::generate::torus;
use tvf_discretizations::{Conforming, HodgeDecomposer, MassLumping, Nonconforming};
use tvf_spectral::{
    compute_basis, BasisRequest, FieldFamily, FilterSpecError, FrequencyResponse, SpectralBasis,
    SpectralFilter,
};

fn small_torus() -> tvf_core::TriangleMesh {
    torus(1.0, 0.45, 9, 6).expect("valid torus parameters")
}

fn random_field(dimension: usize, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..dimension)
        .map(|_| rng.random_range(-1.0..1.0))
        .collect()
}

/// The first `d` fields of a basis (a truncated basis).
fn truncated(basis: &SpectralBasis, d: usize) -> SpectralBasis {
    SpectralBasis::new(
        basis.eigenvalues()[..d].to_vec(),
        basis.families()[..d].to_vec(),
        basis.fields().subcols(0, d).to_owned(),
        basis.field_mass().clone(),
    )
    .expect("a prefix of a basis is a basis")
}

fn max_abs_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

fn max_abs(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m, x| m.max(x.abs()))
}

#[test]
fn identity_filter_returns_the_field_with_a_complete_basis() {
    let mesh = small_torus();
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let basis = compute_basis(&complex, &BasisRequest::complete()).unwrap();
    assert_eq!(basis.len(), 2 * mesh.face_count());
    let filter = SpectralFilter {
        rest_gain: 0.0, // nothing is left for the rest field to carry
        ..SpectralFilter::identity()
    };
    for seed in 0..3 {
        let field = random_field(basis.field_dimension(), seed);
        let out = filter.apply(&basis, &field).unwrap();
        assert!(
            max_abs_difference(&out.field, &field) < 1e-10 * max_abs(&field),
            "identity changed the field by {}",
            max_abs_difference(&out.field, &field)
        );
        assert!(out.rest_norm < 1e-10);
    }
}

#[test]
fn identity_filter_with_unit_rest_gain_keeps_what_a_truncated_basis_cannot_represent() {
    let mesh = small_torus();
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let basis = truncated(
        &compute_basis(&complex, &BasisRequest::complete()).unwrap(),
        40,
    );
    let field = random_field(basis.field_dimension(), 7);
    let out = SpectralFilter::identity().apply(&basis, &field).unwrap();
    assert!(out.rest_norm > 0.1 * basis.inner_product(&field, &field).sqrt());
    assert!(max_abs_difference(&out.field, &field) < 1e-13 * max_abs(&field));
    // With rest gain 0 the output is the projection U Uᵀ M_X v: its rest field vanishes.
    let projection = SpectralFilter {
        rest_gain: 0.0,
        ..SpectralFilter::identity()
    }
    .apply(&basis, &field)
    .unwrap();
    let again = SpectralFilter::identity()
        .apply(&basis, &projection.field)
        .unwrap();
    assert!(again.rest_norm < 1e-10 * out.rest_norm);
    let removed: Vec<f64> = field
        .iter()
        .zip(&projection.field)
        .map(|(a, b)| a - b)
        .collect();
    assert!((basis.inner_product(&removed, &removed).sqrt() - out.rest_norm).abs() < 1e-10);
}

fn dirichlet(s: &LinearOperator, v: &[f64]) -> f64 {
    s.apply(v).iter().zip(v).map(|(a, b)| a * b).sum()
}

fn check_low_pass_energy<H: HodgeComplex + ?Sized>(complex: &H) {
    let s = complex.dirichlet_energy();
    let complete = compute_basis(complex, &BasisRequest::complete()).unwrap();
    let partial = truncated(&complete, 60);
    let filters = [
        FrequencyResponse::LowPass { t: 0.01 },
        FrequencyResponse::LowPass { t: 0.3 },
        FrequencyResponse::Cutoff { f: 3.0 },
        FrequencyResponse::BandPass { lo: 1.0, hi: 4.0 },
        "curve:0,1;2,0.2;4,0.9;8,0".parse().unwrap(),
    ];
    for basis in [&complete, &partial] {
        for seed in 0..5 {
            let field = random_field(basis.field_dimension(), 100 + seed);
            let before = dirichlet(s, &field);
            for response in &filters {
                for rest_gain in [0.0, 0.5, 1.0] {
                    let filter = SpectralFilter {
                        harmonic_gain: 0.7,
                        ..SpectralFilter::both(response.clone(), rest_gain)
                    };
                    assert!(response.is_contraction());
                    let after = dirichlet(s, &filter.apply(basis, &field).unwrap().field);
                    assert!(
                        after <= before * (1.0 + 1e-10),
                        "{response:?} (rest gain {rest_gain}, d = {}) raised the Dirichlet energy {before} to {after}",
                        basis.len()
                    );
                }
            }
            // A strong low-pass removes most of the energy; a high-pass never lowers it.
            let smooth = SpectralFilter::both(FrequencyResponse::LowPass { t: 1.0 }, 0.0)
                .apply(basis, &field)
                .unwrap();
            assert!(dirichlet(s, &smooth.field) < 0.05 * before);
            let sharp = SpectralFilter::both(FrequencyResponse::HighPass { t: 0.1 }, 1.0)
                .apply(basis, &field)
                .unwrap();
            assert!(dirichlet(s, &sharp.field) >= before * (1.0 - 1e-10));
        }
    }
}

#[test]
fn low_pass_filters_never_increase_the_dirichlet_energy_conforming() {
    let mesh = small_torus();
    check_low_pass_energy(&Conforming::new(&mesh, MassLumping::Barycentric).unwrap());
}

#[test]
fn low_pass_filters_never_increase_the_dirichlet_energy_nonconforming() {
    let mesh = small_torus();
    check_low_pass_energy(&Nonconforming::new(&mesh, MassLumping::Barycentric).unwrap());
}

#[test]
fn filtering_the_integrable_family_leaves_the_other_parts_unchanged() {
    let mesh = small_torus();
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let basis = compute_basis(&complex, &BasisRequest::complete()).unwrap();
    assert_eq!(
        basis
            .families()
            .iter()
            .filter(|f| **f == FieldFamily::Harmonic)
            .count(),
        2
    );
    let decomposer = HodgeDecomposer::new(&complex).unwrap();
    for (seed, response) in [
        FrequencyResponse::LowPass { t: 0.2 },
        FrequencyResponse::HighPass { t: 0.2 },
        FrequencyResponse::Cutoff { f: 0.0 },
    ]
    .into_iter()
    .enumerate()
    {
        let field = random_field(basis.field_dimension(), 200 + seed as u64);
        let filter = SpectralFilter {
            integrable: response.clone(),
            ..SpectralFilter::identity()
        };
        let out = filter.apply(&basis, &field).unwrap();
        let before = decomposer.decompose(&field).unwrap();
        let after = decomposer.decompose(&out.field).unwrap();
        let scale = max_abs(&field);
        assert!(max_abs_difference(&before.cointegrable, &after.cointegrable) < 1e-10 * scale);
        assert!(max_abs_difference(&before.harmonic, &after.harmonic) < 1e-10 * scale);
        let change = max_abs_difference(&before.integrable, &after.integrable);
        assert!(
            change > 1e-3 * scale,
            "{response:?} did not change the integrable part"
        );
    }
}

#[test]
fn filter_specs_parse_and_refuse_clearly() {
    let ok = |s: &str| s.parse::<FrequencyResponse>().unwrap();
    assert_eq!(ok("identity"), FrequencyResponse::Identity);
    assert_eq!(ok(" LowPass:t=0.5 "), FrequencyResponse::LowPass { t: 0.5 });
    assert_eq!(ok("highpass:t=2"), FrequencyResponse::HighPass { t: 2.0 });
    assert_eq!(
        ok("bandpass:hi=3,lo=1"),
        FrequencyResponse::BandPass { lo: 1.0, hi: 3.0 }
    );
    assert_eq!(ok("cutoff:f=4"), FrequencyResponse::Cutoff { f: 4.0 });
    let curve = ok("curve:0,1;5,0.5;10,0;");
    assert_eq!(curve.gain(2.5), 0.75);
    assert_eq!(curve.gain(20.0), 0.0);

    let err = |s: &str| s.parse::<FrequencyResponse>().unwrap_err();
    assert!(matches!(err(""), FilterSpecError::Empty));
    assert!(matches!(
        err("blur:t=1"),
        FilterSpecError::UnknownKind { .. }
    ));
    assert!(matches!(
        err("lowpass"),
        FilterSpecError::MissingParameter { name: "t", .. }
    ));
    assert!(matches!(
        err("lowpass:s=1"),
        FilterSpecError::UnexpectedParameter { .. }
    ));
    assert!(matches!(
        err("lowpass:t=1,t=2"),
        FilterSpecError::UnexpectedParameter { .. }
    ));
    assert!(matches!(
        err("lowpass:t=-1"),
        FilterSpecError::BadNumber { .. }
    ));
    assert!(matches!(
        err("lowpass:t=nan"),
        FilterSpecError::BadNumber { .. }
    ));
    assert!(matches!(
        err("bandpass:lo=3,hi=1"),
        FilterSpecError::BandOrder { .. }
    ));
    assert!(matches!(
        err("identity:x"),
        FilterSpecError::UnexpectedParameter { .. }
    ));
    assert!(matches!(err("curve:"), FilterSpecError::EmptyCurve));
    assert!(matches!(
        err("curve:0,1;x,2"),
        FilterSpecError::BadPoint { index: 1, .. }
    ));
    assert!(matches!(
        err("curve:0,1;0,2"),
        FilterSpecError::UnsortedControlPoints { .. }
    ));
    assert!(matches!(
        err("curve:0,-1"),
        FilterSpecError::BadControlPoint { .. }
    ));
    let message = err("lowpass:s=1").to_string();
    assert!(message.contains("lowpass:t="), "{message}");
}

#[test]
fn drawn_curves_load_from_json_files() {
    let folder = tempfile::tempdir().unwrap();
    let object = folder.path().join("curve.json");
    std::fs::write(&object, r#"{"points": [[0, 1], [4, 2], [8, 0]]}"#).unwrap();
    let response: FrequencyResponse = format!("@{}", object.display()).parse().unwrap();
    assert_eq!(response.gain(2.0), 1.5);
    assert_eq!(response.max_gain(), 2.0);
    let bare = folder.path().join("bare.json");
    std::fs::write(&bare, "[[1, 0.5]]").unwrap();
    let response: FrequencyResponse = format!("@{}", bare.display()).parse().unwrap();
    assert_eq!(response.gain(100.0), 0.5);

    let broken = folder.path().join("broken.json");
    std::fs::write(&broken, r#"{"points": [[0, 1], [4]]}"#).unwrap();
    let error = format!("@{}", broken.display())
        .parse::<FrequencyResponse>()
        .unwrap_err();
    assert!(matches!(error, FilterSpecError::Json { .. }));
    assert!(error.to_string().contains("broken.json"), "{error}");
    let missing = folder.path().join("missing.json");
    let error = format!("@{}", missing.display())
        .parse::<FrequencyResponse>()
        .unwrap_err();
    assert!(matches!(error, FilterSpecError::FileRead { .. }));
}

#[test]
fn bad_gains_and_fields_are_refused() {
    let mesh = small_torus();
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let basis = truncated(
        &compute_basis(&complex, &BasisRequest::complete()).unwrap(),
        10,
    );
    let field = random_field(basis.field_dimension(), 1);
    let negative = SpectralFilter {
        rest_gain: -1.0,
        ..SpectralFilter::identity()
    };
    assert!(negative.apply(&basis, &field).is_err());
    assert!(SpectralFilter::identity()
        .apply(&basis, &field[1..])
        .is_err());
    let mut bad = field.clone();
    bad[3] = f64::NAN;
    assert!(SpectralFilter::identity().apply(&basis, &bad).is_err());
}
