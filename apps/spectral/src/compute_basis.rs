//! [`compute_basis`]: the Fourier basis of tangent fields (Section 6 of the paper) for any
//! [`HodgeComplex`].

use crate::basis_request::{BasisRequest, BasisSize, BasisStage};
use crate::eigenfunction_basis::EigenfunctionBasis;
use crate::harmonic_fields::harmonic_fields;
use crate::scalar_spectrum::{ScalarEigenpairs, ScalarSpectrum};
use crate::{BasisError, FieldFamily, SpectralBasis};
use faer::Mat;
use rayon::prelude::*;
use std::cell::Cell;
use std::sync::mpsc;
use std::time::Instant;
use tvf_core::discretization::sparse::mul_vec;
use tvf_core::discretization::{FunctionSpace, HodgeComplex, HodgeOperators};

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
    /// Eigensolver calls (more than two when a family needed more eigenpairs than estimated).
    pub eigensolver_calls: usize,
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
/// spectrum-slicing Lanczos, dense for small problems), the constant eigenfunctions (one per
/// connected component, found by count) dropped; by Lemma 1 `Φ = d0 φ / ‖d0 φ‖` and
/// `Ψ = J G_co ψ / ‖J G_co ψ‖` are eigenfields of `L` with eigenvalues `λ`, `μ`.
///
/// Errors: [`BasisError::Boundary`] on a mesh with boundary, [`BasisError::InvalidRequest`],
/// solver failures.
pub fn compute_basis<H: HodgeComplex>(
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
        complex.m1().to_vec(),
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
pub fn compute_eigenfunction_basis<H: HodgeComplex>(
    complex: &H,
    request: &BasisRequest<'_>,
) -> Result<(EigenfunctionBasis, BasisReport), BasisError> {
    let start = Instant::now();
    if complex.has_boundary() {
        return Err(BasisError::Boundary);
    }
    let components = complex.component_count();
    let exact = ScalarSpectrum::new(
        "potential",
        complex.exact_eigenproblem(),
        complex.potentials().node_components(),
        components,
    );
    let co_exact = ScalarSpectrum::new(
        "co-potential",
        complex.co_exact_eigenproblem(),
        complex.co_potentials().node_components(),
        components,
    );
    let h = complex.harmonic_dimension();
    let area: f64 = complex.m1().iter().sum::<f64>() / 2.0;
    let (mut ka, mut kb) = initial_counts(
        request.size,
        h,
        exact.available(),
        co_exact.available(),
        area,
    )?;

    request.report(BasisStage::Harmonic, 0, h);
    let harmonic = harmonic_fields(complex, request.seed)?;
    request.report(BasisStage::Harmonic, h, h);

    let mut report = BasisReport {
        harmonic_dimension: h,
        harmonic_orthonormality_error: harmonic.orthonormality_error,
        harmonic_kernel_residual: harmonic.kernel_residual,
        ..BasisReport::default()
    };
    let family_seed =
        |stage: BasisStage| request.seed ^ (stage as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    let solve =
        |side: &ScalarSpectrum, count: usize, stage: BasisStage, report: &mut BasisReport| {
            let progress = |p: &tvf_solvers::EigenProgress| {
                request.report(stage, p.found.saturating_sub(components).min(count), count)
            };
            request.report(stage, 0, count);
            let pairs = side.lowest_nonzero(count, family_seed(stage), &progress)?;
            request.report(stage, pairs.values.len(), count);
            report.add_solver_counts(&pairs);
            Ok::<ScalarEigenpairs, BasisError>(pairs)
        };
    let (first_a, first_b) = solve_both_families(
        (&exact, ka, family_seed(BasisStage::Integrable)),
        (&co_exact, kb, family_seed(BasisStage::Cointegrable)),
        components,
        request,
    );
    let (mut a, mut b) = (first_a?, first_b?);
    report.add_solver_counts(&a);
    report.add_solver_counts(&b);
    // Fields(d) and MaxEigenvalue guess each family's share; grow a family while the requested
    // range may hold eigenvalues it has not computed yet.
    loop {
        let target = match request.size {
            BasisSize::Fields(d) => {
                let m = d.saturating_sub(h);
                let mut merged: Vec<f64> = a.values.iter().chain(&b.values).copied().collect();
                merged.sort_by(f64::total_cmp);
                if m == 0 {
                    break;
                }
                merged[m - 1]
            }
            BasisSize::MaxEigenvalue(bound) => bound,
            BasisSize::Pairs(_) | BasisSize::Complete => break,
        };
        let inclusive = matches!(request.size, BasisSize::MaxEigenvalue(_));
        let short = |pairs: &ScalarEigenpairs, side: &ScalarSpectrum| {
            let last = pairs.values.last().copied().unwrap_or(0.0);
            pairs.values.len() < side.available()
                && (last < target || (inclusive && last == target))
        };
        let grow = |k: usize, pairs: &ScalarEigenpairs, side: &ScalarSpectrum| {
            let last = pairs
                .values
                .last()
                .copied()
                .unwrap_or(0.0)
                .max(f64::MIN_POSITIVE);
            let estimate = (k as f64 * (target / last) * 1.15).ceil() as usize + 8;
            estimate.max(k + 8).min(side.available())
        };
        let (short_a, short_b) = (short(&a, &exact), short(&b, &co_exact));
        if !short_a && !short_b {
            break;
        }
        if short_a {
            ka = grow(ka, &a, &exact);
            a = solve(&exact, ka, BasisStage::Integrable, &mut report)?;
        }
        if short_b {
            kb = grow(kb, &b, &co_exact);
            b = solve(&co_exact, kb, BasisStage::Cointegrable, &mut report)?;
        }
    }

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

    let co_gradient = complex.co_gradient();
    let potentials = normalised(complex.d0(), complex.m1(), &a.vectors, na);
    let co_potentials = normalised(&co_gradient, complex.m1(), &b.vectors, nb);
    let harmonic = harmonic.fields.as_ref().subcols(0, nh).to_owned();
    report.seconds = start.elapsed().as_secs_f64();
    Ok((
        EigenfunctionBasis::new(entries, potentials, co_potentials, harmonic),
        report,
    ))
}

/// Both scalar eigenproblems at once: the co-potential one on a second thread, the potential one
/// on this thread (each solver runs sequentially, so two cores are used without any
/// synchronisation inside the solvers; results are bit-identical to solving one after the other).
/// Progress of both is reported from this thread as one [`BasisStage::Eigenpairs`] stage with
/// `done` = eigenpairs found in both and `wanted = ka + kb` (the callback need not be `Sync`).
///
/// Each family is `(problem, count, seed)`; returns the potential and the co-potential eigenpairs.
fn solve_both_families(
    potential: (&ScalarSpectrum, usize, u64),
    co_potential: (&ScalarSpectrum, usize, u64),
    components: usize,
    request: &BasisRequest<'_>,
) -> (
    Result<ScalarEigenpairs, BasisError>,
    Result<ScalarEigenpairs, BasisError>,
) {
    let (exact, ka, seed_a) = potential;
    let (co_exact, kb, seed_b) = co_potential;
    let wanted = ka + kb;
    let found = |p: &tvf_solvers::EigenProgress, count: usize| {
        p.found.saturating_sub(components).min(count)
    };
    let done_a = Cell::new(0);
    let done_b = Cell::new(0);
    let report = || request.report(BasisStage::Eigenpairs, done_a.get() + done_b.get(), wanted);
    request.report(BasisStage::Eigenpairs, 0, wanted);
    let (sender, receiver) = mpsc::channel::<usize>();
    std::thread::scope(|scope| {
        let worker = scope.spawn(move || {
            let progress = |p: &tvf_solvers::EigenProgress| {
                // The receiver outlives this thread; a failed send only loses a progress line.
                let _ = sender.send(found(p, kb));
            };
            co_exact.lowest_nonzero(kb, seed_b, &progress)
        });
        let progress = |p: &tvf_solvers::EigenProgress| {
            done_a.set(found(p, ka));
            while let Ok(done) = receiver.try_recv() {
                done_b.set(done);
            }
            report();
        };
        let a = exact.lowest_nonzero(ka, seed_a, &progress);
        if let Ok(pairs) = &a {
            done_a.set(pairs.values.len());
        }
        // Forward the other family's progress until its thread ends (and drops the sender).
        while let Ok(done) = receiver.recv() {
            done_b.set(done);
            report();
        }
        let b = worker
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        if let Ok(pairs) = &b {
            done_b.set(pairs.values.len());
        }
        report();
        (a, b)
    })
}

/// How many non-zero eigenpairs of each family to compute first.
fn initial_counts(
    size: BasisSize,
    harmonic: usize,
    available_a: usize,
    available_b: usize,
    area: f64,
) -> Result<(usize, usize), BasisError> {
    let total = harmonic + available_a + available_b;
    match size {
        BasisSize::Pairs(k) => Ok((k.min(available_a), k.min(available_b))),
        BasisSize::Complete => Ok((available_a, available_b)),
        BasisSize::Fields(d) => {
            if d > total {
                return Err(BasisError::InvalidRequest(format!(
                    "{d} fields requested, but the field space has only {total} eigenfields"
                )));
            }
            let m = d.saturating_sub(harmonic);
            if m == 0 {
                return Ok((0, 0));
            }
            let guess = m.div_ceil(2) + (m / 10).max(8);
            Ok((
                guess.max(m.saturating_sub(available_b)).min(available_a),
                guess.max(m.saturating_sub(available_a)).min(available_b),
            ))
        }
        BasisSize::MaxEigenvalue(bound) => {
            if !bound.is_finite() || bound < 0.0 {
                return Err(BasisError::InvalidRequest(format!(
                    "eigenvalue bound {bound} must be finite and non-negative"
                )));
            }
            // Weyl's law: a scalar Laplacian has about area·λ/(4π) eigenvalues below λ.
            let weyl = (area * bound / (4.0 * std::f64::consts::PI) * 1.2).ceil();
            let guess = if weyl.is_finite() {
                weyl as usize + 8
            } else {
                usize::MAX
            };
            Ok((guess.min(available_a), guess.min(available_b)))
        }
    }
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
