//! [`compute_basis`]: the Fourier basis of tangent fields (Section 6 of the paper) for any
//! [`HodgeComplex`].

use crate::basis_request::{BasisRequest, BasisSize, BasisStage};
use crate::eigenfunction_basis::EigenfunctionBasis;
use crate::family_split::split_families;
use crate::harmonic_fields::harmonic_fields;
use crate::scalar_spectrum::{free_nodes, ScalarEigenpairs, ScalarSpectrum};
use crate::{BasisError, FieldFamily, SpectralBasis};
use faer::Mat;
use rayon::prelude::*;
use std::cell::Cell;
use std::time::Instant;
use tvf_core::discretization::sparse::mul_vec;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};

/// How a basis computation went: sizes, accuracy and cost.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct BasisReport {
    /// Number of harmonic fields (`2g`).
    pub harmonic_dimension: usize,
    /// `max |Γᵀ M_X Γ − I|` of the harmonic fields.
    pub harmonic_orthonormality_error: f64,
    /// `max ‖L Γ‖_{M_X}` of the harmonic fields (distance from the kernel of `L`).
    pub harmonic_kernel_residual: f64,
    /// Integrable eigenfields in the basis.
    pub integrable_count: usize,
    /// Co-integrable eigenfields in the basis.
    pub cointegrable_count: usize,
    /// The dropped kernel eigenvalues of the potential problem (one per component, ≈ 0).
    pub potential_kernel_eigenvalues: Vec<f64>,
    /// The dropped kernel eigenvalues of the co-potential problem (one per component, ≈ 0).
    pub co_potential_kernel_eigenvalues: Vec<f64>,
    /// Largest relative residual `‖Ax − λMx‖ / (‖A‖‖x‖)` the eigensolver reported.
    pub max_solver_residual: f64,
    /// Sparse factorizations used by the eigensolver.
    pub factorizations: usize,
    /// Single-vector solves used by the eigensolver.
    pub solves: usize,
    /// Eigensolver calls: one per family, each with its exact count.
    pub eigensolver_calls: usize,
    /// For [`BasisSize::Fields`] and [`BasisSize::MaxEigenvalue`] split by inertia counts: the
    /// threshold `t` (units of λ, 1/length²) such that exactly the non-zero eigenvalues of both
    /// families strictly below `t` were computed. `None` when the request fixed the counts
    /// (pairs, complete, tiny meshes solved densely).
    pub split_threshold: Option<f64>,
    /// Sparse `LDLᵀ` factorizations spent counting eigenvalues below candidate thresholds.
    pub counting_factorizations: usize,
    /// Wall-clock seconds spent counting (included in [`BasisReport::seconds`]).
    pub counting_seconds: f64,
    /// Non-zero eigenpairs of the potential problem the eigensolver computed (at least
    /// [`BasisReport::integrable_count`]; the difference was computed in vain).
    pub integrable_computed: usize,
    /// Non-zero eigenpairs of the co-potential problem the eigensolver computed (at least
    /// [`BasisReport::cointegrable_count`]).
    pub cointegrable_computed: usize,
    /// Wall-clock seconds of the whole computation.
    pub seconds: f64,
}

impl BasisReport {
    /// Adds one eigensolver call's factorizations and solves.
    fn add_solver_counts(&mut self, pairs: &ScalarEigenpairs) {
        self.factorizations += pairs.factorizations;
        self.solves += pairs.solves;
        self.eigensolver_calls += 1;
    }
}

