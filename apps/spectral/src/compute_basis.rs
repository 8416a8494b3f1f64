//! [`compute_basis`]: the Fourier basis of tangent fields (Section 6 of the paper) for any
//! [`HodgeComplex`].

use crate::basis_request::{BasisRequest, BasisSize, BasisStage};
use crate::eigenfunction_basis::EigenfunctionBasis;
use crate::eigenfunction_sink::EigenfunctionSink;
use crate::family_split::split_families;
use crate::harmonic_fields::harmonic_fields;
use crate::scalar_spectrum::{free_nodes, ScalarEigenpairs, ScalarSpectrum};
use crate::{BasisError, FieldFamily, SpectralBasis};
use faer::reborrow::Reborrow;
use faer::{Mat, MatRef};
use rayon::prelude::*;
use std::cell::Cell;
use std::time::Instant;
use tvf_core::discretization::sparse::to_csr;
use tvf_core::discretization::{HodgeComplex, HodgeOperators, LinearOperator, Mass};
use tvf_solvers::{
    lowest_eigenpairs_of, process_cpu_seconds, EigenOptions, EigenProgress, EigenRequest,
    EigenvectorSink, FinishedEigenvectors, Pencil, PhaseStatistics, ShiftCount, SolverStatistics,
};

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
    /// Largest relative eigenfield residual `‖LΦ − λΦ‖/λ` the eigensolver reported for the
    /// eigenfields of both families (after its refinement).
    pub max_field_residual: f64,
    /// Largest rounding floor of those residuals (what rounding `A x` alone gives; on meshes
    /// with slivers it can be far above 1e-8, and so can the residuals).
    pub max_field_residual_floor: f64,
    /// Sparse factorizations of both families, all phases (counting included).
    pub factorizations: usize,
    /// Distinct shifts factored for both families: equal to
    /// [`BasisReport::factorizations`] when every shift was factored once (a shift nudged off
    /// an eigenvalue costs one more).
    pub distinct_shifts: usize,
    /// Single-vector solves of both families, all phases.
    pub solves: usize,
    /// Eigenproblems solved: one per family, each with its exact count (both in one call).
    pub eigensolver_calls: usize,
    /// The eigensolver's cost by phase: counting at interval boundaries (its times; the threshold
    /// search is [`BasisReport::counting_seconds`]), solving, refinement; factorization counts
    /// include the threshold search.
    pub solver: SolverStatistics,
    /// Forming the dense fields from the eigenfunctions ([`compute_basis`] only).
    pub assembly: PhaseStatistics,
    /// For [`BasisSize::Fields`] and [`BasisSize::MaxEigenvalue`] split by inertia counts: the
    /// threshold `t` (units of λ, 1/length²) such that exactly the non-zero eigenvalues of both
    /// families strictly below `t` were computed. `None` when the request fixed the counts
    /// (pairs, complete, tiny meshes solved densely).
    pub split_threshold: Option<f64>,
    /// Sparse `LDLᵀ` factorizations spent counting eigenvalues below candidate thresholds.
    pub counting_factorizations: usize,
    /// Wall-clock seconds spent counting (included in [`BasisReport::seconds`]).
    pub counting_seconds: f64,
    /// Processor seconds of the whole process (all threads) while counting: the harmonic
    /// fields are computed beside the counts, so this includes their share of that time.
    pub counting_cpu_seconds: f64,
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
    /// The eigensolver's statistics of one call over both families' pencils.
    fn record_solver(
        &mut self,
        solver: SolverStatistics,
        exact: &Pencil<'_>,
        co_exact: &Pencil<'_>,
    ) {
        self.solver = solver;
        self.factorizations = solver.factorizations();
        self.solves = solver.solves();
        self.eigensolver_calls = 2;
        self.distinct_shifts = distinct_shifts(exact) + distinct_shifts(co_exact);
    }

    /// The counts, kernels and residuals of the two families' eigenpairs `a` (potentials) and
    /// `b` (co-potentials), of which the basis keeps `kept`.
    fn record_families(
        &mut self,
        a: &ScalarEigenpairs,
        b: &ScalarEigenpairs,
        kept: (usize, usize),
    ) {
        self.integrable_count = kept.0;
        self.cointegrable_count = kept.1;
        self.potential_kernel_eigenvalues = a.kernel_values.clone();
        self.co_potential_kernel_eigenvalues = b.kernel_values.clone();
        self.max_solver_residual = a.max_residual.max(b.max_residual);
        self.max_field_residual = a.max_field_residual.max(b.max_field_residual);
        self.max_field_residual_floor = a.max_field_residual_floor.max(b.max_field_residual_floor);
    }
}

