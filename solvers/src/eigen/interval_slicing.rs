//! The eigen driver: the lowest part of the spectrum of one or more pencils is cut into
//! intervals with exact eigenvalue counts (Sylvester inertia), and all intervals of all pencils
//! are solved concurrently.
//!
//! 1. *Counting.* The top shift `σ_top` with `ν(σ_top) ≥ k` (`ν(σ)`: negative pivots of an
//!    `LDLᵀ` of `A − σM`, or for a mixed pencil those of its factored matrix less the ones that
//!    are no eigenvalues, the exact number of eigenvalues below σ; see [`Pencil`]) is given by the caller (who
//!    counted it already, e.g. to split a basis between two pencils) or found from Weyl's law for
//!    surfaces (`ν` grows linearly in σ) anchored at the mean eigenvalue `trace(A)/trace(M)`.
//!    `m = ⌈ν(σ_top)/interval_size⌉` intervals `(b_i, b_{i+1})`, `b_0 = −∞`, `b_m = σ_top`,
//!    `b_i ≈ σ_top·i/m` in between (equal counts under Weyl's law; a shift the pencil has
//!    counted before within a quarter interval of `σ_top·i/m` is taken instead, so no shift is
//!    factored twice); the boundaries are counted concurrently.
//! 2. *Solving.* Each interval is factored at its midpoint σ (so the eigenvalues at both ends
//!    have the same `|θ| = 1/|λ − σ|`) and solved by the Krylov–Schur slice
//!    ([`super::krylov_slice`]) with exact targets `ν(σ) − ν(b_i)` below and `ν(b_{i+1}) − ν(σ)`
//!    above σ, no deflation against other intervals; its locked vectors get one
//!    inverse-iteration step with the interval's factorization (it damps the high-frequency
//!    rounding noise of the Krylov vectors, which the eigenfields amplify) and go through the
//!    Rayleigh–Ritz against `A` ([`super::rayleigh_ritz`]), and those inside the interval are
//!    kept. The intervals of every pencil run as one pool of jobs, `EigenOptions::threads` at a
//!    time as tasks of rayon's pool (their parallel products split across the same threads);
//!    interval `i` of a pencil is seeded from `(seed, i)`, so the result does not depend on
//!    thread timing. An interval that does not converge within `EigenOptions::max_restarts`
//!    restarts, or whose pairs disagree with its counts, is split near (not at) its midpoint
//!    (one more count) and the halves are solved with their own midpoints as shifts: a shift
//!    that lands next to an eigenvalue makes `max|θ|` huge and the far end of the interval
//!    unresolvable (`ε·max|θ| > tolerance·|θ|`: the slice restarts until its restart limit), and
//!    a cluster that straddles an interval end converges slowly; both are cured by a different
//!    shift and a narrower interval.
//! 3. *Refinement*, by the interval's job right after its solve, with the same factorization
//!    (so no factorization outlives its job): pairs whose eigenfield residual still misses
//!    `EigenOptions::refinement_target` (and is clearly above its rounding floor) get
//!    inverse-iteration steps ([`super::refinement`]) if a trial step on the worst of them
//!    halves its residual; the others are left as they are.
//!
//! The result is complete by construction: interval `i` must return exactly its count, so the
//! total is `ν(σ_top) ≥ k`, every eigenvalue below `σ_top`. Vectors of neighbouring intervals
//! are M-orthogonalised against each other (their eigenvalues differ by at least the distance
//! across a boundary, but that can be small) and their field residuals taken as soon as both
//! intervals are solved, while the other jobs run ([`super::interval_stream`]).
//!
//! Memory: each job writes its refined eigenvectors straight into its columns of the pencil's
//! `n × k` result (reserved up front, so each column is touched once, by its job: the views over
//! the reserved memory are the one `unsafe` step here, kept because making zeros up front for
//! safe views touches the whole result before the jobs' own memory is released — the peak of
//! `tvf basis bunny-closed.obj -k 1000` rose from 1.32 to 1.55 GiB with it; see
//! `docs/performance.md`), and a slice's Krylov basis, locked vectors and buffers are handed to
//! the next job
//! ([`super::workspace_pool`]). With [`EigenOptions::finished`] the jobs run plan by plan in
//! ascending interval order, and each interval's vectors, once orthogonalised against the
//! previous interval's and used for the next one's, are handed to the caller and their pages
//! given back ([`super::interval_stream`]): then only the intervals being solved or waiting
//! for an earlier one are in memory, never the whole `n × k`. The slices solved at the same
//! time stay within [`EigenOptions::slice_memory`] ([`super::slice_memory`]): a job waits until
//! its slice fits next to the running ones, and a pencil whose single slice would not fit gets
//! smaller intervals. Fresh memory is expensive: the kernel faults in and zeroes
//! every new page on first touch, many times slower than a second pass over it, which made the
//! per-slice bases and a copy of every interval's vectors a visible share of the processor
//! time (numbers in `docs/performance.md`).

use super::file_backed_columns::{
    streamed_eigenvectors_in_memory, FileBackedColumns, ParkedColumns,
};
use super::interval_stream::{jobs_in_interval_order, IntervalStream, RawColumns, SolvedPart};
use super::krylov_slice::{run_slice, SliceMemory, SliceProblem, SliceSettings};
use super::pencil::{Pencil, ShiftCount};
use super::rayleigh_ritz::rayleigh_ritz;
use super::refinement::{
    field_residuals, refine_interval, FieldResidual, Refinement, RefinementSettings,
};
use super::shift_factor::ShiftFactor;
use super::slice_memory::{default_slice_memory, interval_size_within, slice_bytes, MemoryGate};
use super::statistics::{Phase, PhaseClock, SolverStatistics};
use super::types::{
    EigenOptions, EigenProgress, Eigenpairs, EigenvectorSink, FinishedEigenvectors,
};
use super::workspace_pool::WorkspacePool;
use crate::calling_thread::on_calling_thread;
use crate::error::SolverError;
use crate::huge_pages::reserve_on_huge_pages;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Mat, MatMut, Par};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Mutex};

