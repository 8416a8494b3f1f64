//! Core checks of the Hodge decomposition and of the harmonic space.

use crate::check_cache::CheckCache;
use crate::check_outcome::{assert_outcomes, CheckOutcome};
use crate::corpus::CorpusMesh;
use crate::dense::split_zeros;
use faer::{Mat, Side};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::discretization::{HodgeComplex, HodgeOperators, LinearOperator};
use tvf_core::mesh::Mesh;
use tvf_discretizations::{HodgeDecomposer, HodgeParts};

/// A seeded random field of the complex's space: `n1` coefficients uniform in `[−1, 1]`, zero
/// on the Dirichlet field nodes (relative forms: boundary edges).
pub fn random_field<H: HodgeComplex + ?Sized>(complex: &H, seed: u64) -> Vec<f64> {
    drawn_field(complex, &mut ChaCha8Rng::seed_from_u64(seed))
}

/// The next random field of `rng` ([`random_field`]'s draws): `n1` values, zero on the Dirichlet
/// field nodes.
fn drawn_field<H: HodgeComplex + ?Sized>(complex: &H, rng: &mut ChaCha8Rng) -> Vec<f64> {
    let fixed = &complex.field_nodes().dirichlet;
    (0..complex.field_dimension())
        .map(|i| {
            let x = rng.random_range(-1.0..1.0);
            if fixed[i] {
                0.0
            } else {
                x
            }
        })
        .collect()
}

/// The `M1` norm `√(xᵀ M1 x)`.
pub fn m1_norm<H: HodgeComplex + ?Sized>(complex: &H, x: &[f64]) -> f64 {
    complex.field_inner(x, x).sqrt()
}

fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// Decomposes a random field and a field with known parts and measures: the three parts are
/// mutually `M1`-orthogonal (relative 1e-10), sum back to the input, the integrable part is
/// curl-free (`co_potential_curl = M2 d1` kills it), the co-integrable part divergence-free
/// (`potential_divergence = −M0⁻¹ d0ᵀ M1` kills it), the harmonic part is both and in the kernel
/// of `L`; a field `d0 f − M1⁻¹ d1ᵀ g + h` is split back into exactly these parts.
pub fn measure_hodge_decomposition<H: HodgeComplex + ?Sized>(
    complex: &H,
    seed: u64,
) -> Vec<CheckOutcome> {
    measure_hodge_decomposition_with(&CheckCache::new(complex), seed)
}

/// [`measure_hodge_decomposition`] with the decomposer of `cache` (factored once for every
/// check of its complex).
pub fn measure_hodge_decomposition_with<H: HodgeComplex + ?Sized>(
    cache: &CheckCache<'_, H>,
    seed: u64,
) -> Vec<CheckOutcome> {
    let complex = cache.complex();
    let decomposer = match cache.decomposer() {
        Ok(decomposer) => decomposer,
        Err(e) => return vec![CheckOutcome::failed("hodge_decomposition", e)],
    };
    let field = random_field(complex, seed);
    let parts = match decomposer.decompose(&field) {
        Ok(parts) => parts,
        Err(e) => return vec![CheckOutcome::failed("hodge_decomposition", e.to_string())],
    };
    let mut outcomes = orthogonality_outcomes(complex, &field, &parts);
    outcomes.extend(operator_outcomes(complex, &field, &parts));
    outcomes.extend(known_parts_outcomes(complex, decomposer, &parts, seed));
    outcomes
}

/// The `parts` of `field` are mutually `M1`-orthogonal and sum back to it.
fn orthogonality_outcomes<H: HodgeComplex + ?Sized>(
    complex: &H,
    field: &[f64],
    parts: &HodgeParts,
) -> Vec<CheckOutcome> {
    let mut outcomes = Vec::new();
    let norm = m1_norm(complex, field);
    let named = [
        ("integrable", &parts.integrable),
        ("co-integrable", &parts.cointegrable),
        ("harmonic", &parts.harmonic),
    ];
    for a in 0..3 {
        for b in a + 1..3 {
            let inner = complex.field_inner(named[a].1, named[b].1);
            outcomes.push(CheckOutcome::at_most(
                format!("orthogonal parts: {} and {}", named[a].0, named[b].0),
                inner.abs(),
                1e-10 * norm * norm,
                format!(
                    "{} and {} parts: inner product {inner:e} (|v|² = {:e})",
                    named[a].0,
                    named[b].0,
                    norm * norm
                ),
            ));
        }
    }
    let worst_sum = field
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            let sum = parts.integrable[i] + parts.cointegrable[i] + parts.harmonic[i];
            (sum - v).abs() / (1.0 + v.abs())
        })
        .fold(0.0f64, f64::max);
    outcomes.push(CheckOutcome::at_most(
        "parts sum to the field",
        worst_sum,
        1e-12,
        format!("max |Σ parts − v| / (1 + |v|) = {worst_sum:e}"),
    ));
    outcomes
}

