//! [`compute_basis`]: the Fourier basis of tangent fields (Section 6 of the paper) for any
//! [`HodgeComplex`].

use crate::basis_request::{BasisRequest, BasisSize, BasisStage};
use crate::eigenfunction_basis::EigenfunctionBasis;
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
    lowest_eigenpairs_of, process_cpu_seconds, EigenOptions, EigenProgress, EigenRequest, Pencil,
    PhaseStatistics, ShiftCount, SolverStatistics,
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
    /// Processor seconds (all threads) spent counting.
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
    let h = complex.topology().harmonic_dimension;
    let area = complex.total_area();
    let (exact_pencil, co_exact_pencil) = (exact.pencil()?, co_exact.pencil()?);
    // Exact counts per family up front (inertia), so each family is solved once; the pencils
    // remember the counted shifts, so the eigensolver factors none of them again.
    let cpu = process_cpu_seconds();
    let split = split_families(
        request.size,
        h,
        (&exact, &exact_pencil),
        (&co_exact, &co_exact_pencil),
        area,
    )?;
    let counting_cpu_seconds = process_cpu_seconds() - cpu;
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
        counting_cpu_seconds,
        ..BasisReport::default()
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
    )?;
    report.solver = solver;
    report.factorizations = solver.factorizations();
    report.solves = solver.solves();
    report.eigensolver_calls = 2;
    report.distinct_shifts = distinct_shifts(&exact_pencil) + distinct_shifts(&co_exact_pencil);
    // Fails loudly if the eigensolver disagrees with the counts the selection below relies on.
    split.check(&exact, &a.values, ka)?;
    split.check(&co_exact, &b.values, kb)?;
    report.integrable_computed = a.values.len();
    report.cointegrable_computed = b.values.len();

    let entries = selected_entries(harmonic.fields.ncols(), &a.values, &b.values, request.size);
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
    report.max_field_residual = a.max_field_residual.max(b.max_field_residual);
    report.max_field_residual_floor = a.max_field_residual_floor.max(b.max_field_residual_floor);

    let gradient = LinearOperator::Sparse(complex.d0().clone());
    let potentials = normalised(&gradient, complex.m1(), (&exact, &a.values), a.vectors, na);
    let co_potentials = normalised(
        complex.co_gradient(),
        complex.m1(),
        (&co_exact, &b.values),
        b.vectors,
        nb,
    );
    let harmonic = harmonic.fields.as_ref().subcols(0, nh).to_owned();
    report.seconds = start.elapsed().as_secs_f64();
    Ok((
        EigenfunctionBasis::new(entries, potentials, co_potentials, harmonic),
        report,
    ))
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
/// solver's statistics.
fn solve_both_families(
    potential: Family<'_, '_>,
    co_potential: Family<'_, '_>,
    request: &BasisRequest<'_>,
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
    let options = EigenOptions {
        progress: Some(&progress),
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
/// co-gradient `−M1⁻¹ d1ᵀ`); `spectrum` is the family's eigenproblem with the eigenvalues of
/// the columns. Works in place (no second copy of the eigenfunctions). Where the gradient is a
/// sparse matrix and `M1` diagonal the norms are taken from the fields as they are formed
/// ([`field_norms`]); otherwise (a non-diagonal `M1`: its inverse or its products would be
/// block solves or sparse products with every field) from the eigenvalues,
/// `‖gradient · φ‖²_{M1} = φᵀ A φ = λ φᵀ M φ` ([`ScalarSpectrum::energy_norms`]).
fn normalised(
    gradient: &LinearOperator,
    m1: &Mass,
    (spectrum, values): (&ScalarSpectrum, &[f64]),
    mut functions: Mat<f64>,
    count: usize,
) -> Mat<f64> {
    let rows = functions.nrows();
    functions.truncate(rows, count.min(functions.ncols()));
    let (Some(gradient), Some(m1)) = (gradient.as_sparse(), m1.diagonal_values()) else {
        let norms = spectrum.energy_norms(values, functions.as_ref());
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