/// Times an interval may be split after failing to converge.
const MAX_SPLITS: usize = 3;
/// Where an interval that failed is split, as a fraction of its width from its lower end: not
/// its midpoint, where the failed shift was.
const SPLIT_POINT: f64 = 0.55;
/// Trial shifts of the search for the top shift.
const MAX_TOP_TRIALS: usize = 12;

/// One eigenproblem of [`lowest_eigenpairs_of`]: the `count` lowest eigenpairs of `pencil`.
pub struct EigenRequest<'p, 'a> {
    /// The pencil `(A, M)`.
    pub pencil: &'p Pencil<'a>,
    /// Number of eigenpairs wanted (kernel included).
    pub count: usize,
    /// A shift counted before with at least `count` eigenvalues below it (the lower, the
    /// better), or `None` to search for one.
    pub top: Option<ShiftCount>,
    /// Seed of the random start blocks; equal seeds give identical results.
    pub seed: u64,
}

/// The eigenpairs of every request and what the call cost.
#[derive(Debug, Clone)]
pub struct EigenSolution {
    /// One result per request, in request order.
    pub pairs: Vec<Eigenpairs>,
    /// Factorizations and solves of every pencil (counts made before the call included) and the
    /// wall-clock and processor seconds of this call's phases (all requests together).
    pub statistics: SolverStatistics,
}

/// A failed request: which one and why.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("eigenproblem {request}: {source}")]
pub struct RequestError {
    /// Index of the request in the slice given to [`lowest_eigenpairs_of`].
    pub request: usize,
    /// What went wrong.
    #[source]
    pub source: SolverError,
}

/// The lowest eigenpairs of several pencils at once (see the module documentation): all
/// boundaries are counted in one concurrent batch, all intervals solved in one pool, so two
/// pencils of different size keep every core busy until the end.
///
/// Small problems (`n ≤ options.dense_threshold` or `3k ≥ n`) are solved densely.
///
/// Errors: [`RequestError`] with [`SolverError::TooManyEigenpairs`] (`k > n`),
/// [`SolverError::NoConvergence`] or a factorization failure.
pub fn lowest_eigenpairs_of(
    requests: &[EigenRequest<'_, '_>],
    options: &EigenOptions<'_>,
) -> Result<EigenSolution, RequestError> {
    let mut statistics = SolverStatistics::default();
    let mut pairs: Vec<Option<(Vec<f64>, Mat<f64>)>> = vec![None; requests.len()];
    let budget = options.slice_memory.unwrap_or_else(default_slice_memory);

    let clock = PhaseClock::start();
    let plans = count_intervals(requests, options, budget, &mut pairs)?;
    clock.stop(&mut statistics.counting);

    let clock = PhaseClock::start();
    let jobs = interval_jobs(requests, &plans);
    let gate = MemoryGate::new(budget, job_memory(requests, options, &plans, &jobs));
    let streaming = options.finished.is_some();
    let (eigenvectors, files, columns) = eigenvector_storage(requests, &plans, streaming, budget);
    let (intervals, assembled) =
        solve_intervals(requests, options, &plans, (&jobs, &gate), &columns)?;
    drop(files);
    statistics.peak_slice_memory = gate.peak();
    for part in intervals.iter().flatten() {
        statistics.refined_pairs += part.refinement.refined;
        statistics.refinement.wall_seconds += part.refinement.wall_seconds;
        statistics.refinement.cpu_seconds += part.refinement.cpu_seconds;
    }
    let mut residuals: Vec<Option<Vec<FieldResidual>>> = vec![None; requests.len()];
    let mut eigenvectors = eigenvectors.into_iter();
    for (plan, (values, field)) in plans.iter().zip(assembled) {
        let request = &requests[plan.request];
        let values = checked_values(plan, request, values).map_err(fail(plan.request))?;
        let (n, k) = (request.pencil.dimension(), request.count);
        let vectors = match eigenvectors.next() {
            Some(mut vectors) => {
                // SAFETY: every job of the plan returned, and each wrote all the columns of
                // its part of the reserved `n × k` (checked in `solve_job`); the parts cover
                // columns `0..k`.
                unsafe { vectors.set_dims(n, k) };
                vectors
            }
            None => Mat::zeros(n, 0),
        };
        pairs[plan.request] = Some((values, vectors));
        residuals[plan.request] = Some(field);
    }
    let mut results = Vec::with_capacity(requests.len());
    for (r, ((request, found), field)) in requests.iter().zip(pairs).zip(residuals).enumerate() {
        let found = match (options.finished, found, field) {
            // Solved densely (or nothing wanted): handed on whole.
            (Some(sink), Some((values, vectors)), None) => {
                let result = finish_request(
                    request,
                    Some((values, vectors)),
                    None,
                    &mut statistics,
                    options.parallelism,
                );
                hand_on_whole(sink, r, result).map_err(fail(r))?
            }
            (_, found, field) => {
                finish_request(request, found, field, &mut statistics, options.parallelism)
            }
        };
        results.push(found);
    }
    clock.stop(&mut statistics.solving);
    Ok(EigenSolution {
        pairs: results,
        statistics,
    })
}