/// The Fourier basis of `complex` as requested, with dense `n1 × d` fields (the eigenfunctions
/// and an `f32` copy too if the request asks for them), sorted by eigenvalue and labelled.
///
/// Steps (Section 6): the `2g` harmonic fields by projecting seeded random fields; the lowest
/// eigenpairs `(λ, φ)` of `(d0ᵀ M1 d0, M0)` and `(μ, ψ)` of `(d1 M1⁻¹ d1ᵀ, M2⁻¹)` (the spectrum
/// intervals of both, with exact inertia counts, solved in one pool of threads by shift-invert
/// Krylov–Schur and refined where the eigenfield residual misses 1e-9·λ; dense for small
/// problems; every shift is factored once, the threshold's counts included), the constant
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
    let (assembly_start, assembly_cpu) = (Instant::now(), process_cpu_seconds());
    let fields = compact.dense_fields(complex);
    report.assembly = PhaseStatistics {
        wall_seconds: assembly_start.elapsed().as_secs_f64(),
        cpu_seconds: process_cpu_seconds() - assembly_cpu,
        ..PhaseStatistics::default()
    };
    let mut basis = SpectralBasis::new(
        compact.eigenvalues().to_vec(),
        compact.families().to_vec(),
        fields,
        complex.m1().clone(),
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
    let solved = solve_basis(complex, request, None)?;
    let (basis, mut report) = kept_in_memory(complex, solved);
    report.seconds = start.elapsed().as_secs_f64();
    Ok((basis, report))
}

/// The basis of `solved` (whose eigenfunctions were kept, not streamed) with its eigenfunctions
/// normalised, and its report (without its seconds).
pub(crate) fn kept_in_memory<H: HodgeComplex + ?Sized>(
    complex: &H,
    solved: SolvedBasis,
) -> (EigenfunctionBasis, BasisReport) {
    let gradient = LinearOperator::Sparse(complex.d0().clone());
    let (potential_norms, co_potential_norms) = solved.energy_norms.unzip();
    let potentials = normalised(
        &gradient,
        complex.m1(),
        potential_norms,
        solved.potential.vectors,
        solved.kept.0,
    );
    let co_potentials = normalised(
        complex.co_gradient(),
        complex.m1(),
        co_potential_norms,
        solved.co_potential.vectors,
        solved.kept.1,
    );
    let basis = EigenfunctionBasis::new(solved.entries, potentials, co_potentials, solved.harmonic);
    (basis, solved.report)
}

/// What [`solve_basis`] found: the basis entries, the eigenpairs of both scalar problems (their
/// vectors `n × 0` where they went to a sink), the number of each family's columns kept
/// (integrable, co-integrable), the harmonic fields kept and the report (without its seconds).
pub(crate) struct SolvedBasis {
    pub entries: Vec<(f64, FieldFamily, usize)>,
    pub potential: ScalarEigenpairs,
    pub co_potential: ScalarEigenpairs,
    pub kept: (usize, usize),
    pub harmonic: Mat<f64>,
    /// The `M1` norms of the kept potentials' and co-potentials' fields, from their eigenvalues,
    /// where the fields cannot be normalised column by column (a non-diagonal `M1`, or a
    /// co-gradient that is not a sparse matrix); `None` otherwise.
    pub energy_norms: Option<(Vec<f64>, Vec<f64>)>,
    pub report: BasisReport,
    /// Whether the eigenfunctions went to the sink (a sink is used only when the counts of
    /// every family are known before solving and the normalisation works column by column).
    pub streamed: bool,
}

