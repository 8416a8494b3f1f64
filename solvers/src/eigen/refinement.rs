//! Refinement of eigenpairs whose residual misses a target: one step of inverse iteration with
//! the factorization of the interval that found them, then a Rayleigh–Ritz against `A`.
//!
//! Why: for a pencil `A = Dᵀ W D` (a gradient `D`, a diagonal weight `W`; the potential and
//! co-potential problems of a Hodge complex are of this form), Lemma 1 of Brandt et al. maps an
//! eigenpair `(λ, x)` to the eigenfield `D x / √λ` of the Hodge–Laplacian, whose residual is
//! `√(sᵀ A s / λ)` with `s = M⁻¹ (A x − λ M x)` ([`field_residuals`]). The gradient amplifies the
//! high-frequency part of `r = A x − λ M x` (by about 1/h), so a Krylov pair converged to the
//! solver's tolerance in the shift-inverted metric can still show `1e-8` or more in the field.
//! One step
//! `z = (A − σM)⁻¹ M x` at the interval's own shift σ (no new factorization) damps every component
//! of eigenvalue `λ_m` by `|λ − σ| / |λ_m − σ|`, tiny for high frequencies since σ lies within
//! half an interval of `λ`; the Rayleigh–Ritz on the interval's span then restores `A`- and
//! `M`-orthogonality inside clusters.
//!
//! Every interval takes that step once on all its locked vectors, before the one Rayleigh–Ritz
//! it needs anyway (the slice takes it in its elimination order, see `krylov_slice.rs`): on the
//! bunny, nearly every pair missed the target without it, so checking first cost a residual pass
//! and a second Rayleigh–Ritz for nothing. [`refine_interval`] then handles the few pairs still above the
//! target: more steps at the interval's shift, and for a pair still ten times above it (the
//! lowest pair of the first interval on kitten and hand: components along eigenvectors near the
//! interval's far end are hardly damped at its midpoint, and the lowest eigenfields amplify them
//! most) one step at a shift of its own, next to its eigenvalue (one more factorization).
//! Both stop where they cannot cut the interval's worst residual by a quarter: at a million
//! faces every interval has dozens of pairs at 1e-8–1e-7, within 20 % of each other, which the
//! steps at the shift leave there (the accuracy of solves at that shift) and a step on one or
//! two pairs cannot lower as a whole.

use super::mass::{solve_mass_rows, Mass};
use super::pencil::PencilOperators;
use super::rayleigh_ritz::rayleigh_ritz;
use super::shift_factor::ShiftFactor;
use super::sparse_summaries::{diagonal_of, max_column_sum};
use super::statistics::ThreadClock;
use super::stiffness::Stiffness;
use super::symmetric_products::{
    gather_times, gather_times_and_magnitudes, map_column_chunks, map_column_chunks_reusing,
    ChunkBuffers, ChunkWork, Row, CHUNK,
};
use super::tall_products::mass_inner;
use crate::error::SolverError;
use crate::kernel_dispatch::{fma_dispatch, multiply_add};
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::SparseColMatRef;
use faer::{Mat, MatMut, MatRef, Par};
use std::sync::Arc;

/// Relative eigenfield residuals `√(sᵀ A s / λ) / λ`, `s = M⁻¹ (A x − λ M x)`, of the `n × s`
/// M-orthonormal `vectors` (see the module documentation), and the rounding floor of each: the
/// same expression for the rounding error of `s` itself, `δs_i ≈ ε (|A| |x|)_i / M_ii` with
/// random signs (`δsᵀ A δs ≈ Σ_i A_ii δs_i²`). On meshes with slivers (tiny `M_ii`) the floor
/// can exceed any target: no `f64` vector shows a smaller residual. Both are `0` for eigenvalues
/// at most `floor` (the kernel, which has no eigenfield). The same pass gives every pair's plain
/// relative residual `‖A x − λ M x‖₂ / (‖A‖₁ ‖x‖₂)` ([`FieldResidual::relative`]).
///
/// For a sparse mass, `M⁻¹` is a solve with its Cholesky factorization, and the floor takes
/// `M_ii` for the scale of `M` (`δs_i ≈ ε (|A| |x|)_i / M_ii`: within a small factor of the
/// true `M⁻¹` for a mass matrix); for a mixed pencil `A_ii` is the estimate of
/// [`super::mixed_operator::MixedOperator::diagonal_estimate`] and `‖A‖` the one the pencil
/// made (see [`super::pencil::Pencil::mixed`]). `scratch` (stale values, e.g. a slice's idle
/// Krylov basis) holds the chunks' buffers where it is long enough ([`map_column_chunks`]).
pub(crate) fn field_residuals(
    operators: &PencilOperators<'_>,
    values: &[f64],
    vectors: MatRef<'_, f64>,
    floor: f64,
    par: Par,
    scratch: &mut [f64],
) -> Vec<FieldResidual> {
    residuals_by_chunks(operators, values, floor, |chunk| {
        map_column_chunks(vectors, par, scratch, chunk)
    })
}