/// Where each plan's eigenvectors go while its jobs refine them (`n × k` columns per plan): the
/// jobs write straight into their columns of one matrix, reserved here untouched, and their own
/// memory is recycled ([`WorkspacePool`]), so no interval holds a copy until the end. Streamed
/// (`streaming`), they are in a mapped temporary file instead, where an interval that waits for
/// an earlier one to be handed on can leave memory ([`FileBackedColumns`]), unless all of them
/// are small next to the slice budget `budget` ([`streamed_eigenvectors_in_memory`]): then in
/// anonymous memory, whose pages are given back as they are handed on. Returns the matrices
/// (not streamed), the files or memory (streamed) and the jobs' raw view of each plan's
/// columns, which stays valid while the matrices or files live.
fn eigenvector_storage(
    requests: &[EigenRequest<'_, '_>],
    plans: &[Plan],
    streaming: bool,
    budget: usize,
) -> (Vec<Mat<f64>>, Vec<FileBackedColumns>, Vec<RawColumns>) {
    let (mut eigenvectors, mut files): (Vec<Mat<f64>>, Vec<FileBackedColumns>) = (vec![], vec![]);
    let bytes = plans
        .iter()
        .map(|plan| {
            let request = &requests[plan.request];
            request.pencil.dimension() * request.count * std::mem::size_of::<f64>()
        })
        .sum();
    let in_memory = streaming && streamed_eigenvectors_in_memory(bytes, budget);
    for plan in plans {
        let request = &requests[plan.request];
        let (n, k) = (request.pencil.dimension(), request.count);
        if in_memory {
            files.push(FileBackedColumns::in_memory(n, k));
        } else if streaming {
            files.push(FileBackedColumns::new(n, k));
        } else {
            eigenvectors.push(reserve_on_huge_pages(n, k));
        }
    }
    let columns = plans
        .iter()
        .enumerate()
        .map(|(p, plan)| {
            let request = &requests[plan.request];
            let (n, k) = (request.pencil.dimension(), request.count);
            match streaming {
                true => files[p].raw(k),
                false => RawColumns {
                    ptr: eigenvectors[p].as_ptr_mut(),
                    rows: n,
                    col_stride: eigenvectors[p].col_stride().unsigned_abs(),
                    k,
                    file: None,
                },
            }
        })
        .collect();
    (eigenvectors, files, columns)
}

/// `result` with its vectors handed to `sink` (request `request`, from column 0) and dropped.
fn hand_on_whole(
    sink: &EigenvectorSink<'_>,
    request: usize,
    mut result: Eigenpairs,
) -> Result<Eigenpairs, SolverError> {
    if !result.values.is_empty() {
        sink(&FinishedEigenvectors {
            request,
            first: 0,
            values: &result.values,
            vectors: result.vectors.as_ref(),
        })
        .map_err(|reason| SolverError::Stopped { reason })?;
    }
    result.vectors = Mat::zeros(result.vectors.nrows(), 0);
    Ok(result)
}

/// Turns a [`SolverError`] of request `request` into a [`RequestError`].
fn fail(request: usize) -> impl Fn(SolverError) -> RequestError {
    move |source: SolverError| RequestError { request, source }
}

/// Phase 1, counting: the requests with nothing to slice are answered in `pairs` (none wanted,
/// or small enough for the dense solver); the others get a [`Plan`] whose boundaries are all
/// counted (concurrently) and checked for monotone counts. Its intervals are of
/// `EigenOptions::interval_size` eigenpairs, fewer where one slice of that size would not fit
/// in `budget` bytes ([`interval_size_within`]).
fn count_intervals(
    requests: &[EigenRequest<'_, '_>],
    options: &EigenOptions<'_>,
    budget: usize,
    pairs: &mut [Option<(Vec<f64>, Mat<f64>)>],
) -> Result<Vec<Plan>, RequestError> {
    let mut plans: Vec<Plan> = Vec::new();
    for (r, request) in requests.iter().enumerate() {
        let pencil = request.pencil;
        let (n, k) = (pencil.dimension(), request.count);
        if k > n {
            return Err(fail(r)(SolverError::TooManyEigenpairs {
                requested: k,
                dimension: n,
            }));
        }
        if k == 0 {
            pairs[r] = Some((Vec::new(), Mat::zeros(n, 0)));
        } else if n <= options.dense_threshold || 3 * k >= n {
            let (values, vectors) = pencil.dense_eigenpairs().map_err(fail(r))?;
            pairs[r] = Some((
                values[..k].to_vec(),
                vectors.as_ref().subcols(0, k).to_owned(),
            ));
        } else {
            let block = block_size(options, n);
            let top = top_shift(request, block).map_err(fail(r))?;
            let size = interval_size_within(n, block, options.interval_size, budget);
            plans.push(Plan::new(r, pencil, top, size));
        }
    }
    count_boundaries(requests, &mut plans)?;
    Ok(plans)
}

/// The request's top shift: the one it brings (checked to have at least `count` eigenvalues
/// below it), else one found by [`search_top`].
fn top_shift(request: &EigenRequest<'_, '_>, block: usize) -> Result<ShiftCount, SolverError> {
    let k = request.count;
    match request.top {
        Some(top) if top.below >= k => Ok(top),
        Some(top) => Err(SolverError::NoConvergence {
            reason: format!(
                "the top shift {:e} has {} eigenvalues below it, fewer than the {k} wanted",
                top.shift, top.below
            ),
        }),
        None => search_top(request.pencil, k, block),
    }
}

/// Counts every plan's uncounted boundaries in one concurrent batch, then checks that each
/// plan's bounds increase and its counts do not decrease.
fn count_boundaries(
    requests: &[EigenRequest<'_, '_>],
    plans: &mut [Plan],
) -> Result<(), RequestError> {
    let boundary_jobs: Vec<(usize, usize)> = plans
        .iter()
        .enumerate()
        .flat_map(|(p, plan)| plan.uncounted().map(move |i| (p, i)))
        .collect();
    let counted: Vec<Result<ShiftCount, RequestError>> = boundary_jobs
        .par_iter()
        .map(|&(p, i)| {
            let plan = &plans[p];
            requests[plan.request]
                .pencil
                .count_below(plan.bounds[i])
                .map_err(fail(plan.request))
        })
        .collect();
    for (&(p, i), count) in boundary_jobs.iter().zip(counted) {
        let count = count?;
        plans[p].bounds[i] = count.shift;
        plans[p].counts[i] = count.below;
    }
    for plan in plans.iter() {
        if plan.counts.windows(2).any(|w| w[1] < w[0])
            || plan.bounds.windows(2).any(|w| w[1] <= w[0])
        {
            return Err(fail(plan.request)(SolverError::NoConvergence {
                reason: "inertia counts at the interval boundaries are not monotone".into(),
            }));
        }
    }
    Ok(())
}