/// How many fields of each family `entries` keeps (integrable, co-integrable, harmonic). For a
/// basis whose eigenfunctions went to a sink (`streamed_for`: the counts announced to it), fails
/// unless they fit what was written: at most the announced integrable and co-integrable
/// columns, exactly the announced harmonic ones.
fn kept_counts(
    entries: &[(f64, FieldFamily, usize)],
    streamed_for: Option<Option<(usize, usize, usize)>>,
) -> Result<(usize, usize, usize), BasisError> {
    let count = |family| entries.iter().filter(|e| e.1 == family).count();
    let (na, nb, nh) = (
        count(FieldFamily::Integrable),
        count(FieldFamily::Cointegrable),
        count(FieldFamily::Harmonic),
    );
    let within = |(a, b, h): (usize, usize, usize)| na <= a && nb <= b && nh == h;
    match streamed_for {
        Some(counts) if !counts.is_some_and(within) => Err(BasisError::InvalidRequest(format!(
            "the basis kept {na} + {nb} + {nh} fields, not the {counts:?} its eigenfunctions were \
             written for"
        ))),
        _ => Ok((na, nb, nh)),
    }
}

/// The steps of [`compute_eigenfunction_basis`] up to the normalisation of the eigenfunctions,
/// which is done here, column by column as the eigensolver hands them on, for a `sink` that
/// can be used (see [`SolvedBasis::streamed`]).
pub(crate) fn solve_basis<H: HodgeComplex + ?Sized>(
    complex: &H,
    request: &BasisRequest<'_>,
    sink: Option<&dyn EigenfunctionSink>,
) -> Result<SolvedBasis, BasisError> {
    let (exact, co_exact) = scalar_spectra(complex);
    let h = complex.topology().harmonic_dimension;
    let area = complex.total_area();
    // Both pencils at once: a sparse mass or a mixed pencil is factored and estimated as it is
    // made, on one core each.
    let (exact_pencil, co_exact_pencil) = rayon::join(|| exact.pencil(), || co_exact.pencil());
    let (exact_pencil, co_exact_pencil) = (exact_pencil?, co_exact_pencil?);
    // Exact counts per family up front (inertia), so each family is solved once; the pencils
    // remember the counted shifts, so the eigensolver factors none of them again. The harmonic
    // fields beside them: two Poisson factorizations and a dozen solves, mostly on one core
    // (at a million faces of genus 2, 19 s after counts that kept 1.45 cores busy for 10 s).
    request.report(BasisStage::Harmonic, 0, h);
    let cpu = process_cpu_seconds();
    let (size, seed) = (request.size, request.seed);
    let ((split, counting_cpu_seconds), harmonic) = rayon::join(
        || {
            let split = split_families(
                size,
                h,
                (&exact, &exact_pencil),
                (&co_exact, &co_exact_pencil),
                area,
            );
            (split, process_cpu_seconds() - cpu)
        },
        || harmonic_fields(complex, seed),
    );
    let split = split?;
    let harmonic = harmonic?;
    request.report(BasisStage::Harmonic, h, h);
    let (ka, kb) = (split.potential, split.co_potential);

    let mut report = BasisReport {
        harmonic_dimension: h,
        harmonic_orthonormality_error: harmonic.orthonormality_error,
        harmonic_kernel_residual: harmonic.kernel_residual,
        split_threshold: split.threshold,
        counting_factorizations: split.factorizations,
        counting_seconds: split.seconds,
        counting_cpu_seconds,
        ..BasisReport::default()
    };
    // The columns each family keeps, and so the basis's counts, when they are known now.
    let kept = (ka.min(exact.available()), kb.min(co_exact.available()));
    let counts = predicted_counts(request.size, harmonic.fields.ncols(), kept);
    let streaming = match (sink, counts) {
        (Some(sink), Some(counts)) if streams_columns(complex) => sink
            .begin(counts)
            .map_err(stopped("potential"))?
            .then(|| ColumnStreaming::new(complex, [&exact, &co_exact], kept, sink)),
        _ => None,
    };
    // Each family's eigensolver gets its own seed, derived from the request's with a fixed salt
    // per family: the same request seed gives the same bases (and so the same cached files and
    // recorded results), so the salts must not change.
    let family_seed = |salt: u64| request.seed ^ salt.wrapping_mul(0x9e37_79b9_7f4a_7c15);
    let tops = split.tops.map_or((None, None), |(a, b)| (Some(a), Some(b)));
    let (a, b, solver) = solve_both_families(
        (&exact, &exact_pencil, ka, tops.0, family_seed(2)),
        (&co_exact, &co_exact_pencil, kb, tops.1, family_seed(3)),
        request,
        streaming.as_ref(),
    )?;
    report.record_solver(solver, &exact_pencil, &co_exact_pencil);
    // Fails loudly if the eigensolver disagrees with the counts the selection below relies on.
    split.check(&exact, &a.values, ka)?;
    split.check(&co_exact, &b.values, kb)?;
    report.integrable_computed = a.values.len();
    report.cointegrable_computed = b.values.len();

    let entries = selected_entries(harmonic.fields.ncols(), &a.values, &b.values, request.size);
    let (na, nb, nh) = kept_counts(&entries, streaming.is_some().then_some(counts))?;
    report.record_families(&a, &b, (na, nb));
    // Where the fields cannot be normalised column by column, their norms come from the
    // eigenvalues while the spectra are at hand.
    let energy_norms = (!streams_columns(complex)).then(|| {
        (
            kept_energy_norms(&exact, &a, na),
            kept_energy_norms(&co_exact, &b, nb),
        )
    });
    let harmonic = harmonic.fields.as_ref().subcols(0, nh).to_owned();
    Ok(SolvedBasis {
        entries,
        potential: a,
        co_potential: b,
        kept: (na, nb),
        harmonic,
        energy_norms,
        report,
        streamed: streaming.is_some(),
    })
}