/// [`field_residuals`] on the calling thread, in `buffers` (see
/// [`map_column_chunks_reusing`]): for the narrow blocks of the interval stream, which pass
/// over an interval a few columns at a time.
pub(crate) fn field_residuals_reusing(
    operators: &PencilOperators<'_>,
    values: &[f64],
    vectors: MatRef<'_, f64>,
    floor: f64,
    buffers: &mut Option<ChunkBuffers>,
) -> Vec<FieldResidual> {
    residuals_by_chunks(operators, values, floor, |chunk| {
        map_column_chunks_reusing(vectors, buffers, chunk)
    })
}

/// The residuals of one packed chunk: `(first column, width, rows, work buffers)`.
type ChunkResiduals<'a> =
    dyn Fn(usize, usize, &[Row], &mut ChunkWork<'_>) -> Vec<FieldResidual> + Sync + 'a;

/// The field residuals of the vectors whose eigenvalues are `values`, from `map`, which runs
/// [`residuals_of_chunk`] (given to it) on every packed chunk of them in column order.
fn residuals_by_chunks(
    operators: &PencilOperators<'_>,
    values: &[f64],
    floor: f64,
    map: impl FnOnce(&ChunkResiduals<'_>) -> Vec<Vec<FieldResidual>>,
) -> Vec<FieldResidual> {
    let pencil = ChunkPencil::of(operators, floor);
    let chunk = |first: usize, width: usize, x: &[Row], work: &mut ChunkWork<'_>| {
        residuals_of_chunk(
            operators,
            pencil.as_ref(),
            (values, first, width),
            x,
            work,
            floor,
        )
    };
    map(&chunk).into_iter().flatten().collect()
}

/// The [`FieldResidual`]s of the packed chunk `x` (columns `first..first + width` of the
/// vectors whose eigenvalues are `values`), through `pencil` where the pencil has a diagonal
/// mass and a sparse stiffness, else through `operators`.
fn residuals_of_chunk(
    operators: &PencilOperators<'_>,
    pencil: Option<&ChunkPencil<'_>>,
    (values, first, width): (&[f64], usize, usize),
    x: &[Row],
    work: &mut ChunkWork<'_>,
    floor: f64,
) -> Vec<FieldResidual> {
    let lambda: Row = std::array::from_fn(|j| if j < width { values[first + j] } else { 0.0 });
    match pencil {
        Some(pencil) => diagonal_chunk_residuals(pencil, &lambda, width, x, work),
        None => general_chunk_residuals(operators, &lambda, width, x, work, floor),
    }
}

/// The [`FieldResidual`]s of one packed chunk `x` of a pencil with a sparse stiffness and a
/// diagonal mass, with fused multiply–adds where the CPU has them.
fn diagonal_chunk_residuals(
    pencil: &ChunkPencil<'_>,
    lambda: &Row,
    width: usize,
    x: &[Row],
    work: &mut ChunkWork<'_>,
) -> Vec<FieldResidual> {
    fma_dispatch!(chunk_residuals(
        pencil: &ChunkPencil<'_>,
        lambda: &Row,
        width: usize,
        x: &[Row],
        work: &mut ChunkWork<'_>,
    ) -> Vec<FieldResidual>)
}

/// What [`field_residuals`] needs of the pencil, per chunk of columns.
struct ChunkPencil<'a> {
    a: SparseColMatRef<'a, usize, f64>,
    mass: &'a [f64],
    /// `1 / M_ii`.
    inverse_mass: Vec<f64>,
    /// `A_ii`.
    diagonal: Vec<f64>,
    /// `‖A‖₁`.
    norm_a: f64,
    /// Eigenvalues at most this have no eigenfield.
    floor: f64,
}