/// The jobs of phase 2: `(plan, interval)` for every interval that holds eigenvalues, the
/// plans of larger dimension first and each plan's intervals in ascending order, so that each
/// finished interval soon becomes final ([`IntervalStream`] places it and takes its residuals
/// while the other jobs run) and few wait in memory for an earlier one.
fn interval_jobs(requests: &[EigenRequest<'_, '_>], plans: &[Plan]) -> Vec<(usize, usize)> {
    let mut jobs: Vec<(usize, usize)> = plans
        .iter()
        .enumerate()
        .flat_map(|(p, plan)| {
            (0..plan.bounds.len() - 1)
                .filter(|&i| plan.counts[i + 1] > plan.counts[i])
                .map(move |i| (p, i))
        })
        .collect();
    let dimension = |p: usize| requests[plans[p].request].pencil.dimension();
    jobs.sort_by_key(|&(p, i)| (std::cmp::Reverse(dimension(p)), p, i));
    jobs
}

/// The estimated work memory of each job's slice in bytes ([`slice_bytes`]), from its plan's
/// largest interval, so that all jobs of a plan cost the same and [`MemoryGate`] keeps each
/// plan's jobs in their order.
fn job_memory(
    requests: &[EigenRequest<'_, '_>],
    options: &EigenOptions<'_>,
    plans: &[Plan],
    jobs: &[(usize, usize)],
) -> Vec<usize> {
    let plan_memory: Vec<usize> = widest_slices(requests, options, plans)
        .into_iter()
        .map(|(n, wanted, block)| slice_bytes(n, wanted, block))
        .collect();
    jobs.iter().map(|&(p, _)| plan_memory[p]).collect()
}

/// Each plan's widest slice, `(n, eigenpairs, block)`: what its jobs' memory is estimated and
/// reserved for.
fn widest_slices(
    requests: &[EigenRequest<'_, '_>],
    options: &EigenOptions<'_>,
    plans: &[Plan],
) -> Vec<(usize, usize, usize)> {
    plans
        .iter()
        .map(|plan| {
            let n = requests[plan.request].pencil.dimension();
            (n, plan.widest(), block_size(options, n))
        })
        .collect()
}

/// Phase 2, solving: runs every job (`options.threads` at a time, fewer while `gate` finds no
/// room for another slice, see [`run_jobs`]), each
/// writing its eigenvectors into its columns of its plan's memory `columns[p]` (reserved
/// `n × k`, one per plan); returns the solved intervals of each plan (in no particular order).
/// On success every column `0..k` of every plan was written and assembled (M-orthogonalised
/// against its neighbours, [`IntervalStream`]); with [`EigenOptions::finished`], every column
/// was handed to it instead (and released). The second result holds each plan's eigenvalues
/// (all of them, in column order) and field residuals (of its first `k` columns).
#[allow(clippy::type_complexity)]
fn solve_intervals(
    requests: &[EigenRequest<'_, '_>],
    options: &EigenOptions<'_>,
    plans: &[Plan],
    (jobs, gate): (&[(usize, usize)], &MemoryGate),
    columns: &[RawColumns],
) -> Result<
    (
        Vec<Vec<SolvedInterval>>,
        Vec<(Vec<f64>, Vec<FieldResidual>)>,
    ),
    RequestError,
> {
    let settings = IntervalSettings::of(options);
    let outputs = job_outputs(plans, jobs, columns);
    let streams = plans
        .iter()
        .zip(columns)
        .map(|(plan, &columns)| (plan.request, requests[plan.request].pencil, columns))
        .collect();
    let mut stream = IntervalStream::new(streams, jobs, options.finished, options.parallelism);
    let slice_memory = WorkspacePool::<SliceMemory>::new(jobs.len());
    // Streamed, each job's columns leave memory as it finishes, on the job's thread: the
    // calling thread places them only when its products get a worker of the pool the jobs
    // occupy (`interval_stream.rs`), which at a million faces took minutes.
    let parked: Vec<Option<ParkedColumns>> = jobs
        .iter()
        .enumerate()
        .map(|(job, &(p, _))| {
            let (first, width) = job_columns(plans, columns, jobs, job);
            options
                .finished
                .and(ParkedColumns::of(&columns[p], first, width))
        })
        .collect();
    let widest = widest_slices(requests, options, plans);
    let solve_job = |job: usize, report: &dyn Fn(usize, usize)| {
        let (p, i) = jobs[job];
        let plan = &plans[p];
        let output = outputs[job]
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
            .take()
            .expect("every job runs once");
        let mut memory = slice_memory.take();
        let (n, wanted, block) = widest[p];
        memory.expect(n, wanted, block);
        let result = solve_job(
            &requests[plan.request],
            plan,
            i,
            &settings,
            &mut memory,
            report,
            output,
        );
        slice_memory.give_back(memory);
        if let (Ok(_), Some(parked)) = (&result, parked[job]) {
            // SAFETY: the job has returned, so its view of its columns is gone; the calling
            // thread reads them only once this job's result has reached it.
            unsafe { parked.park() };
        }
        result.map_err(fail(plan.request))
    };
    let mut board = ProgressBoard::new(requests, plans, jobs, options.progress);
    let mut on_message = |job: usize, found: usize, done: bool| board.record(job, found, done);
    let mut on_result = |job: usize, parts: &Vec<SolvedInterval>| {
        let parts = parts
            .iter()
            .map(|part| SolvedPart {
                lower: part.lower,
                values: part.values.clone(),
            })
            .collect();
        let p = jobs[job].0;
        // SAFETY: the job has returned, so its view of its columns is gone; views of finished
        // jobs' columns live only inside the stream's calls.
        // On this thread: the pool's threads are busy with the jobs (see `calling_thread.rs`).
        on_calling_thread(|| unsafe { stream.job_done(job, parts) }).map_err(fail(plans[p].request))
    };
    let solved = run_jobs(
        (jobs.len(), gate),
        options.threads,
        &solve_job,
        &mut on_message,
        &mut on_result,
    )?;
    let mut intervals: Vec<Vec<SolvedInterval>> = plans.iter().map(|_| Vec::new()).collect();
    for (&(p, _), parts) in jobs.iter().zip(solved) {
        intervals[p].extend(parts);
    }
    Ok((intervals, stream.into_results()))
}

/// The columns `(first, width)` of plan `p`'s eigenvectors that job `job = (p, i)` fills:
/// `counts[i]..counts[i + 1]`, cut at the request's `k`.
fn job_columns(
    plans: &[Plan],
    columns: &[RawColumns],
    jobs: &[(usize, usize)],
    job: usize,
) -> (usize, usize) {
    let (p, i) = jobs[job];
    let (counts, k) = (&plans[p].counts, columns[p].k);
    (counts[i].min(k), counts[i + 1].min(k) - counts[i].min(k))
}