/// The Fourier basis of `complex` as requested, with dense `2F × d` fields (the eigenfunctions
/// and an `f32` copy too if the request asks for them), sorted by eigenvalue and labelled.
///
/// Steps (Section 6): the `2g` harmonic fields by projecting seeded random fields; the lowest
/// eigenpairs `(λ, φ)` of `(d0ᵀ M1 d0, M0)` and `(μ, ψ)` of `(d1 M1⁻¹ d1ᵀ, M2⁻¹)` (sparse
/// spectrum-slicing Lanczos, dense for small problems, both at once), the constant
/// eigenfunctions (one per connected component, found by count) dropped; for `Fields` and
/// `MaxEigenvalue` requests each family's number of eigenpairs is counted exactly beforehand by
/// Sylvester's law of inertia (every eigenvalue of both below one threshold), so each family is
/// solved once and the selection is provably the lowest of the union; by Lemma 1 `Φ = d0 φ / ‖d0 φ‖` and
/// `Ψ = −M1⁻¹ d1ᵀ ψ / ‖M1⁻¹ d1ᵀ ψ‖` (finite elements: `J G_co ψ` normalised) are eigenfields of `L` with eigenvalues `λ`, `μ`.
///
/// On a mesh with boundary the scalar problems are those of the complex's boundary condition
/// (Dirichlet eigenfunctions on the space whose boundary values are fixed, Neumann on the other)
/// and there are `2g + b − 1` harmonic fields per component.
///
/// Errors: [`BasisError::InvalidRequest`], solver failures.
pub fn compute_basis<H: HodgeComplex + ?Sized>(
    complex: &H,
    request: &BasisRequest<'_>,
) -> Result<SpectralBasis, BasisError> {
    let start = Instant::now();
    let (compact, mut report) = compute_eigenfunction_basis(complex, request)?;
    request.report(BasisStage::Assembling, 0, compact.len());
    let fields = compact.dense_fields(complex);
    let mut basis = SpectralBasis::new(
        compact.eigenvalues().to_vec(),
        compact.families().to_vec(),
        fields,
        complex.m1().values().to_vec(),
    )?;
    if request.single_precision_copy {
        basis.store_single_precision_copy();
    }
    if request.keep_eigenfunctions {
        basis.attach_eigenfunctions(compact);
    }
    request.report(BasisStage::Assembling, basis.len(), basis.len());
    report.seconds = start.elapsed().as_secs_f64();
    basis.attach_report(report);
    Ok(basis)
}

/// The Fourier basis in compact form (eigenfunctions instead of dense fields, see
/// [`EigenfunctionBasis`]) and the report of its computation. Same steps and errors as
/// [`compute_basis`], without forming the dense fields.
pub fn compute_eigenfunction_basis<H: HodgeComplex + ?Sized>(
    complex: &H,
    request: &BasisRequest<'_>,
) -> Result<(EigenfunctionBasis, BasisReport), BasisError> {
    let start = Instant::now();
    let (potential_nodes, co_potential_nodes) =
        (complex.potential_nodes(), complex.co_potential_nodes());
    let exact = ScalarSpectrum::new(
        "potential",
        complex.exact_eigenproblem(),
        &free_nodes(potential_nodes),
        potential_nodes.kernel_dimension(),
    );
    let co_exact = ScalarSpectrum::new(
        "co-potential",
        complex.co_exact_eigenproblem(),
        &free_nodes(co_potential_nodes),
        co_potential_nodes.kernel_dimension(),
    );
    let h = complex.topology().harmonic_dimension;
    let area = complex.total_area();
    // Exact counts per family up front (inertia), so each family is solved once.
    let split = split_families(request.size, h, &exact, &co_exact, area)?;
    let (ka, kb) = (split.potential, split.co_potential);

    request.report(BasisStage::Harmonic, 0, h);
    let harmonic = harmonic_fields(complex, request.seed)?;
    request.report(BasisStage::Harmonic, h, h);

    let mut report = BasisReport {
        harmonic_dimension: h,
        harmonic_orthonormality_error: harmonic.orthonormality_error,
        harmonic_kernel_residual: harmonic.kernel_residual,
        split_threshold: split.threshold,
        counting_factorizations: split.factorizations,
        counting_seconds: split.seconds,
        ..BasisReport::default()
    };
    // Each family's eigensolver gets its own seed, derived from the request's (salts 2 and 3
    // keep the seeds, and so the bases, of earlier versions).
    let family_seed = |salt: u64| request.seed ^ salt.wrapping_mul(0x9e37_79b9_7f4a_7c15);
    let (a, b) = solve_both_families(
        (&exact, ka, family_seed(2)),
        (&co_exact, kb, family_seed(3)),
        request,
    );
    let (a, b) = (a?, b?);
    report.add_solver_counts(&a);
    report.add_solver_counts(&b);
    // Fails loudly if the eigensolver disagrees with the counts the selection below relies on.
    split.check(&exact, &a.values, ka)?;
    split.check(&co_exact, &b.values, kb)?;
    report.integrable_computed = a.values.len();
    report.cointegrable_computed = b.values.len();

    // Merge, sort by eigenvalue (stable: harmonic first), select.
    let mut entries: Vec<(f64, FieldFamily, usize)> = (0..harmonic.fields.ncols())
        .map(|i| (0.0, FieldFamily::Harmonic, i))
        .chain(
            a.values
                .iter()
                .enumerate()
                .map(|(i, &l)| (l, FieldFamily::Integrable, i)),
        )
        .chain(
            b.values
                .iter()
                .enumerate()
                .map(|(i, &l)| (l, FieldFamily::Cointegrable, i)),
        )
        .collect();
    entries.sort_by(|x, y| x.0.total_cmp(&y.0));
    match request.size {
        BasisSize::Fields(d) => entries.truncate(d),
        BasisSize::MaxEigenvalue(bound) => entries.retain(|e| e.0 <= bound),
        BasisSize::Pairs(_) | BasisSize::Complete => {}
    }
    let count = |family| entries.iter().filter(|e| e.1 == family).count();
    let (na, nb, nh) = (
        count(FieldFamily::Integrable),
        count(FieldFamily::Cointegrable),
        count(FieldFamily::Harmonic),
    );
    report.integrable_count = na;
    report.cointegrable_count = nb;
    report.potential_kernel_eigenvalues = a.kernel_values.clone();
    report.co_potential_kernel_eigenvalues = b.kernel_values.clone();
    report.max_solver_residual = a.max_residual.max(b.max_residual);

    let potentials = normalised(complex.d0(), complex.m1().values(), &a.vectors, na);
    let co_potentials = normalised(complex.co_gradient(), complex.m1().values(), &b.vectors, nb);
    let harmonic = harmonic.fields.as_ref().subcols(0, nh).to_owned();
    report.seconds = start.elapsed().as_secs_f64();
    Ok((
        EigenfunctionBasis::new(entries, potentials, co_potentials, harmonic),
        report,
    ))
}