/// The curl kills the integrable and the harmonic part of `field`, the divergence the
/// co-integrable and the harmonic part, and `L` the harmonic part (relative to how large the
/// operator makes a field of the part's size). Each operator is applied once to the field and
/// its parts together, as one block.
fn operator_outcomes<H: HodgeComplex + ?Sized>(
    complex: &H,
    field: &[f64],
    parts: &HodgeParts,
) -> Vec<CheckOutcome> {
    let checks: [(&LinearOperator, Vec<NamedPart<'_>>); 3] = [
        (
            complex.co_potential_curl(),
            vec![
                ("curl of the integrable part", &parts.integrable),
                ("curl of the harmonic part", &parts.harmonic),
            ],
        ),
        (
            complex.potential_divergence(),
            vec![
                ("divergence of the co-integrable part", &parts.cointegrable),
                ("divergence of the harmonic part", &parts.harmonic),
            ],
        ),
        (
            complex.hodge_laplacian(),
            vec![("Hodge-Laplacian of the harmonic part", &parts.harmonic)],
        ),
    ];
    let mut outcomes = Vec::new();
    for (operator, named) in checks {
        // Column 0 the field, then the parts.
        let columns: Vec<&[f64]> = std::iter::once(field)
            .chain(named.iter().map(|(_, part)| *part))
            .collect();
        let block = Mat::from_fn(field.len(), columns.len(), |i, j| columns[j][i]);
        let applied = operator.apply_block(block.as_ref());
        let largest =
            |j: usize| (0..applied.nrows()).fold(0.0f64, |m, i| m.max(applied[(i, j)].abs()));
        // Operator scale: how large div/curl/L of a unit-size field can be.
        let field_scale = largest(0);
        for (k, (what, _)) in named.iter().enumerate() {
            let value = largest(k + 1);
            let reference = field_scale + value;
            outcomes.push(CheckOutcome::at_most(
                *what,
                value,
                1e-9 * reference,
                format!("{what}: {value:e} (scale {reference:e})"),
            ));
        }
    }
    outcomes
}

/// A part of a decomposition with what the check of it is called.
type NamedPart<'a> = (&'a str, &'a [f64]);

/// Known parts: `v = d0 f − M1⁻¹ d1ᵀ g + h` (seeded random `f`, `g`; `h` the harmonic part of
/// the random field's `parts`) is split back into exactly these parts.
fn known_parts_outcomes<H: HodgeComplex + ?Sized>(
    complex: &H,
    decomposer: &HodgeDecomposer<'_, H>,
    parts: &HodgeParts,
    seed: u64,
) -> Vec<CheckOutcome> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    let f: Vec<f64> = (0..complex.potential_dimension())
        .map(|_| rng.random_range(-1.0..1.0))
        .collect();
    let g: Vec<f64> = (0..complex.co_potential_dimension())
        .map(|_| rng.random_range(-1.0..1.0))
        .collect();
    let grad = complex.gradient_field(&f);
    let cograd = complex.co_gradient_field(&g);
    let composed: Vec<f64> = (0..grad.len())
        .map(|i| grad[i] + cograd[i] + parts.harmonic[i])
        .collect();
    let again = match decomposer.decompose(&composed) {
        Ok(again) => again,
        Err(e) => return vec![CheckOutcome::failed("known parts recovered", e.to_string())],
    };
    let scale = m1_norm(complex, &composed);
    [
        ("integrable", &again.integrable, &grad),
        ("co-integrable", &again.cointegrable, &cograd),
        ("harmonic", &again.harmonic, &parts.harmonic),
    ]
    .into_iter()
    .map(|(what, got, expected)| {
        let difference: Vec<f64> = got.iter().zip(expected).map(|(a, b)| a - b).collect();
        let error = m1_norm(complex, &difference);
        CheckOutcome::at_most(
            format!("known {what} part recovered"),
            error,
            1e-9 * scale,
            format!("{what} part not recovered: error {error:e} (|v| = {scale:e})"),
        )
    })
    .collect()
}

/// The checks of [`measure_hodge_decomposition`], asserted.
pub fn check_hodge_decomposition<H: HodgeComplex + ?Sized>(complex: &H, seed: u64) {
    check_hodge_decomposition_with(&CheckCache::new(complex), seed);
}

/// [`check_hodge_decomposition`] with the decomposer of `cache`.
pub fn check_hodge_decomposition_with<H: HodgeComplex + ?Sized>(
    cache: &CheckCache<'_, H>,
    seed: u64,
) {
    assert_outcomes(&measure_hodge_decomposition_with(cache, seed));
}