impl<'a> ChunkPencil<'a> {
    /// For a pencil with a sparse stiffness and a diagonal mass; `None` for any other.
    fn of(operators: &PencilOperators<'a>, floor: f64) -> Option<Self> {
        match (operators.stiffness, operators.mass) {
            (Stiffness::Sparse(a), Mass::Diagonal(mass)) => Some(ChunkPencil {
                a,
                mass,
                inverse_mass: mass.iter().map(|m| m.recip()).collect(),
                diagonal: diagonal_of(a),
                norm_a: max_column_sum(a),
                floor,
            }),
            _ => None,
        }
    }
}

/// The [`FieldResidual`]s of one packed chunk `x` (`n` rows, `width` columns used) with
/// eigenvalues `lambda`, in the `n`-row buffers `work`; multiply–adds fused when `FUSED` (in
/// functions compiled with FMA).
#[inline(always)]
fn chunk_residuals<const FUSED: bool>(
    pencil: &ChunkPencil<'_>,
    lambda: &Row,
    width: usize,
    x: &[Row],
    work: &mut ChunkWork<'_>,
) -> Vec<FieldResidual> {
    let n = x.len();
    let (mass, inverse_mass) = (pencil.mass, &pencil.inverse_mass);
    let [ax, abs_ax, a_s] = &mut work.rows;
    // A x and |A| |x| (for the floor) from one pass over A.
    gather_times_and_magnitudes(pencil.a, x, ax, abs_ax);
    // r = A x − λ M x (its norm), then s = M⁻¹ r, in place.
    let (mut r2, mut x2) = ([0.0; CHUNK], [0.0; CHUNK]);
    for (((s, x), m), inverse) in ax.iter_mut().zip(x).zip(mass).zip(inverse_mass) {
        for j in 0..CHUNK {
            let r = multiply_add::<FUSED>(-lambda[j] * m, x[j], s[j]);
            r2[j] = multiply_add::<FUSED>(r, r, r2[j]);
            x2[j] = multiply_add::<FUSED>(x[j], x[j], x2[j]);
            s[j] = r * inverse;
        }
    }
    let s = ax;
    gather_times(pencil.a, s, a_s);
    let (mut energy, mut noise) = ([0.0; CHUNK], [0.0; CHUNK]);
    for i in 0..n {
        let weight = pencil.diagonal[i].max(0.0);
        for j in 0..CHUNK {
            energy[j] = multiply_add::<FUSED>(s[i][j], a_s[i][j], energy[j]);
            let e = f64::EPSILON
                * multiply_add::<FUSED>(abs_ax[i][j], inverse_mass[i], lambda[j] * x[i][j].abs());
            noise[j] = multiply_add::<FUSED>(weight * e, e, noise[j]);
        }
    }
    let sums = ChunkSums {
        r2,
        x2,
        energy,
        noise,
    };
    sums.residuals(lambda, width, pencil.norm_a, pencil.floor)
}

/// The per-column sums of one chunk from which its [`FieldResidual`]s follow.
struct ChunkSums {
    /// `‖r‖²`, `r = A x − λ M x`.
    r2: Row,
    /// `‖x‖²`.
    x2: Row,
    /// `sᵀ A s`, `s = M⁻¹ r`.
    energy: Row,
    /// The rounding-noise estimate of the energy.
    noise: Row,
}

