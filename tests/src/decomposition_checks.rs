//! Checks of the Hodge decomposition and of the harmonic space.

use crate::dense::{generalized_eigenvalues, split_zeros};
use faer::{Mat, Side};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::discretization::sparse::mul_vec;
use tvf_core::discretization::{FieldSpace, HodgeComplex, HodgeOperators};
use tvf_discretizations::HodgeDecomposer;

/// A seeded random field (`2F` coefficients uniform in `[−1, 1]`).
pub fn random_field<H: HodgeComplex>(complex: &H, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..complex.fields().dimension())
        .map(|_| rng.random_range(-1.0..1.0))
        .collect()
}

fn m1_norm<H: HodgeComplex>(complex: &H, x: &[f64]) -> f64 {
    complex.field_inner(x, x).sqrt()
}

fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// Decomposes a random field and a field with known parts and checks: the three parts are
/// mutually `M1`-orthogonal (relative 1e-10), sum back to the input, the integrable part is
/// curl-free (`M2 d1`), the co-integrable part divergence-free (`−M0⁻¹ d0ᵀ M1`), the harmonic
/// part is both and in the kernel of `L`; a pure gradient plus co-gradient is recovered with its
/// potentials.
pub fn check_hodge_decomposition<H: HodgeComplex>(complex: &H, seed: u64) {
    let decomposer = HodgeDecomposer::new(complex).expect("decomposer factors");
    let field = random_field(complex, seed);
    let parts = decomposer
        .decompose(&field)
        .expect("decomposition succeeds");
    let norm = m1_norm(complex, &field);
    let named = [
        ("integrable", &parts.integrable),
        ("co-integrable", &parts.co_integrable),
        ("harmonic", &parts.harmonic),
    ];
    for a in 0..3 {
        for b in a + 1..3 {
            let inner = complex.field_inner(named[a].1, named[b].1);
            assert!(
                inner.abs() <= 1e-10 * norm * norm,
                "{} and {} parts not orthogonal: {inner:e} (|v|² = {:e})",
                named[a].0,
                named[b].0,
                norm * norm
            );
        }
    }
    for (i, &v) in field.iter().enumerate() {
        let sum = parts.integrable[i] + parts.co_integrable[i] + parts.harmonic[i];
        assert!(
            (sum - v).abs() <= 1e-12 * (1.0 + v.abs()),
            "parts do not sum to the input"
        );
    }
    let curl = complex.co_potential_curl();
    let divergence = complex.potential_divergence();
    let laplacian = complex.hodge_laplacian();
    // Operator scale: how large div/curl/L of a unit-size field can be.
    let scale = |matrix: &sprs::CsMat<f64>, x: &[f64]| {
        max_abs(&mul_vec(matrix, &field)) + max_abs(&mul_vec(matrix, x))
    };
    for (what, matrix, part) in [
        ("curl of the integrable part", &curl, &parts.integrable),
        (
            "divergence of the co-integrable part",
            &divergence,
            &parts.co_integrable,
        ),
        ("curl of the harmonic part", &curl, &parts.harmonic),
        (
            "divergence of the harmonic part",
            &divergence,
            &parts.harmonic,
        ),
        (
            "Hodge-Laplacian of the harmonic part",
            &laplacian,
            &parts.harmonic,
        ),
    ] {
        let value = max_abs(&mul_vec(matrix, part));
        let reference = scale(matrix, part);
        assert!(
            value <= 1e-9 * reference,
            "{what}: {value:e} (scale {reference:e})"
        );
    }
    // Known parts: v = d0 f + J G_co g (+ harmonic h from the random field) is recovered.
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    let f: Vec<f64> = parts
        .potential
        .iter()
        .map(|_| rng.random_range(-1.0..1.0))
        .collect();
    let g: Vec<f64> = parts
        .co_potential
        .iter()
        .map(|_| rng.random_range(-1.0..1.0))
        .collect();
    let grad = complex.gradient_field(&f);
    let cograd = complex.co_gradient_field(&g);
    let composed: Vec<f64> = (0..field.len())
        .map(|i| grad[i] + cograd[i] + parts.harmonic[i])
        .collect();
    let again = decomposer
        .decompose(&composed)
        .expect("decomposition succeeds");
    let scale = m1_norm(complex, &composed);
    for (what, got, expected) in [
        ("integrable", &again.integrable, &grad),
        ("co-integrable", &again.co_integrable, &cograd),
        ("harmonic", &again.harmonic, &parts.harmonic),
    ] {
        let difference: Vec<f64> = got
            .iter()
            .zip(expected.iter())
            .map(|(a, b)| a - b)
            .collect();
        let error = m1_norm(complex, &difference);
        assert!(
            error <= 1e-9 * scale,
            "{what} part not recovered: error {error:e}"
        );
    }
}