/// `dim ker L` = `harmonic_dimension` by dense eigenvalues of `(S, M1)` (small meshes),
/// measured.
pub fn measure_kernel_dimension_dense<H: HodgeComplex + ?Sized>(
    complex: &H,
    harmonic_dimension: usize,
) -> CheckOutcome {
    measure_kernel_dimension_dense_with(&CheckCache::new(complex), harmonic_dimension)
}

/// [`measure_kernel_dimension_dense`] on the spectrum of `L` of `cache`.
pub fn measure_kernel_dimension_dense_with<H: HodgeComplex + ?Sized>(
    cache: &CheckCache<'_, H>,
    harmonic_dimension: usize,
) -> CheckOutcome {
    let eigenvalues = match cache.hodge_spectrum() {
        Ok(eigenvalues) => eigenvalues,
        Err(reason) => {
            let detail = format!("the spectrum of L cannot be computed: {reason}");
            return CheckOutcome::failed("kernel dimension", detail);
        }
    };
    let (zeros, _) = split_zeros(eigenvalues, 1e-9);
    CheckOutcome::count(
        "kernel dimension",
        zeros,
        harmonic_dimension,
        format!(
            "dim ker L = {zeros}, expected {harmonic_dimension} (lowest eigenvalues {:?})",
            &eigenvalues[..(harmonic_dimension + 3).min(eigenvalues.len())]
        ),
    )
}

/// `dim ker L` = the corpus mesh's harmonic dimension (`2g`; `2g + b − 1` per component with
/// boundary) by dense eigenvalues of `(S, M1)` on the free field nodes (small meshes).
pub fn check_kernel_is_2g_dense<H: HodgeComplex + ?Sized, M>(complex: &H, mesh: &CorpusMesh<M>) {
    check_kernel_is_2g_dense_with(&CheckCache::new(complex), mesh);
}

/// [`check_kernel_is_2g_dense`] on the spectrum of `L` of `cache`.
pub fn check_kernel_is_2g_dense_with<H: HodgeComplex + ?Sized, M>(
    cache: &CheckCache<'_, H>,
    mesh: &CorpusMesh<M>,
) {
    assert_outcomes(&[measure_kernel_dimension_dense_with(
        cache,
        mesh.harmonic_dimension,
    )]);
}

/// `dim H = h_c` on every component `c` without dense eigenvalues (any size), `h_c = 2g_c` on a
/// closed component and `2g_c + b_c − 1` on one with `b_c ≥ 1` boundary loops: the harmonic
/// parts of `h_c + 1` random fields supported on component `c` span a space whose `M1`-Gram
/// matrix has exactly `h_c` eigenvalues above `1e-12 · |v|²` (a larger kernel shows as rank
/// `h_c + 1`, a smaller one as a rank below `h_c`: one field beyond `h_c` decides both, since
/// random fields are in general position) (`g_c`, `b_c` from the mesh, their
/// `h_c` must sum to the corpus's stated harmonic dimension); the harmonic basis of the whole
/// mesh is `M1`-orthonormal, `Σ h_c` fields, in the kernel of `L`.
///
/// The random fields of all components are projected together, and the basis is built by
/// [`harmonic_basis_by_blocks`]: one multi-column block per projection instead of one
/// decomposition per field (on the raw bunny, 69k faces, these projections were about half of an
/// open-mesh suite's time). The measured quantities and their tolerances are those of the
/// projections one field at a time; the library's sequential
/// [`HodgeDecomposer::harmonic_basis`] (whose bits `tvf basis` writes) stays checked by
/// [`crate::spectral_checks::check_basis_orthonormal`] and
/// [`crate::open_suite::check_fields_vanish_on_fixed_nodes`].
pub fn check_kernel_is_2g_sparse<H: HodgeComplex + ?Sized, M: Mesh>(
    complex: &H,
    mesh: &CorpusMesh<M>,
    seed: u64,
) {
    check_kernel_is_2g_sparse_with(&CheckCache::new(complex), mesh, seed);
}