impl ChunkSums {
    /// The [`FieldResidual`]s of the first `width` columns with eigenvalues `lambda`, `‖A‖₁ =
    /// norm_a`; an eigenvalue at most `floor` gets only the relative residual.
    fn residuals(&self, lambda: &Row, width: usize, norm_a: f64, floor: f64) -> Vec<FieldResidual> {
        let Self {
            r2,
            x2,
            energy,
            noise,
        } = self;
        (0..width)
            .map(|j| {
                let relative = r2[j].sqrt() / (norm_a * x2[j].sqrt().max(f64::MIN_POSITIVE));
                if lambda[j] <= floor {
                    return FieldResidual {
                        relative,
                        ..FieldResidual::default()
                    };
                }
                FieldResidual {
                    residual: (energy[j].max(0.0) / lambda[j]).sqrt() / lambda[j],
                    floor: (noise[j] / lambda[j]).sqrt() / lambda[j],
                    relative,
                }
            })
            .collect()
    }
}

/// The [`FieldResidual`]s of one packed chunk `x` of any other pencil (see [`field_residuals`]).
fn general_chunk_residuals(
    operators: &PencilOperators<'_>,
    lambda: &Row,
    width: usize,
    x: &[Row],
    work: &mut ChunkWork<'_>,
    floor: f64,
) -> Vec<FieldResidual> {
    let ChunkWork {
        rows: [ax, abs_ax, a_s],
        extra: scratch,
    } = work;
    operators
        .stiffness
        .times_rows_and_magnitudes(x, ax, abs_ax, scratch);
    operators.mass.times_rows(x, a_s);
    // r = A x − λ M x (its norm), then s = M⁻¹ r.
    let (mut r2, mut x2) = ([0.0; CHUNK], [0.0; CHUNK]);
    for ((r, mx), x) in ax.iter_mut().zip(a_s.iter()).zip(x) {
        for j in 0..CHUNK {
            r[j] -= lambda[j] * mx[j];
            r2[j] += r[j] * r[j];
            x2[j] += x[j] * x[j];
        }
    }
    let s = ax;
    match operators.mass_factor {
        Some(factor) => solve_mass_rows(factor, s, scratch),
        None => {
            for (row, m) in s.iter_mut().zip(operators.mass_diagonal) {
                row.iter_mut().for_each(|v| *v /= m);
            }
        }
    }
    let energy = operators.stiffness.energy_rows(s, a_s, scratch);
    let mut noise = [0.0; CHUNK];
    for i in 0..x.len() {
        let weight = operators.stiffness_diagonal[i].max(0.0);
        let inverse = operators.mass_diagonal[i].recip();
        for j in 0..CHUNK {
            let e = f64::EPSILON * (abs_ax[i][j] * inverse + lambda[j] * x[i][j].abs());
            noise[j] += weight * e * e;
        }
    }
    let norm_a = operators.stiffness_norm.max(f64::MIN_POSITIVE);
    let sums = ChunkSums {
        r2,
        x2,
        energy,
        noise,
    };
    sums.residuals(lambda, width, norm_a, floor)
}

/// A relative eigenfield residual, its rounding floor and the pair's plain relative residual
/// (see [`field_residuals`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct FieldResidual {
    pub residual: f64,
    pub floor: f64,
    pub relative: f64,
}

impl FieldResidual {
    /// Whether refinement could help: above `target` and clearly above the rounding floor.
    pub(crate) fn misses(&self, target: f64) -> bool {
        self.residual > target && self.residual > FLOOR_MARGIN * self.floor
    }
}

/// The trial step must bring the worst residual below this fraction of itself for the interval
/// to be refined, each step the worst residual that misses the target for another to follow,
/// and the pairs not stepped at a near shift must be below it times the worst (a pair gets a
/// further step only if the last one halved its residual). After the inverse-iteration step
/// every interval takes, a further step gains about a factor 2 where it helps at all (hand:
/// 1.38e-8 → 7.3e-9 for its lowest pair), so asking for a halving rejected steps that work; on
/// meshes with slivers a step gains nothing.
const TRIAL_GAIN: f64 = 0.75;

/// Pairs whose residual still exceeds this multiple of the target after the steps at the
/// interval's shift get a step at a shift of their own.
const NEAR_SHIFT_FACTOR: f64 = 10.0;