/// The output columns of each job: job `(p, i)` gets the columns of plan `p`'s eigenvectors
/// (`columns[p]`, reserved `n × k`) that interval `i` fills (`counts[i]..counts[i + 1]`, cut at
/// the request's `k`), as a view that a job takes once.
fn job_outputs<'m>(
    plans: &[Plan],
    jobs: &[(usize, usize)],
    columns: &'m [RawColumns],
) -> Vec<Mutex<Option<MatMut<'m, f64>>>> {
    let mut outputs: Vec<Option<MatMut<'m, f64>>> = jobs.iter().map(|_| None).collect();
    for (p, raw) in columns.iter().enumerate() {
        // SAFETY: the memory has room for `k` columns of `n` rows at its column stride
        // (reserved by the caller, and kept until the jobs are done); the views only write
        // (each job its own columns, all of them, checked in `solve_job` before the columns
        // become part of a matrix with `set_dims` in `lowest_eigenpairs_of` or are handed on by
        // the [`IntervalStream`]).
        let mut rest = unsafe {
            MatMut::from_raw_parts_mut(raw.ptr, raw.rows, raw.k, 1, raw.col_stride as isize)
        };
        for (i, job) in jobs_in_interval_order(jobs, p) {
            let counts = &plans[p].counts;
            let width = counts[i + 1].min(raw.k) - counts[i].min(raw.k);
            let (columns, tail) = rest.split_at_col_mut(width);
            outputs[job] = Some(columns);
            rest = tail;
        }
    }
    outputs.into_iter().map(Mutex::new).collect()
}

/// One job of phase 2: solves interval `i` of `plan` into `output` (its columns of the
/// eigenvectors) and checks that every column was written.
fn solve_job(
    request: &EigenRequest<'_, '_>,
    plan: &Plan,
    i: usize,
    settings: &IntervalSettings,
    memory: &mut SliceMemory,
    report: &dyn Fn(usize, usize),
    output: MatMut<'_, f64>,
) -> Result<Vec<SolvedInterval>, SolverError> {
    let interval = Interval {
        lower: (plan.bounds[i], plan.counts[i]),
        upper: (plan.bounds[i + 1], plan.counts[i + 1]),
        stream: i as u64 + 1,
    };
    let width = output.ncols();
    let mut solved = Vec::new();
    let written = solve_interval(
        request,
        &interval,
        settings,
        memory,
        0,
        report,
        &mut solved,
        output,
    )?;
    if written == width {
        Ok(solved)
    } else {
        Err(SolverError::NoConvergence {
            reason: format!("an interval wrote {written} of its {width} eigenvectors"),
        })
    }
}

/// Eigenpairs locked so far by each job, for the progress callback (per request: found, and
/// confirmed by finished jobs).
struct ProgressBoard<'r, 'p> {
    requests: &'r [EigenRequest<'p, 'p>],
    plans: &'r [Plan],
    jobs: &'r [(usize, usize)],
    callback: Option<&'r dyn Fn(&EigenProgress)>,
    locked: Vec<usize>,
    finished: Vec<bool>,
}

impl<'r, 'p> ProgressBoard<'r, 'p> {
    fn new(
        requests: &'r [EigenRequest<'p, 'p>],
        plans: &'r [Plan],
        jobs: &'r [(usize, usize)],
        callback: Option<&'r dyn Fn(&EigenProgress)>,
    ) -> Self {
        Self {
            requests,
            plans,
            jobs,
            callback,
            locked: vec![0; jobs.len()],
            finished: vec![false; jobs.len()],
        }
    }

    /// Job `job` has locked `found` eigenpairs, or (`done`) finished; reports the job's request.
    fn record(&mut self, job: usize, found: usize, done: bool) {
        let (p, i) = self.jobs[job];
        let plan = &self.plans[p];
        let wanted_here = plan.counts[i + 1] - plan.counts[i];
        if done {
            self.finished[job] = true;
            self.locked[job] = wanted_here;
        } else {
            self.locked[job] = found.min(wanted_here);
        }
        let Some(callback) = self.callback else {
            return;
        };
        let of_plan = |j: &usize| self.jobs[*j].0 == p;
        let confirmed = (0..self.jobs.len())
            .filter(|j| of_plan(j) && self.finished[*j])
            .map(|j| self.locked[j])
            .sum::<usize>();
        let found = (0..self.jobs.len())
            .filter(of_plan)
            .map(|j| self.locked[j])
            .sum::<usize>();
        let request = &self.requests[plan.request];
        let pencil_statistics = request.pencil.statistics();
        callback(&EigenProgress {
            request: plan.request,
            found: found.min(request.count),
            confirmed: confirmed.min(request.count),
            wanted: request.count,
            factorizations: pencil_statistics.factorizations(),
            solves: pencil_statistics.solves(),
        });
    }
}

/// The eigenvalues of every interval of `plan` in order, checked against its top count (all of
/// them, ascending) and cut to the request's `k`.
fn checked_values(
    plan: &Plan,
    request: &EigenRequest<'_, '_>,
    mut values: Vec<f64>,
) -> Result<Vec<f64>, SolverError> {
    let top = plan.counts[plan.counts.len() - 1];
    if values.len() != top || values.windows(2).any(|w| w[1] < w[0]) {
        return Err(SolverError::NoConvergence {
            reason: format!(
                "the intervals returned {} eigenvalues, the inertia count says {top}",
                values.len()
            ),
        });
    }
    values.truncate(request.count);
    Ok(values)
}