/// `dim ker L = 2g` by dense eigenvalues of `(S, M1)` (small meshes), and the complex reports
/// the same harmonic dimension.
pub fn check_kernel_is_2g_dense<H: HodgeComplex>(complex: &H, genus: usize) {
    assert_eq!(
        complex.harmonic_dimension(),
        2 * genus,
        "reported harmonic dimension"
    );
    let eigenvalues = generalized_eigenvalues(&complex.dirichlet_energy(), complex.m1());
    let (zeros, _) = split_zeros(&eigenvalues, 1e-9);
    assert_eq!(
        zeros,
        2 * genus,
        "dim ker L (lowest eigenvalues {:?})",
        &eigenvalues[..(2 * genus + 3).min(eigenvalues.len())]
    );
}

/// `dim H = 2g` without dense eigenvalues (any size): the harmonic parts of `2g + 3` random
/// fields span a space whose `M1`-Gram matrix has exactly `2g` eigenvalues above
/// `1e-12 · |v|²`; the harmonic basis is `M1`-orthonormal and harmonic.
pub fn check_kernel_is_2g_sparse<H: HodgeComplex>(complex: &H, genus: usize, seed: u64) {
    assert_eq!(
        complex.harmonic_dimension(),
        2 * genus,
        "reported harmonic dimension"
    );
    let decomposer = HodgeDecomposer::new(complex).expect("decomposer factors");
    let samples = 2 * genus + 3;
    let mut harmonic = Vec::new();
    let mut size = 0.0f64;
    for k in 0..samples {
        let field = random_field(complex, seed + k as u64);
        size = size.max(complex.field_inner(&field, &field));
        harmonic.push(
            decomposer
                .harmonic_part(&field)
                .expect("decomposition succeeds"),
        );
    }
    let gram = Mat::<f64>::from_fn(samples, samples, |i, j| {
        complex.field_inner(&harmonic[i], &harmonic[j])
    });
    let eigenvalues = gram
        .self_adjoint_eigenvalues(Side::Lower)
        .expect("small dense eigenvalues");
    let rank = eigenvalues.iter().filter(|&&x| x > 1e-12 * size).count();
    assert_eq!(
        rank,
        2 * genus,
        "rank of harmonic projections (Gram eigenvalues {eigenvalues:?})"
    );
    let basis = decomposer.harmonic_basis(seed).expect("harmonic basis");
    assert_eq!(basis.len(), 2 * genus);
    let laplacian = complex.hodge_laplacian();
    for (i, a) in basis.iter().enumerate() {
        for (j, b) in basis.iter().enumerate() {
            let expected = if i == j { 1.0 } else { 0.0 };
            let inner = complex.field_inner(a, b);
            assert!(
                (inner - expected).abs() < 1e-10,
                "harmonic basis Gram ({i},{j}) = {inner}"
            );
        }
        let la = mul_vec(&laplacian, a);
        let random = random_field(complex, seed);
        let reference = max_abs(&mul_vec(&laplacian, &random)) / m1_norm(complex, &random);
        assert!(
            max_abs(&la) <= 1e-9 * reference,
            "harmonic basis field {i} not in ker L"
        );
    }
}