/// At most this many pairs of an interval get a shift of their own (one factorization each).
const MAX_NEAR_SHIFT_PAIRS: usize = 2;

/// How far above its rounding floor a residual must be for refinement to be worth a solve.
const FLOOR_MARGIN: f64 = 10.0;

/// Inverse-iteration steps of the refinement of one interval (each one solve per pair still
/// above the target).
const MAX_REFINEMENT_STEPS: usize = 3;

/// When a pair is refined.
pub(crate) struct RefinementSettings {
    /// Relative eigenfield residual to reach (see `EigenOptions::refinement_target`).
    pub target: f64,
    /// Eigenvalues at most `floor` (the kernel) have no eigenfield and are left alone.
    pub floor: f64,
    pub parallelism: Par,
}

/// What the refinement of one interval did and cost.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Refinement {
    /// Pairs refined (in the first step; later steps refine a subset of them).
    pub refined: usize,
    /// Single-vector solves (the trial step included).
    pub solves: usize,
    /// Wall-clock seconds of the calling thread in the refinement.
    pub wall_seconds: f64,
    /// Processor seconds of the calling thread in the refinement (threads it lends work to
    /// are not counted).
    pub cpu_seconds: f64,
}

/// Refines the eigenpairs of one interval (`values` ascending, `vectors` `n × s`
/// M-orthonormal) whose eigenfield residual misses `settings.target` and is clearly above its
/// rounding floor, with `factor = LDLᵀ(A − σM)` at the interval's shift: first one trial step on
/// the worst pair (if it does not cut that residual by a quarter ([`TRIAL_GAIN`]), no step will
/// help any: the interval sits
/// at the accuracy of its solves), then up to [`MAX_REFINEMENT_STEPS`] steps of
/// [`refine_columns`], each on the pairs the previous step halved that still miss the target,
/// while the last step cut the worst residual that misses it by a quarter ([`TRIAL_GAIN`]),
/// then [`refine_stubborn_pairs`] after `factor` is released. `scratch` (`n × 2s` at least,
/// stale values: the slice's idle Krylov basis) holds every `n`-row block the steps need.
///
/// Errors: [`SolverError::NoConvergence`] if a step loses a vector.
pub(crate) fn refine_interval(
    operators: &PencilOperators<'_>,
    factor: Arc<ShiftFactor>,
    factor_at: &dyn Fn(f64) -> Result<Arc<ShiftFactor>, SolverError>,
    values: &mut Vec<f64>,
    (mut vectors, scratch): (MatMut<'_, f64>, &mut [f64]),
    settings: &RefinementSettings,
) -> Result<Refinement, SolverError> {
    let clock = ThreadClock::start();
    let solve_cost = factor.refined_solve_cost();
    let mut outcome = Refinement::default();
    // The residuals' buffers are cut from `scratch`, idle between the steps.
    let residual_of = |values: &[f64], vectors: MatRef<'_, f64>, scratch: &mut [f64]| {
        field_residuals(
            operators,
            values,
            vectors,
            settings.floor,
            settings.parallelism,
            scratch,
        )
    };
    let mut before = residual_of(values, vectors.rb(), scratch);
    let mut which: Vec<usize> = (0..before.len())
        .filter(|&j| before[j].misses(settings.target))
        .collect();
    let worst = which
        .iter()
        .copied()
        .max_by(|&i, &j| before[i].residual.total_cmp(&before[j].residual));
    if let Some(worst) = worst {
        outcome.solves += 1;
        if step_helps(
            operators,
            &factor,
            vectors.rb(),
            worst,
            before[worst].residual,
            settings.floor,
            scratch,
        ) {
            for _ in 0..MAX_REFINEMENT_STEPS {
                let worst_before = worst_missing(&before, settings.target);
                *values = refine_columns(
                    operators,
                    &factor,
                    (vectors.rb_mut(), &mut *scratch),
                    &which,
                    settings.parallelism,
                )?;
                outcome.solves += which.len();
                outcome.refined = outcome.refined.max(which.len());
                let after = residual_of(values, vectors.rb(), scratch);
                // Another step only for pairs still above the target that the last step
                // improved: the others are at the rounding floor of their vectors.
                which = (0..after.len())
                    .filter(|&j| {
                        after[j].misses(settings.target)
                            && after[j].residual < 0.5 * before[j].residual
                    })
                    .collect();
                // And only while the steps cut the worst residual that misses the target by a
                // quarter: where they do not, the interval sits at the accuracy of solves at
                // its shift (at a million faces, dozens of pairs at 1e-8–1e-7 each).
                let gained = worst_missing(&after, settings.target) < TRIAL_GAIN * worst_before;
                before = after;
                if which.is_empty() || !gained {
                    break;
                }
            }
        }
    }
    // The interval's factorization is not needed any more: released before a near shift's
    // is made, so that the two are never in memory together.
    drop(factor);
    refine_stubborn_pairs(
        operators,
        factor_at,
        values,
        (vectors, scratch),
        &before,
        settings,
        &mut outcome,
    );
    // A mixed pencil's solves are refined once (two solves each).
    outcome.solves *= solve_cost;
    (outcome.wall_seconds, outcome.cpu_seconds) = clock.elapsed();
    Ok(outcome)
}