/// The result of one request from its assembled (or dense, or empty) pairs, with the field
/// residuals of every pair (`field`, if they were taken as the vectors were handed on, else
/// computed here); adds the pencil's factorizations and solves to `statistics`.
fn finish_request(
    request: &EigenRequest<'_, '_>,
    found: Option<(Vec<f64>, Mat<f64>)>,
    field: Option<Vec<FieldResidual>>,
    statistics: &mut SolverStatistics,
    par: Par,
) -> Eigenpairs {
    let pencil = request.pencil;
    let (values, vectors) =
        found.unwrap_or_else(|| (Vec::new(), Mat::zeros(pencil.dimension(), 0)));
    statistics.counting.factorizations += pencil.statistics().counting.factorizations;
    statistics.counting.solves += pencil.statistics().counting.solves;
    statistics.solving.factorizations += pencil.statistics().solving.factorizations;
    statistics.solving.solves += pencil.statistics().solving.solves;
    statistics.refinement.factorizations += pencil.statistics().refinement.factorizations;
    statistics.refinement.solves += pencil.statistics().refinement.solves;
    let field = field.unwrap_or_else(|| {
        let floor = 1e-8 * pencil.mean_eigenvalue.abs();
        field_residuals(
            &pencil.operators(),
            &values,
            vectors.as_ref(),
            floor,
            par,
            &mut [],
        )
    });
    Eigenpairs::new(
        pencil,
        values,
        vectors,
        field.iter().map(|f| f.relative).collect(),
        field.iter().map(|f| f.residual).collect(),
        field.iter().map(|f| f.floor).collect(),
    )
}

/// Vectors per Krylov block for a problem of dimension `n`.
fn block_size(options: &EigenOptions<'_>, n: usize) -> usize {
    options.block_size.clamp(1, n / 8 + 1)
}

/// The intervals of one request: boundaries `b_0 = −∞ < b_1 < … < b_m = σ_top` and their counts.
struct Plan {
    request: usize,
    bounds: Vec<f64>,
    counts: Vec<usize>,
    /// Whether `counts[i]` is known (`b_0`, `b_m` and shifts counted before).
    known: Vec<bool>,
}

impl Plan {
    fn new(request: usize, pencil: &Pencil<'_>, top: ShiftCount, interval_size: usize) -> Self {
        let intervals = top.below.div_ceil(interval_size).max(1);
        let width = top.shift / intervals as f64;
        let before = pencil.counted();
        let mut bounds = vec![f64::NEG_INFINITY];
        let mut counts = vec![0];
        let mut known = vec![true];
        for i in 1..intervals {
            let wanted = width * i as f64;
            let near = before
                .iter()
                .filter(|c| c.shift > bounds[i - 1] && c.shift < top.shift)
                .filter(|c| (c.shift - wanted).abs() <= 0.25 * width)
                .min_by(|a, b| {
                    (a.shift - wanted)
                        .abs()
                        .total_cmp(&(b.shift - wanted).abs())
                });
            match near {
                Some(count) => {
                    bounds.push(count.shift);
                    counts.push(count.below);
                    known.push(true);
                }
                None => {
                    bounds.push(wanted);
                    counts.push(0);
                    known.push(false);
                }
            }
        }
        bounds.push(top.shift);
        counts.push(top.below);
        known.push(true);
        Self {
            request,
            bounds,
            counts,
            known,
        }
    }

    /// Eigenpairs of the widest interval (0 before the boundaries are counted).
    fn widest(&self) -> usize {
        self.counts
            .windows(2)
            .map(|w| w[1].saturating_sub(w[0]))
            .max()
            .unwrap_or(0)
    }

    /// Boundaries still to be counted.
    fn uncounted(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.bounds.len()).filter(|&i| !self.known[i])
    }
}

/// A shift `σ_top` with at least `k` eigenvalues below it and not many more: trial shifts from
/// Weyl's law (ν grows linearly in σ), rescaled by `k/ν` and bracketed.
fn search_top(pencil: &Pencil<'_>, k: usize, block: usize) -> Result<ShiftCount, SolverError> {
    let n = pencil.dimension();
    let enough = k + block;
    let plenty = enough + enough / 16;
    let mean = if pencil.mean_eigenvalue > 0.0 {
        pencil.mean_eigenvalue
    } else {
        pencil.scale
    };
    let mut sigma = 2.0 * mean * enough as f64 / n as f64;
    let mut top: Option<ShiftCount> = None;
    let mut below: Option<ShiftCount> = None;
    for _ in 0..MAX_TOP_TRIALS {
        let count = pencil.count_below(sigma)?;
        if count.below >= k {
            if top.is_none_or(|t| count.shift < t.shift) {
                top = Some(count);
            }
            if count.below <= plenty {
                break;
            }
        } else if below.is_none_or(|b| count.shift > b.shift) {
            below = Some(count);
        }
        let target = 0.5 * (enough + plenty) as f64;
        let mut next = if count.below > 0 {
            count.shift * target / count.below as f64
        } else {
            4.0 * count.shift.abs().max(1e-12 * pencil.scale)
        };
        if let (Some(lo), Some(hi)) = (below, top) {
            if !(next > lo.shift && next < hi.shift) {
                next = 0.5 * (lo.shift + hi.shift);
            }
        }
        sigma = next;
    }
    top.ok_or_else(|| SolverError::NoConvergence {
        reason: format!("no shift with {k} eigenvalues below it found in {MAX_TOP_TRIALS} trials"),
    })
}

/// An interval to solve: `(bound, count)` at both ends and the random stream of its start block.
struct Interval {
    lower: (f64, usize),
    upper: (f64, usize),
    stream: u64,
}

/// One solved interval: its eigenvalues (ascending, refined; the eigenvectors went to the
/// columns the driver gave it) and what the refinement cost.
struct SolvedInterval {
    lower: f64,
    values: Vec<f64>,
    refinement: Refinement,
}

/// The numeric settings of the intervals (the part of [`EigenOptions`] the worker threads see).
#[derive(Clone, Copy)]
struct IntervalSettings {
    tolerance: f64,
    block_size: usize,
    max_restarts: usize,
    parallelism: Par,
    refinement_target: f64,
}

impl IntervalSettings {
    /// The settings `options` give.
    fn of(options: &EigenOptions<'_>) -> Self {
        Self {
            tolerance: options.tolerance,
            block_size: options.block_size,
            max_restarts: options.max_restarts,
            parallelism: options.parallelism,
            refinement_target: options.refinement_target,
        }
    }
}