/// Both scalar eigenproblems, one after the other, each using all threads (the eigensolver
/// spreads its dense products and blocked solves over rayon's pool). Running them at the same
/// time on two threads, as before the solver was threaded, was slower: bunny-closed, d = 1000,
/// 47.3 s against 44.3 s (2 cores, 2026-11-21). Progress of both is reported as one
/// [`BasisStage::Eigenpairs`] stage with `done` = eigenpairs found in both and
/// `wanted = ka + kb`.
///
/// Each family is `(problem, count, seed)`; returns the potential and the co-potential eigenpairs.
fn solve_both_families(
    potential: (&ScalarSpectrum, usize, u64),
    co_potential: (&ScalarSpectrum, usize, u64),
    request: &BasisRequest<'_>,
) -> (
    Result<ScalarEigenpairs, BasisError>,
    Result<ScalarEigenpairs, BasisError>,
) {
    let (exact, ka, seed_a) = potential;
    let (co_exact, kb, seed_b) = co_potential;
    let wanted = ka + kb;
    let found = |p: &tvf_solvers::EigenProgress, kernel: usize, count: usize| {
        p.found.saturating_sub(kernel).min(count)
    };
    let done_a = Cell::new(0);
    let done_b = Cell::new(0);
    let report = || request.report(BasisStage::Eigenpairs, done_a.get() + done_b.get(), wanted);
    request.report(BasisStage::Eigenpairs, 0, wanted);
    let a = exact.lowest_nonzero(ka, seed_a, &|p: &tvf_solvers::EigenProgress| {
        done_a.set(found(p, exact.components(), ka));
        report();
    });
    if let Ok(pairs) = &a {
        done_a.set(pairs.values.len());
    }
    let b = co_exact.lowest_nonzero(kb, seed_b, &|p: &tvf_solvers::EigenProgress| {
        done_b.set(found(p, co_exact.components(), kb));
        report();
    });
    if let Ok(pairs) = &b {
        done_b.set(pairs.values.len());
    }
    report();
    (a, b)
}

/// The first `count` columns of `functions`, each divided by the `M1` norm of `gradient · φ`,
/// so that `gradient · φ̃` is `M1`-unit. `gradient` is `2F × n` (the complex's `d0` or `J G_co`).
fn normalised(
    gradient: &sprs::CsMat<f64>,
    m1: &[f64],
    functions: &Mat<f64>,
    count: usize,
) -> Mat<f64> {
    let rows = functions.nrows();
    let columns: Vec<Vec<f64>> = (0..count)
        .into_par_iter()
        .map(|j| {
            let mut phi: Vec<f64> = (0..rows).map(|i| functions[(i, j)]).collect();
            let field = mul_vec(gradient, &phi);
            let norm = field
                .iter()
                .zip(m1)
                .map(|(v, m)| v * v * m)
                .sum::<f64>()
                .sqrt();
            phi.iter_mut().for_each(|x| *x /= norm);
            phi
        })
        .collect();
    Mat::from_fn(rows, count, |i, j| columns[j][i])
}