/// The largest of the `residuals` that miss `target` (see [`FieldResidual::misses`]), 0 if none
/// does.
fn worst_missing(residuals: &[FieldResidual], target: f64) -> f64 {
    residuals
        .iter()
        .filter(|r| r.misses(target))
        .map(|r| r.residual)
        .fold(0.0, f64::max)
}

/// The pairs of an interval whose residual `before` still misses [`NEAR_SHIFT_FACTOR`] times
/// the target after the steps at the interval's shift (at most [`MAX_NEAR_SHIFT_PAIRS`], the
/// worst first) are at the accuracy of solves at that shift: components along eigenvectors near
/// the interval's ends are hardly damped by it, and the lowest pairs' eigenfields amplify them
/// most. Each gets one step at a shift next to its eigenvalue ([`near_shift_steps`], in
/// `scratch`, `n × s` at least), if that can cut the interval's worst residual by a quarter
/// ([`near_shift_can_cut`]), kept only if the worst residual improves; best effort: a failed
/// factorization or a lost vector leaves the pairs as they are (their residuals are reported
/// either way). Adds what it did to `outcome` (solves before the mixed pencil's factor 2).
fn refine_stubborn_pairs(
    operators: &PencilOperators<'_>,
    factor_at: &dyn Fn(f64) -> Result<Arc<ShiftFactor>, SolverError>,
    values: &mut Vec<f64>,
    (mut vectors, scratch): (MatMut<'_, f64>, &mut [f64]),
    before: &[FieldResidual],
    settings: &RefinementSettings,
    outcome: &mut Refinement,
) {
    let mut stubborn: Vec<usize> = (0..before.len())
        .filter(|&j| before[j].misses(NEAR_SHIFT_FACTOR * settings.target))
        .collect();
    stubborn.sort_by(|&i, &j| before[j].residual.total_cmp(&before[i].residual));
    stubborn.truncate(MAX_NEAR_SHIFT_PAIRS);
    if !near_shift_can_cut(before, &stubborn) {
        return;
    }
    outcome.solves += stubborn.len();
    let (n, s) = (vectors.nrows(), vectors.ncols());
    let (trial, rest) = scratch.split_at_mut(n * s);
    let mut trial = MatMut::from_column_major_slice_mut(trial, n, s);
    trial.copy_from(vectors.rb());
    let Some((new_values, after)) = near_shift_steps(
        operators,
        factor_at,
        values,
        (trial.rb_mut(), rest),
        &stubborn,
        settings,
    ) else {
        return;
    };
    let worst = |r: &[FieldResidual]| r.iter().map(|r| r.residual).fold(0.0, f64::max);
    if after.iter().all(|r| r.residual.is_finite()) && worst(&after) < worst(before) {
        outcome.refined = outcome.refined.max(stubborn.len());
        *values = new_values;
        vectors.copy_from(trial.rb());
    }
}

/// Whether steps on the pairs `stepped` (the worst first) can cut the worst of the `residuals`
/// by a quarter ([`TRIAL_GAIN`]): a step is kept only if it lowers the interval's worst
/// residual, and it cannot lower it below the worst of the pairs it does not step, so two
/// factorizations are not spent unless those are below three quarters of it (at a million
/// faces dozens of pairs sit within 20 % of the worst). `false` when nothing is stepped.
fn near_shift_can_cut(residuals: &[FieldResidual], stepped: &[usize]) -> bool {
    let unstepped = (0..residuals.len())
        .filter(|j| !stepped.contains(j))
        .map(|j| residuals[j].residual)
        .fold(0.0, f64::max);
    stepped
        .first()
        .is_some_and(|&worst| unstepped < TRIAL_GAIN * residuals[worst].residual)
}

/// One inverse-iteration step for each column in `pairs` of the `n × s` eigenvectors `trial`,
/// in place, at a shift of its own (`λ_j − gap/100`, `gap` the distance to the nearest
/// neighbouring eigenvalue or to 0), then the Rayleigh–Ritz on the span of all columns.
/// Returns the new values and field residuals, or `None` if a factorization fails or a vector
/// is lost (`trial` then holds no useful values).
fn near_shift_steps(
    operators: &PencilOperators<'_>,
    factor_at: &dyn Fn(f64) -> Result<Arc<ShiftFactor>, SolverError>,
    values: &[f64],
    (mut trial, scratch): (MatMut<'_, f64>, &mut [f64]),
    pairs: &[usize],
    settings: &RefinementSettings,
) -> Option<(Vec<f64>, Vec<FieldResidual>)> {
    for &j in pairs {
        let gap = [j.checked_sub(1), Some(j + 1)]
            .into_iter()
            .flatten()
            .filter_map(|k| values.get(k))
            .map(|v| (v - values[j]).abs())
            .fold(values[j].abs(), f64::min);
        let near = factor_at(values[j] - 0.01 * gap).ok()?;
        let mut z = operators.mass.times(trial.rb().subcols(j, 1));
        near.solve_in_place(z.as_mut());
        let norm = mass_inner(z.as_ref(), operators.mass, z.as_ref(), Par::Seq)[(0, 0)].sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return None;
        }
        trial.rb_mut().col_mut(j).copy_from(z.col(0) / norm);
    }
    let new_values = rayleigh_ritz(
        operators.stiffness,
        operators.mass,
        trial.rb_mut(),
        scratch,
        settings.parallelism,
    )
    .ok()?;
    let residuals = field_residuals(
        operators,
        &new_values,
        trial.rb(),
        settings.floor,
        settings.parallelism,
        scratch,
    );
    Some((new_values, residuals))
}

/// Refines the columns `which` of the `n × s` eigenvectors `vectors` (M-orthonormal, one
/// interval's) with `factor = LDLᵀ(A − σM)`: `z = (A − σM)⁻¹ M x`, M-normalised, replaces `x`,
/// and a Rayleigh–Ritz against `A` on the span of all `s` columns gives the new ascending values
/// (returned) and M-orthonormal vectors (in place). `scratch` (`n × 2·which.len()` at least, the
/// idle Krylov basis of the slice) holds the selected columns and their steps, so that no
/// `n`-row block is allocated (two of `n × s` at most: 2.1 GB for a co-potential interval at a
/// million faces).
///
/// Errors: [`SolverError::NoConvergence`] if the refined columns become dependent.
pub(crate) fn refine_columns(
    operators: &PencilOperators<'_>,
    factor: &ShiftFactor,
    (mut vectors, scratch): (MatMut<'_, f64>, &mut [f64]),
    which: &[usize],
    par: Par,
) -> Result<Vec<f64>, SolverError> {
    let (n, w) = (vectors.nrows(), which.len());
    let mass = operators.mass;
    let (selected, rest) = scratch.split_at_mut(n * w);
    let mut selected = MatMut::from_column_major_slice_mut(selected, n, w);
    let mut z = MatMut::from_column_major_slice_mut(&mut rest[..n * w], n, w);
    for (j, &column) in which.iter().enumerate() {
        selected
            .rb_mut()
            .col_mut(j)
            .copy_from(vectors.rb().col(column));
    }
    mass.times_into(selected.rb(), z.rb_mut());
    factor.solve_in_place(z.rb_mut());
    let norms = mass_inner(z.rb(), mass, z.rb(), par);
    for (j, &column) in which.iter().enumerate() {
        let norm = norms[(j, j)].sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return Err(SolverError::NoConvergence {
                reason: "an inverse-iteration step of the refinement lost its vector".into(),
            });
        }
        // Keep the sign of x (z ≈ x/(λ − σ) points either way).
        let sign = if mass_inner(
            vectors.rb().subcols(column, 1),
            mass,
            z.rb().subcols(j, 1),
            Par::Seq,
        )[(0, 0)]
            < 0.0
        {
            -1.0
        } else {
            1.0
        };
        for i in 0..n {
            vectors[(i, column)] = sign * z[(i, j)] / norm;
        }
    }
    rayleigh_ritz(operators.stiffness, mass, vectors, scratch, par)
}

/// Whether an inverse-iteration step with `factor` cuts the field residual `before` of column
/// `column` of `vectors`: one solve and no Rayleigh–Ritz, to find out before refining a whole
/// interval. On meshes with slivers the residual of every pair sits at the accuracy of the
/// solves themselves, which no step improves. `scratch` (stale values) holds the residual's
/// buffers where it is long enough.
pub(crate) fn step_helps(
    operators: &PencilOperators<'_>,
    factor: &ShiftFactor,
    vectors: MatRef<'_, f64>,
    column: usize,
    before: f64,
    floor: f64,
    scratch: &mut [f64],
) -> bool {
    let n = vectors.nrows();
    let mass = operators.mass;
    let mut z = mass.times(vectors.subcols(column, 1));
    factor.solve_in_place(z.as_mut());
    let norm = mass_inner(z.as_ref(), mass, z.as_ref(), Par::Seq)[(0, 0)].sqrt();
    if !(norm.is_finite() && norm > 0.0) {
        return false;
    }
    z.col_mut(0).iter_mut().for_each(|x| *x /= norm);
    let mut az = Mat::<f64>::zeros(n, 1);
    operators.stiffness.times(az.as_mut(), z.as_ref(), Par::Seq);
    let rayleigh: f64 = (0..n).map(|i| z[(i, 0)] * az[(i, 0)]).sum();
    let after = field_residuals(operators, &[rayleigh], z.as_ref(), floor, Par::Seq, scratch);
    after
        .first()
        .is_some_and(|r| r.residual < TRIAL_GAIN * before)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Residuals with rounding floors far below them.
    fn residuals(values: &[f64]) -> Vec<FieldResidual> {
        values
            .iter()
            .map(|&residual| FieldResidual {
                residual,
                floor: 1e-13,
                relative: 0.0,
            })
            .collect()
    }

    #[test]
    fn near_shifts_are_taken_for_outlying_pairs_only() {
        // One pair far above the rest (the lowest pair of hand's first interval).
        let lone = residuals(&[2e-7, 3e-9, 1e-9, 4e-9]);
        assert!(near_shift_can_cut(&lone, &[0]));
        // Two outliers, both stepped.
        let two = residuals(&[2e-7, 1e-9, 1.5e-7, 4e-9]);
        assert!(near_shift_can_cut(&two, &[0, 2]));
        // A crowd near the worst (a million faces): the third is at 0.81 of it.
        let crowd = residuals(&[1.22e-7, 1.04e-7, 9.8e-8, 9.0e-8]);
        assert!(!near_shift_can_cut(&crowd, &[0, 1]));
        assert!(!near_shift_can_cut(&lone, &[]));
    }

    #[test]
    fn the_worst_missing_residual_leaves_out_pairs_that_meet_the_target_or_their_floor() {
        let mut mixed = residuals(&[5e-10, 3e-8, 2e-8]);
        // Within ten times its rounding floor: no step could help it.
        mixed[1].floor = 1e-8;
        assert_eq!(worst_missing(&mixed, 1e-9), 2e-8);
        assert_eq!(worst_missing(&residuals(&[5e-10]), 1e-9), 0.0);
    }
}