/// Solves `interval` into `out` (its eigenvalues) and `output` (its eigenvectors: the first
/// `output.ncols() ≤ wanted` of them, fewer where the request ends inside the interval), with
/// `memory` as the slices' work memory; on failure splits it (`depth` splits so far). Returns
/// the number of columns of `output` written (all of them on success).
#[allow(clippy::too_many_arguments)]
fn solve_interval(
    request: &EigenRequest<'_, '_>,
    interval: &Interval,
    options: &IntervalSettings,
    memory: &mut SliceMemory,
    depth: usize,
    report: &dyn Fn(usize, usize),
    out: &mut Vec<SolvedInterval>,
    output: MatMut<'_, f64>,
) -> Result<usize, SolverError> {
    let pencil = request.pencil;
    let (lower, nu_lower) = interval.lower;
    let (upper, nu_upper) = interval.upper;
    let wanted = nu_upper - nu_lower;
    if wanted == 0 {
        return Ok(0);
    }
    let midpoint = if lower.is_finite() {
        0.5 * (lower + upper)
    } else {
        0.5 * upper
    };
    let (factor, count) = pencil.factor(midpoint, Phase::Solving, Par::Seq)?;
    let (sigma, nu) = (count.shift, count.below);
    if nu < nu_lower || nu > nu_upper || sigma >= upper {
        return Err(SolverError::NoConvergence {
            reason: format!(
                "the count {nu} at shift {sigma:e} contradicts the interval's counts {nu_lower}..{nu_upper}"
            ),
        });
    }
    let attempt = solve_at_shift(request, interval, options, memory, &factor, count, report);
    match attempt {
        Ok((mut values, (first, found))) => {
            let (vectors, scratch) = memory.vectors_and_scratch(pencil.dimension(), first + found);
            let mut vectors = vectors.subcols_mut(first, found);
            // Refined here, while the factorization is at hand, not in a later phase that
            // would have to keep every interval's factorization alive.
            let factor_at = |shift: f64| {
                pencil
                    .factor(shift, Phase::Refinement, Par::Seq)
                    .map(|(f, _)| f)
            };
            let refinement = refine_interval(
                &pencil.operators(),
                factor,
                &factor_at,
                &mut values,
                (vectors.rb_mut(), scratch),
                &RefinementSettings {
                    target: options.refinement_target,
                    floor: 1e-8 * pencil.mean_eigenvalue.abs(),
                    parallelism: options.parallelism,
                },
            )?;
            pencil.add_solves(Phase::Refinement, refinement.solves);
            let written = output.ncols().min(found);
            output
                .subcols_mut(0, written)
                .copy_from(vectors.rb().subcols(0, written));
            out.push(SolvedInterval {
                lower,
                values,
                refinement,
            });
            Ok(written)
        }
        Err(SolverError::NoConvergence { .. }) if depth < MAX_SPLITS => {
            drop(factor);
            solve_halves(
                request, interval, options, memory, depth, report, out, output,
            )
        }
        Err(e) => Err(e),
    }
}

/// [`solve_interval`] of an interval that failed at its midpoint: split near (not at) it, and
/// each half solved into its part of `output` with a midpoint of its own (`depth` splits so
/// far). Returns the number of columns written.
#[allow(clippy::too_many_arguments)]
fn solve_halves(
    request: &EigenRequest<'_, '_>,
    interval: &Interval,
    options: &IntervalSettings,
    memory: &mut SliceMemory,
    depth: usize,
    report: &dyn Fn(usize, usize),
    out: &mut Vec<SolvedInterval>,
    output: MatMut<'_, f64>,
) -> Result<usize, SolverError> {
    let (lower, nu_lower) = interval.lower;
    let (upper, nu_upper) = interval.upper;
    // Not at σ itself: if σ sits on an eigenvalue (the likely cause), a boundary there would
    // put that eigenvalue on an interval end. The halves get new midpoints.
    let split = if lower.is_finite() {
        lower + SPLIT_POINT * (upper - lower)
    } else {
        SPLIT_POINT * upper
    };
    let middle = request.pencil.count_below(split)?;
    if middle.below < nu_lower || middle.below > nu_upper || middle.shift >= upper {
        return Err(SolverError::NoConvergence {
            reason: format!(
                "the count {} at {:e} contradicts the interval's counts {nu_lower}..{nu_upper}",
                middle.below, middle.shift
            ),
        });
    }
    let halves = [
        Interval {
            lower: interval.lower,
            upper: (middle.shift, middle.below),
            stream: 2 * interval.stream + 1_000_003,
        },
        Interval {
            lower: (middle.shift, middle.below),
            upper: interval.upper,
            stream: 2 * interval.stream + 1_000_004,
        },
    ];
    let lower_width = (middle.below - nu_lower).min(output.ncols());
    let (lower_output, upper_output) = output.split_at_col_mut(lower_width);
    let mut written = 0;
    for (half, part) in halves.iter().zip([lower_output, upper_output]) {
        written += solve_interval(request, half, options, memory, depth + 1, report, out, part)?;
    }
    Ok(written)
}