/// [`check_kernel_is_2g_sparse`] with the decomposer of `cache`.
pub fn check_kernel_is_2g_sparse_with<H: HodgeComplex + ?Sized, M: Mesh>(
    cache: &CheckCache<'_, H>,
    mesh: &CorpusMesh<M>,
    seed: u64,
) {
    let complex = cache.complex();
    let genera = mesh.component_genera();
    assert_eq!(
        genera.iter().sum::<usize>(),
        mesh.genus,
        "the corpus genus disagrees with the mesh's Euler characteristics"
    );
    let dimensions = mesh.component_harmonic_dimensions();
    assert_eq!(
        dimensions.iter().sum::<usize>(),
        mesh.harmonic_dimension,
        "the corpus harmonic dimension disagrees with the mesh's topology"
    );
    let decomposer = cache
        .decomposer()
        .unwrap_or_else(|e| panic!("decomposer factors: {e}"));
    let field_components = &complex.field_nodes().components;
    let mut fields = Vec::new();
    let mut sizes = vec![0.0f64; dimensions.len()];
    for (component, &dimension) in dimensions.iter().enumerate() {
        for k in 0..dimension + 1 {
            let mut field = random_field(complex, seed + k as u64);
            for (x, &c) in field.iter_mut().zip(field_components) {
                if c != component {
                    *x = 0.0;
                }
            }
            sizes[component] = sizes[component].max(complex.field_inner(&field, &field));
            fields.push(field);
        }
    }
    let mut harmonic = decomposer
        .harmonic_parts(&as_slices(&fields))
        .expect("decomposition succeeds")
        .into_iter();
    for (component, &dimension) in dimensions.iter().enumerate() {
        let samples = dimension + 1;
        let harmonic: Vec<Vec<f64>> = harmonic.by_ref().take(samples).collect();
        let gram = Mat::<f64>::from_fn(samples, samples, |i, j| {
            complex.field_inner(&harmonic[i], &harmonic[j])
        });
        let eigenvalues = gram
            .self_adjoint_eigenvalues(Side::Lower)
            .expect("small dense eigenvalues");
        let size = sizes[component];
        let rank = eigenvalues.iter().filter(|&&x| x > 1e-12 * size).count();
        assert_eq!(
            rank,
            dimension,
            "component {component}: rank of harmonic projections (Gram eigenvalues {eigenvalues:?})"
        );
    }
    let basis = harmonic_basis_by_blocks(decomposer, seed);
    assert_eq!(basis.len(), mesh.harmonic_dimension, "harmonic basis size");
    let laplacian = complex.hodge_laplacian();
    let random = random_field(complex, seed);
    let reference = max_abs(&laplacian.apply(&random)) / m1_norm(complex, &random);
    for (i, a) in basis.iter().enumerate() {
        for (j, b) in basis.iter().enumerate() {
            let expected = if i == j { 1.0 } else { 0.0 };
            let inner = complex.field_inner(a, b);
            assert!(
                (inner - expected).abs() < 1e-10,
                "harmonic basis Gram ({i},{j}) = {inner}"
            );
        }
        let la = max_abs(&laplacian.apply(a));
        assert!(
            la <= 1e-9 * reference,
            "harmonic basis field {i} not in ker L: |L h| = {la:e} (scale {reference:e})"
        );
    }
}

/// An `M1`-orthonormal basis of the harmonic fields by the arithmetic of
/// [`HodgeDecomposer::harmonic_basis`] — the same seeded random fields (zero on the Dirichlet
/// field nodes), projected onto `H`, two passes of Gram–Schmidt in `M1` each followed by a
/// re-projection, normalised — with every projection of all fields done as one block
/// ([`HodgeDecomposer::harmonic_parts`]): three block decompositions in all instead of three
/// decompositions a field. Within a pass each field is orthogonalised against the fields before
/// it of the same pass (sequentially it was against their final form); the re-projection after
/// each pass is what makes the result harmonic to round-off either way, and the check that reads
/// this basis asserts orthonormality (`1e-10`) and `L h ≈ 0` of the final fields, which the block
/// solves must reach as the single ones do.
pub fn harmonic_basis_by_blocks<H: HodgeComplex + ?Sized>(
    decomposer: &HodgeDecomposer<'_, H>,
    seed: u64,
) -> Vec<Vec<f64>> {
    let complex = decomposer.complex();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let random: Vec<Vec<f64>> = (0..complex.topology().harmonic_dimension)
        .map(|_| drawn_field(complex, &mut rng))
        .collect();
    let project = |fields: &[Vec<f64>]| {
        decomposer
            .harmonic_parts(&as_slices(fields))
            .expect("harmonic projections")
    };
    let mut basis = project(&random);
    for _pass in 0..2 {
        for i in 0..basis.len() {
            let (before, rest) = basis.split_at_mut(i);
            let h = &mut rest[0];
            for b in before.iter() {
                let coefficient = complex.field_inner(h, b) / complex.field_inner(b, b);
                h.iter_mut().zip(b).for_each(|(x, y)| *x -= coefficient * y);
            }
        }
        basis = project(&basis);
    }
    for h in &mut basis {
        let norm = m1_norm(complex, h);
        h.iter_mut().for_each(|x| *x /= norm);
    }
    basis
}

/// Borrowed views of owned vectors.
fn as_slices(vectors: &[Vec<f64>]) -> Vec<&[f64]> {
    vectors.iter().map(Vec::as_slice).collect()
}