/// The potential and the co-potential eigenproblems of `complex` on their free nodes.
fn scalar_spectra<H: HodgeComplex + ?Sized>(complex: &H) -> (ScalarSpectrum, ScalarSpectrum) {
    let (potential_nodes, co_potential_nodes) =
        (complex.potential_nodes(), complex.co_potential_nodes());
    let free_fields = free_nodes(complex.field_nodes());
    let exact = ScalarSpectrum::new(
        "potential",
        complex.exact_eigenproblem(),
        &free_nodes(potential_nodes),
        &free_fields,
        potential_nodes.kernel_dimension(),
    );
    let co_exact = ScalarSpectrum::new(
        "co-potential",
        complex.co_exact_eigenproblem(),
        &free_nodes(co_potential_nodes),
        &free_fields,
        co_potential_nodes.kernel_dimension(),
    );
    (exact, co_exact)
}

/// The `M1` norms of the fields of the first `kept` eigenfunctions of `pairs`, from their
/// eigenvalues ([`ScalarSpectrum::energy_norms`]).
fn kept_energy_norms(spectrum: &ScalarSpectrum, pairs: &ScalarEigenpairs, kept: usize) -> Vec<f64> {
    let columns = pairs
        .vectors
        .as_ref()
        .subcols(0, kept.min(pairs.vectors.ncols()));
    spectrum.energy_norms(&pairs.values, columns)
}

/// Bounds of the (integrable, co-integrable, harmonic) counts of the basis of `size` from
/// `harmonic` fields and `kept` eigenpairs of each family: the first two are upper bounds (the
/// selection of `d` fields may drop the highest of each family), the harmonic count is exact;
/// `None` where only the eigenvalues can tell (a bound on them).
fn predicted_counts(
    size: BasisSize,
    harmonic: usize,
    kept: (usize, usize),
) -> Option<(usize, usize, usize)> {
    match size {
        BasisSize::Fields(d) => Some((kept.0, kept.1, harmonic.min(d))),
        BasisSize::Pairs(_) | BasisSize::Complete => Some((kept.0, kept.1, harmonic)),
        BasisSize::MaxEigenvalue(_) => None,
    }
}