/// The Krylov–Schur slice of `interval` at the shift of `factor` and its Rayleigh–Ritz against
/// `A`: the interval's eigenvalues, ascending, and `(first, count)`: their eigenvectors are
/// columns `first..first + count` of [`SliceMemory::vectors`].
fn solve_at_shift(
    request: &EigenRequest<'_, '_>,
    interval: &Interval,
    options: &IntervalSettings,
    memory: &mut SliceMemory,
    factor: &ShiftFactor,
    at: ShiftCount,
    report: &dyn Fn(usize, usize),
) -> Result<(Vec<f64>, (usize, usize)), SolverError> {
    let pencil = request.pencil;
    let n = pencil.dimension();
    let (lower, nu_lower) = interval.lower;
    let (upper, nu_upper) = interval.upper;
    let wanted = nu_upper - nu_lower;
    let block = options.block_size.clamp(1, n / 8 + 1);
    let problem = SliceProblem {
        factor,
        mass: pencil.mass(),
        sigma: at.shift,
        lower_bound: lower,
        lower_needed: at.below - nu_lower,
        upper_target: nu_upper - at.below,
        upper_bound: upper,
    };
    let settings = SliceSettings {
        block_size: block,
        tolerance: options.tolerance,
        max_restarts: options.max_restarts,
        max_basis: 2 * wanted + 4 * block,
        parallelism: options.parallelism,
    };
    let mut rng = ChaCha8Rng::seed_from_u64(request.seed);
    rng.set_stream(interval.stream);
    let outcome = run_slice(
        &problem,
        &settings,
        memory,
        &mut rng,
        &mut |locked, solves| report(locked, solves),
    );
    let solves = match &outcome {
        Ok(o) => o.solves,
        Err(_) => 0,
    };
    pencil.add_solves(Phase::Solving, solves);
    let outcome = outcome?;
    let operators = pencil.operators();
    let (vectors, scratch) = memory.vectors_and_scratch(n, outcome.columns);
    let values = rayleigh_ritz(
        operators.stiffness,
        operators.mass,
        vectors,
        scratch,
        options.parallelism,
    )?;
    // The values ascend, so the ones inside the interval are consecutive.
    let first = values.partition_point(|&v| v <= lower);
    let found = values[first..].partition_point(|&v| v < upper);
    if found != wanted {
        return Err(SolverError::NoConvergence {
            reason: format!(
                "the interval ({lower:e}, {upper:e}) holds {wanted} eigenvalues, {found} were found"
            ),
        });
    }
    Ok((values[first..first + found].to_vec(), (first, found)))
}

/// One job: `(job index, progress report(locked, solves))`.
type Job<'a, T> = dyn Fn(usize, &dyn Fn(usize, usize)) -> Result<T, RequestError> + Sync + 'a;

/// The payload a job unwinds with when the calling thread is gone (see [`run_jobs`]).
struct CallerGone;

/// A message from a worker thread to the coordinating thread.
enum Message<T> {
    Progress {
        job: usize,
        locked: usize,
    },
    Done {
        job: usize,
        result: Result<T, RequestError>,
    },
}

/// Runs `jobs` jobs, `threads` at a time as tasks of the current rayon pool (a job starts only
/// when `gate` admits it, see [`MemoryGate`]), and returns their results in job order;
/// `on_message(job, locked, done)` is called on the calling thread for every progress report and
/// completion, and `on_result(job, result)` with every successful result as it arrives. Stops
/// at the first error (of a job or of `on_result`); if `on_message` unwinds, every job stops at
/// its next report and the unwinding goes on once they have.
fn run_jobs<T: Send>(
    (jobs, gate): (usize, &MemoryGate),
    threads: usize,
    work: &Job<'_, T>,
    on_message: &mut dyn FnMut(usize, usize, bool),
    on_result: &mut dyn FnMut(usize, &T) -> Result<(), RequestError>,
) -> Result<Vec<T>, RequestError> {
    let failed = AtomicBool::new(false);
    let mut results: Vec<Option<Result<T, RequestError>>> = (0..jobs).map(|_| None).collect();
    std::thread::scope(|scope| {
        let (sender, receiver) = mpsc::channel::<Message<T>>();
        let failed = &failed;
        // The workers are tasks of rayon's pool, not threads of their own: a job's parallel
        // products then split by work stealing on the same threads (a thread outside the pool
        // would hand each of them to the pool and sleep until it is done, and the pool's
        // threads and the job threads would contend for the cores).
        scope.spawn(move || {
            rayon::scope(|pool| {
                for _ in 0..threads.clamp(1, jobs.max(1)) {
                    let sender = sender.clone();
                    pool.spawn(move |_| {
                        while let Some(admitted) = gate.admit(failed) {
                            let job = admitted.job;
                            let report = |locked: usize, _solves: usize| {
                                // The receiver outlives the workers unless the calling thread
                                // unwound (its progress callback stopped the computation, e.g. on
                                // Ctrl+C): then this job stops too, at its next report.
                                if sender.send(Message::Progress { job, locked }).is_err() {
                                    std::panic::resume_unwind(Box::new(CallerGone));
                                }
                            };
                            let result = work(job, &report);
                            drop(admitted);
                            if result.is_err() {
                                failed.store(true, Ordering::Relaxed);
                            }
                            let _ = sender.send(Message::Done { job, result });
                        }
                    });
                }
            });
        });
        for message in receiver {
            match message {
                Message::Progress { job, locked } => on_message(job, locked, false),
                Message::Done { job, result } => {
                    on_message(job, 0, true);
                    let result = result.and_then(|value| on_result(job, &value).map(|()| value));
                    if result.is_err() {
                        failed.store(true, Ordering::Relaxed);
                    }
                    results[job] = Some(result);
                }
            }
        }
    });
    // A job is missing only if another one failed: report that failure.
    if let Some(error) = results.iter().flatten().find_map(|r| r.as_ref().err()) {
        return Err(error.clone());
    }
    Ok(results.into_iter().flatten().flatten().collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;

    /// When `on_message` unwinds, every job stops at its next report instead of running to its
    /// end (a Ctrl+C in Python once waited for every interval to finish).
    #[test]
    fn jobs_stop_at_their_next_report_when_the_caller_unwinds() {
        struct Stop;
        const STEPS: usize = 10_000;
        let steps: Vec<AtomicUsize> = (0..4).map(|_| AtomicUsize::new(0)).collect();
        let work = |job: usize, report: &dyn Fn(usize, usize)| -> Result<(), RequestError> {
            for step in 0..STEPS {
                steps[job].fetch_add(1, Ordering::Relaxed);
                report(step, 0);
                std::thread::yield_now();
            }
            Ok(())
        };
        let run = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            run_jobs(
                (4, &MemoryGate::new(usize::MAX, vec![0; 4])),
                4,
                &work,
                &mut |_, _, _| std::panic::resume_unwind(Box::new(Stop)),
                &mut |_, _| Ok(()),
            )
        }));
        let Err(payload) = run else {
            panic!("the jobs were not stopped")
        };
        assert!(payload.is::<Stop>());
        for (job, count) in steps.iter().enumerate() {
            let count = count.load(Ordering::Relaxed);
            assert!(count < STEPS, "job {job} ran all its {count} steps");
        }
    }
}