/// Whether [`normalised`] works column by column for `complex` (a sparse co-gradient and a
/// diagonal `M1`), so that eigenfunctions can be normalised as they come.
fn streams_columns<H: HodgeComplex + ?Sized>(complex: &H) -> bool {
    complex.co_gradient().as_sparse().is_some() && complex.m1().diagonal_values().is_some()
}

/// The error of a sink that failed, for the eigenproblem `problem`.
fn stopped(problem: &'static str) -> impl Fn(String) -> BasisError {
    move |reason| BasisError::Eigen {
        problem,
        source: tvf_solvers::SolverError::Stopped { reason },
    }
}

/// The eigensolver's finished eigenvectors turned into [`EigenfunctionSink`] columns: kernel
/// columns and columns past a family's kept count dropped, the others taken to the full node
/// numbering and normalised as [`normalised`] does (the same arithmetic per column).
struct ColumnStreaming<'a> {
    spectra: [&'a ScalarSpectrum; 2],
    /// `d0` and the co-gradient as CSR matrices.
    gradients: [sprs::CsMat<f64>; 2],
    m1: &'a [f64],
    kept: (usize, usize),
    sink: &'a dyn EigenfunctionSink,
}

impl<'a> ColumnStreaming<'a> {
    /// For a complex where [`streams_columns`] holds.
    fn new<H: HodgeComplex + ?Sized>(
        complex: &'a H,
        spectra: [&'a ScalarSpectrum; 2],
        kept: (usize, usize),
        sink: &'a dyn EigenfunctionSink,
    ) -> Self {
        let co_gradient = complex
            .co_gradient()
            .as_sparse()
            .expect("streams_columns holds");
        Self {
            spectra,
            gradients: [to_csr(complex.d0()), to_csr(co_gradient)],
            m1: complex
                .m1()
                .diagonal_values()
                .expect("streams_columns holds"),
            kept,
            sink,
        }
    }

    /// Hands the kept columns of `finished` (request 0: potentials, 1: co-potentials) to the sink.
    fn hand_on(&self, finished: &FinishedEigenvectors<'_>) -> Result<(), String> {
        let r = finished.request;
        let (spectrum, family) = match r {
            0 => (self.spectra[0], FieldFamily::Integrable),
            _ => (self.spectra[1], FieldFamily::Cointegrable),
        };
        let kept = if r == 0 { self.kept.0 } else { self.kept.1 };
        let components = spectrum.components();
        // Columns of `finished` that are kept, with their index in the family.
        let columns: Vec<(usize, usize)> = (0..finished.vectors.ncols())
            .filter_map(|j| {
                let index = (finished.first + j).checked_sub(components)?;
                (index < kept).then_some((j, index))
            })
            .collect();
        columns.par_chunks(NORM_CHUNK).try_for_each(|chunk| {
            let mut functions = Mat::<f64>::zeros(spectrum.full_dimension(), chunk.len());
            for (c, &(j, _)) in chunk.iter().enumerate() {
                spectrum.to_full(finished.vectors.col(j), functions.col_mut(c));
            }
            let norms = field_norms(&self.gradients[r.min(1)], self.m1, functions.as_ref());
            let mut values = Vec::with_capacity(functions.nrows());
            for (c, (&(_, index), norm)) in chunk.iter().zip(norms).enumerate() {
                values.clear();
                values.extend(functions.col(c).iter().map(|x| x / norm));
                self.sink.column(family, index, &values)?;
            }
            Ok(())
        })
    }
}

/// The basis's entries `(eigenvalue, family, index in the family)`: the `harmonic` fields
/// (eigenvalue 0), the potential eigenvalues `integrable` and the co-potential ones
/// `cointegrable`, merged and sorted by eigenvalue (stable: harmonic first), then cut to the
/// request's `size`.
fn selected_entries(
    harmonic: usize,
    integrable: &[f64],
    cointegrable: &[f64],
    size: BasisSize,
) -> Vec<(f64, FieldFamily, usize)> {
    let of_family = |values: &[f64], family| {
        values
            .iter()
            .enumerate()
            .map(move |(i, &l)| (l, family, i))
            .collect::<Vec<_>>()
    };
    let mut entries: Vec<(f64, FieldFamily, usize)> = (0..harmonic)
        .map(|i| (0.0, FieldFamily::Harmonic, i))
        .chain(of_family(integrable, FieldFamily::Integrable))
        .chain(of_family(cointegrable, FieldFamily::Cointegrable))
        .collect();
    entries.sort_by(|x, y| x.0.total_cmp(&y.0));
    match size {
        BasisSize::Fields(d) => entries.truncate(d),
        BasisSize::MaxEigenvalue(bound) => entries.retain(|e| e.0 <= bound),
        BasisSize::Pairs(_) | BasisSize::Complete => {}
    }
    entries
}

/// The shifts `pencil` counted, consecutive repeats counted once.
fn distinct_shifts(pencil: &Pencil<'_>) -> usize {
    let mut shifts: Vec<f64> = pencil.counted().iter().map(|c| c.shift).collect();
    shifts.dedup();
    shifts.len()
}

/// One family's eigenproblem for [`solve_both_families`]: `(problem, pencil, count, top, seed)`.
type Family<'p, 'a> = (
    &'p ScalarSpectrum,
    &'p Pencil<'a>,
    usize,
    Option<ShiftCount>,
    u64,
);

/// Both scalar eigenproblems in one eigensolver call: their spectrum intervals form one pool of
/// jobs, so both cores stay busy until the last interval of either family is done. Progress of
/// both is reported as one [`BasisStage::Eigenpairs`] stage with `done` = eigenpairs found in
/// both and `wanted = ka + kb`.
///
/// Each family is `(problem, pencil, count, top, seed)` with `top` the count at the split's
/// threshold (kernel included); returns the potential and the co-potential eigenpairs and the
/// solver's statistics. With `streaming`, the eigenvectors go to its sink as they are final
/// (and the returned ones have no columns).
fn solve_both_families(
    potential: Family<'_, '_>,
    co_potential: Family<'_, '_>,
    request: &BasisRequest<'_>,
    streaming: Option<&ColumnStreaming<'_>>,
) -> Result<(ScalarEigenpairs, ScalarEigenpairs, SolverStatistics), BasisError> {
    let families = [potential, co_potential];
    let counts: Vec<usize> = families
        .iter()
        .map(|(spectrum, _, count, _, _)| (*count).min(spectrum.available()))
        .collect();
    let wanted = counts[0] + counts[1];
    let done = [Cell::new(0), Cell::new(0)];
    let progress = |p: &EigenProgress| {
        let (spectrum, ..) = families[p.request];
        done[p.request].set(
            p.found
                .saturating_sub(spectrum.components())
                .min(counts[p.request]),
        );
        request.report(
            BasisStage::Eigenpairs,
            done[0].get() + done[1].get(),
            wanted,
        );
    };
    request.report(BasisStage::Eigenpairs, 0, wanted);
    let requests: Vec<EigenRequest<'_, '_>> = families
        .iter()
        .zip(&counts)
        .map(|((spectrum, pencil, _, top, seed), &count)| EigenRequest {
            pencil,
            count: count + spectrum.components(),
            top: *top,
            seed: *seed,
        })
        .collect();
    let finished = |f: &FinishedEigenvectors<'_>| streaming.map_or(Ok(()), |s| s.hand_on(f));
    let sink: &EigenvectorSink<'_> = &finished;
    let options = EigenOptions {
        progress: Some(&progress),
        finished: streaming.is_some().then_some(sink),
        ..EigenOptions::default()
    };
    let solution = lowest_eigenpairs_of(&requests, &options).map_err(|e| BasisError::Eigen {
        problem: families[e.request].0.name,
        source: e.source,
    })?;
    request.report(BasisStage::Eigenpairs, wanted, wanted);
    let mut pairs = solution.pairs.into_iter();
    let mut next = |family: usize| {
        let found = pairs.next().ok_or_else(|| BasisError::Eigen {
            problem: families[family].0.name,
            source: tvf_solvers::SolverError::NoConvergence {
                reason: "the eigensolver returned no result".into(),
            },
        })?;
        families[family].0.nonzero(found, counts[family])
    };
    let a = next(0)?;
    let b = next(1)?;
    Ok((a, b, solution.statistics))
}

/// The first `count` columns of `functions`, each divided by the `M1` norm of `gradient · φ`,
/// so that `gradient · φ̃` is `M1`-unit. `gradient` is `n1 × n` (the complex's `d0` or its
/// co-gradient `−M1⁻¹ d1ᵀ`). Works in place (no second copy of the eigenfunctions). Where the
/// gradient is a sparse matrix and `M1` diagonal the norms are taken from the fields as they are
/// formed ([`field_norms`]); otherwise (a non-diagonal `M1`: its inverse or its products would be
/// block solves or sparse products with every field) they are `energy_norms`, one per kept
/// column, computed from the eigenvalues, `‖gradient · φ‖²_{M1} = φᵀ A φ = λ φᵀ M φ`
/// ([`ScalarSpectrum::energy_norms`]).
fn normalised(
    gradient: &LinearOperator,
    m1: &Mass,
    energy_norms: Option<Vec<f64>>,
    mut functions: Mat<f64>,
    count: usize,
) -> Mat<f64> {
    let rows = functions.nrows();
    functions.truncate(rows, count.min(functions.ncols()));
    let (Some(gradient), Some(m1)) = (gradient.as_sparse(), m1.diagonal_values()) else {
        let norms = energy_norms.expect("energy norms where M1 is not diagonal");
        functions
            .par_col_iter_mut()
            .zip(norms)
            .for_each(|(column, norm)| column.iter_mut().for_each(|x| *x /= norm));
        return functions;
    };
    let gradient = to_csr(gradient);
    functions
        .as_mut()
        .par_col_chunks_mut(NORM_CHUNK)
        .for_each(|chunk| {
            let norms = field_norms(&gradient, m1, chunk.rb());
            for (column, norm) in chunk.col_iter_mut().zip(norms) {
                column.iter_mut().for_each(|x| *x /= norm);
            }
        });
    functions
}

/// Columns per task of [`normalised`]: their values packed in rows of this many, so that one
/// pass over the gradient serves them all (and each task divides its own columns).
const NORM_CHUNK: usize = 8;

/// `‖gradient · φ_j‖_{M1}` for the columns `φ_j` of `functions` (`n × w`, `w ≤ NORM_CHUNK`) and
/// the CSR `gradient` (`n1 × n`), without forming the fields: each row of the product is a
/// packed row of `w` values, squared and weighted by `M1` as it is formed (in the order of a
/// column-by-column product and sum, so the norms are the same to the bit).
fn field_norms(gradient: &sprs::CsMat<f64>, m1: &[f64], functions: MatRef<'_, f64>) -> Vec<f64> {
    let width = functions.ncols();
    let packed: Vec<[f64; NORM_CHUNK]> = (0..functions.nrows())
        .map(|i| std::array::from_fn(|j| if j < width { functions[(i, j)] } else { 0.0 }))
        .collect();
    let mut squared = [0.0; NORM_CHUNK];
    for (row, m) in gradient.outer_iterator().zip(m1) {
        let mut value = [0.0; NORM_CHUNK];
        for (k, a) in row.iter() {
            for j in 0..NORM_CHUNK {
                value[j] += a * packed[k][j];
            }
        }
        for j in 0..NORM_CHUNK {
            squared[j] += value[j] * value[j] * m;
        }
    }
    squared[..width].iter().map(|s| s.sqrt()).collect()
}
