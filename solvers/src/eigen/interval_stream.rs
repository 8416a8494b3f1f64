//! [`IntervalStream`]: the solved intervals of every plan assembled as their jobs finish, so
//! that the assembly's work overlaps the jobs still running instead of following them all;
//! with a sink ([`EigenOptions::finished`](super::types::EigenOptions::finished)) the final
//! eigenvectors are handed to it and their memory given back, so that a request's `n × k`
//! eigenvectors are never all in memory.
//!
//! A vector is final once it is M-orthogonalised against the previous interval and the next
//! interval has been orthogonalised against it. So the intervals of a plan are taken in
//! ascending order as their jobs finish (the jobs run in that order, see `interval_jobs`; an
//! interval that finishes early waits until the one before it is solved): each part (an
//! interval, or a half of a split one) is orthogonalised against the part before it, whose
//! field residuals are then taken and which is handed on. The stream runs on the calling
//! thread with its products kept there (`calling_thread.rs`): handed to rayon's pool, whose
//! threads run the jobs, they waited for a free worker, and on `bunny-closed.obj` with Galerkin
//! masses the whole stream piled up after the last job (measured in `docs/performance.md`).
//! Without a sink the columns stay in the `n × k` matrix the jobs wrote (a mixed or sparse-mass
//! pencil's eigenfields are formed by the caller from the whole result). With a sink, every
//! job's columns leave memory as the job finishes (on the job's thread, so that they do not
//! wait for the stream), an interval waits on disk until it is placed, and handed-on columns
//! are given back ([`super::file_backed_columns`]). Both give the same vectors bit for bit.

use super::file_backed_columns::{drop_columns, ParkedColumns};
use super::mass::Mass;
use super::pencil::Pencil;
use super::refinement::{field_residuals_reusing, FieldResidual};
use super::symmetric_products::CHUNK;
use super::tall_products::{mass_inner, remove_mass_projection, tall_times};
use super::types::{EigenvectorSink, FinishedEigenvectors};
use crate::error::SolverError;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par};
use std::collections::HashMap;

/// A plan's reserved `rows × k` eigenvector matrix, as the raw columns the jobs write.
#[derive(Clone, Copy)]
pub(crate) struct RawColumns {
    pub ptr: *mut f64,
    pub rows: usize,
    pub col_stride: usize,
    pub k: usize,
    /// The descriptor of the file the columns are a shared mapping of, if they are
    /// ([`super::file_backed_columns`]).
    pub file: Option<i32>,
}

impl RawColumns {
    /// Columns `first..first + width` (inside `0..k`), to read.
    ///
    /// # Safety
    /// Every job that writes these columns has finished, and no mutable view of them is alive.
    unsafe fn columns<'m>(&self, first: usize, width: usize) -> MatRef<'m, f64> {
        debug_assert!(first + width <= self.k);
        MatRef::from_raw_parts(
            self.ptr.add(first * self.col_stride),
            self.rows,
            width,
            1,
            self.col_stride as isize,
        )
    }

    /// Columns `first..first + width` (inside `0..k`), to change.
    ///
    /// # Safety
    /// Every job that writes these columns has finished, and no other view of them is alive.
    unsafe fn columns_mut<'m>(&self, first: usize, width: usize) -> MatMut<'m, f64> {
        debug_assert!(first + width <= self.k);
        MatMut::from_raw_parts_mut(
            self.ptr.add(first * self.col_stride),
            self.rows,
            width,
            1,
            self.col_stride as isize,
        )
    }
}

/// One solved part of an interval: its lower end (the parts of an interval are ordered by it)
/// and its eigenvalues.
pub(crate) struct SolvedPart {
    pub lower: f64,
    pub values: Vec<f64>,
}

/// The stream of one plan (one request solved by intervals).
struct PlanStream<'p> {
    request: usize,
    pencil: &'p Pencil<'p>,
    columns: RawColumns,
    /// The plan's jobs `(interval, job)`, ascending in interval.
    order: Vec<(usize, usize)>,
    /// Position in `order` of the next interval to place.
    next: usize,
    /// Solved intervals waiting for an earlier one, by job.
    waiting: HashMap<usize, Vec<SolvedPart>>,
    /// The last part placed, `(first column, eigenpairs)`: final once the next part is
    /// orthogonalised against it.
    held: Option<(usize, usize)>,
    /// Eigenvalues of the placed parts, in column order.
    values: Vec<f64>,
    /// Field residuals of the columns handed on, in column order.
    residuals: Vec<FieldResidual>,
}

/// The streams of every plan of a call, fed with each job's parts as it finishes.
pub(crate) struct IntervalStream<'s> {
    plans: Vec<PlanStream<'s>>,
    /// Plan and interval of each job.
    jobs: &'s [(usize, usize)],
    /// Where final columns go; `None`: they stay where the jobs wrote them (the whole
    /// `n × k` result), and only their field residuals are taken.
    sink: Option<&'s EigenvectorSink<'s>>,
    par: Par,
}

impl<'s> IntervalStream<'s> {
    /// Streams for the plans of `requests` (`plans[p] = (request, pencil, columns)`) and
    /// `jobs` (plan and interval of each).
    pub(crate) fn new(
        plans: Vec<(usize, &'s Pencil<'s>, RawColumns)>,
        jobs: &'s [(usize, usize)],
        sink: Option<&'s EigenvectorSink<'s>>,
        par: Par,
    ) -> Self {
        let plans = plans
            .into_iter()
            .enumerate()
            .map(|(p, (request, pencil, columns))| {
                let order = jobs_in_interval_order(jobs, p);
                PlanStream {
                    request,
                    pencil,
                    columns,
                    order,
                    next: 0,
                    waiting: HashMap::new(),
                    held: None,
                    values: Vec::new(),
                    residuals: Vec::new(),
                }
            })
            .collect();
        Self {
            plans,
            jobs,
            sink,
            par,
        }
    }

    /// Job `job` finished with `parts` in its columns: places every interval that is now next
    /// in its plan and hands on what became final (all that is left when the plan's last
    /// interval is placed). The job's columns left memory when it finished (the job parked
    /// them, see `interval_slicing.rs`), so an interval that waits for an earlier one waits on
    /// disk; they fault back in when placed, and the part held for the next one is parked
    /// again.
    ///
    /// # Safety
    /// `job` has finished writing its columns, and no view of a finished job's columns is alive.
    pub(crate) unsafe fn job_done(
        &mut self,
        job: usize,
        mut parts: Vec<SolvedPart>,
    ) -> Result<(), SolverError> {
        let (sink, par) = (self.sink, self.par);
        let plan = &mut self.plans[self.jobs[job].0];
        parts.sort_by(|a, b| a.lower.total_cmp(&b.lower));
        plan.waiting.insert(job, parts);
        while let Some(&(_, next_job)) = plan.order.get(plan.next) {
            let Some(parts) = plan.waiting.remove(&next_job) else {
                break;
            };
            for part in parts {
                plan.place(part, sink, par)?;
            }
            plan.next += 1;
        }
        if plan.next == plan.order.len() {
            if let Some((first, count)) = plan.held.take() {
                plan.hand_on(first, count, sink)?;
            }
        }
        // The part held for the next one waits on disk too (placing faulted it back in).
        if let Some((first, count)) = plan.held {
            let width = (first + count).min(plan.columns.k).saturating_sub(first);
            if let Some(parked) = ParkedColumns::of(&plan.columns, first, width) {
                parked.park();
            }
        }
        Ok(())
    }

    /// The eigenvalues (all placed, in column order) and the field residuals (of the columns
    /// handed on) of each plan.
    pub(crate) fn into_results(self) -> Vec<(Vec<f64>, Vec<FieldResidual>)> {
        self.plans
            .into_iter()
            .map(|plan| (plan.values, plan.residuals))
            .collect()
    }
}

impl PlanStream<'_> {
    /// Places `part` after the parts before it: orthogonalises it against the held part
    /// ([`remove_projection_by_chunks`], columns past `k` left out), which is then final and
    /// handed on.
    unsafe fn place(
        &mut self,
        part: SolvedPart,
        sink: Option<&EigenvectorSink<'_>>,
        par: Par,
    ) -> Result<(), SolverError> {
        let k = self.columns.k;
        let start = self.values.len();
        if let Some((first, count)) = self.held.take() {
            if start < k {
                let current = part.values.len().min(k - start);
                let earlier = self.columns.columns(first, count);
                let columns = self.columns;
                // Each chunk of either part leaves memory again once used (the held part's
                // chunks are read again from the page cache for the next chunk; the placed
                // ones wait on disk to be handed on), so that two chunks are in memory at a
                // time. The views stay valid: a parked page keeps its values.
                let park = |first: usize, width: usize| {
                    if let Some(parked) = ParkedColumns::of(&columns, first, width) {
                        parked.park();
                    }
                };
                remove_projection_by_chunks(
                    columns.columns_mut(start, current),
                    earlier,
                    self.mass(),
                    par,
                    stream_columns(columns.rows),
                    |chunk| match chunk {
                        Chunk::Earlier(offset, width) => park(first + offset, width),
                        Chunk::Current(offset, width) => park(start + offset, width),
                    },
                );
            }
            self.hand_on(first, count, sink)?;
        }
        self.held = Some((start, part.values.len()));
        self.values.extend(part.values);
        Ok(())
    }

    fn mass(&self) -> Mass<'_> {
        self.pencil.mass()
    }

    /// Takes the field residuals of columns `first..first + count` (cut at `k`) and hands them
    /// to `sink`, [`stream_columns`] at a time, each chunk's memory released right after it
    /// (without a sink they stay).
    unsafe fn hand_on(
        &mut self,
        first: usize,
        count: usize,
        sink: Option<&EigenvectorSink<'_>>,
    ) -> Result<(), SolverError> {
        let k = self.columns.k;
        let width = (first + count).min(k).saturating_sub(first);
        if width == 0 {
            return Ok(());
        }
        let floor = 1e-8 * self.pencil.mean_eigenvalue.abs();
        // One set of residual buffers for the whole interval, on this thread: parallel
        // residuals made fresh buffers per chunk and per thread (0.8 GB per chunk at a million
        // faces) and waited for workers the jobs occupy.
        let mut buffers = None;
        let step = stream_columns(self.columns.rows);
        for offset in (0..width).step_by(step) {
            let (first, width) = (first + offset, step.min(width - offset));
            let vectors = self.columns.columns(first, width);
            let values = &self.values[first..first + width];
            self.residuals.extend(field_residuals_reusing(
                &self.pencil.operators(),
                values,
                vectors,
                floor,
                &mut buffers,
            ));
            if let Some(sink) = sink {
                sink(&FinishedEigenvectors {
                    request: self.request,
                    first,
                    values,
                    vectors,
                })
                .map_err(|reason| SolverError::Stopped { reason })?;
                drop_columns(&self.columns, first, width);
            }
        }
        Ok(())
    }
}

/// Bytes of an interval's columns orthogonalised or handed on at a time ([`stream_columns`]):
/// with a sink each chunk comes into memory, is worked on and leaves again, so that neither the
/// interval being placed nor the held one is in memory whole (two co-potential intervals of a
/// million-face mesh were 2.0 GB of mapped file pages at the peak, the held one whole beside a
/// chunk 1.27 GB; measured in `docs/performance.md`). Smaller meshes take an interval in one
/// chunk, computed as one product.
const STREAM_BYTES: usize = 256 << 20;

/// Columns of `n` rows taken at a time by the stream: [`STREAM_BYTES`] of them, in whole packed
/// chunks of `field_residuals` (so that its columns are grouped as in one call), at least one.
fn stream_columns(n: usize) -> usize {
    let columns = STREAM_BYTES / (size_of::<f64>() * n.max(1));
    (columns / CHUNK * CHUNK).max(CHUNK)
}

/// A chunk of columns [`remove_projection_by_chunks`] is done with for now: `(offset, width)`
/// in the earlier part (it is read again for the next chunk of the current one) or in the
/// current one (final).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Chunk {
    Earlier(usize, usize),
    Current(usize, usize),
}

/// `current ← current − earlier (earlierᵀ M current)` ([`remove_mass_projection`]) on `step`
/// columns of `current` at a time ([`stream_columns`]), calling `done` after each chunk of
/// either part is used: M-orthogonality restored across an interval boundary. Eigenvectors of
/// different intervals are orthogonal only up to `residual·‖A‖ / gap`, and the gap across a
/// boundary can be small (see `docs/performance.md` for the loss of orthogonality without this
/// step); intervals further apart are separated by at least an interval's width. Costs two
/// `n × s × s` products per boundary; the change of each vector is of the size of that error,
/// so residuals and in-interval orthonormality stay as they were.
///
/// An `earlier` wider than `step` is taken `step` columns at a time too, twice per chunk of
/// `current` (the overlap `earlierᵀ M current` block by block, then the update), so that at
/// most two chunks are in use at once; for `s` columns of `current` that reads `earlier`
/// `2 ⌈s / step⌉` times instead of once (from the page cache, for a streamed interval) and sums
/// the update in blocks (the same to rounding). An `earlier` of at most `step` columns is one
/// product, as without chunks, and stays in memory (it is handed on next).
fn remove_projection_by_chunks(
    mut current: MatMut<'_, f64>,
    earlier: MatRef<'_, f64>,
    mass: Mass<'_>,
    par: Par,
    step: usize,
    mut done: impl FnMut(Chunk),
) {
    let (count, held) = (current.ncols(), earlier.ncols());
    let blocks = |total: usize| {
        (0..total)
            .step_by(step)
            .map(move |o| (o, step.min(total - o)))
    };
    for (offset, width) in blocks(count) {
        let mut chunk = current.rb_mut().subcols_mut(offset, width);
        if held <= step {
            remove_mass_projection(chunk, earlier, mass, par);
        } else {
            let mut overlap = Mat::<f64>::zeros(held, width);
            for (first, rows) in blocks(held) {
                let block = mass_inner(earlier.subcols(first, rows), mass, chunk.rb(), par);
                overlap.as_mut().subrows_mut(first, rows).copy_from(&block);
                done(Chunk::Earlier(first, rows));
            }
            for (first, rows) in blocks(held) {
                tall_times(
                    chunk.rb_mut(),
                    Accum::Add,
                    earlier.subcols(first, rows),
                    overlap.as_ref().subrows(first, rows),
                    -1.0,
                    par,
                );
                done(Chunk::Earlier(first, rows));
            }
        }
        done(Chunk::Current(offset, width));
    }
}

/// The jobs of plan `p` as `(interval, job)` pairs in ascending interval order, where `jobs`
/// holds each job's `(plan, interval)`.
pub(super) fn jobs_in_interval_order(jobs: &[(usize, usize)], p: usize) -> Vec<(usize, usize)> {
    let mut order: Vec<(usize, usize)> = jobs
        .iter()
        .enumerate()
        .filter(|(_, &(q, _))| q == p)
        .map(|(job, &(_, i))| (i, job))
        .collect();
    order.sort_unstable();
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stream's chunks: whole packed chunks of at most [`STREAM_BYTES`], at least one.
    #[test]
    fn stream_chunks_are_whole_packed_chunks_within_the_byte_budget() {
        for n in [1, 1000, 104_000, 510_838, 1_532_520, 50_000_000] {
            let columns = stream_columns(n);
            assert_eq!(columns % CHUNK, 0, "n = {n}");
            assert!(columns >= CHUNK, "n = {n}");
            assert!(
                columns == CHUNK || columns * n * 8 <= STREAM_BYTES,
                "n = {n}"
            );
        }
        assert_eq!(stream_columns(1_532_520), 16);
        assert!(stream_columns(104_000) >= 96 + 16);
    }

    /// Chunk by chunk, the projection is the one of all columns at once (to rounding), the
    /// result is M-orthogonal to `earlier`, and every column is reported once, in order.
    #[test]
    fn a_projection_by_chunks_is_the_whole_projection() {
        let (n, p, q) = (400, 12, 21);
        let mass: Vec<f64> = (0..n).map(|i| 0.5 + (i % 7) as f64 / 7.0).collect();
        let mass = Mass::Diagonal(&mass);
        // M-orthonormal columns, as an interval's eigenvectors are (modified Gram–Schmidt).
        let mut earlier = Mat::from_fn(n, p, |i, j| ((i * 17 + j * 31) % 53) as f64 / 26.0 - 1.0);
        for j in 0..p {
            for k in 0..j {
                let c = mass_inner(
                    earlier.col(k).as_mat(),
                    mass,
                    earlier.col(j).as_mat(),
                    Par::Seq,
                )[(0, 0)];
                for i in 0..n {
                    earlier[(i, j)] -= c * earlier[(i, k)];
                }
            }
            let norm = mass_inner(
                earlier.col(j).as_mat(),
                mass,
                earlier.col(j).as_mat(),
                Par::Seq,
            )[(0, 0)]
                .sqrt();
            for i in 0..n {
                earlier[(i, j)] /= norm;
            }
        }
        let current = Mat::from_fn(n, q, |i, j| ((i * 23 + j * 11) % 41) as f64 / 20.0 - 1.0);
        let mut whole = current.clone();
        remove_mass_projection(whole.as_mut(), earlier.as_ref(), mass, Par::Seq);
        let mut chunked = current.clone();
        let mut reported = Vec::new();
        remove_projection_by_chunks(
            chunked.as_mut(),
            earlier.as_ref(),
            mass,
            Par::Seq,
            CHUNK,
            |chunk| reported.push(chunk),
        );
        // The 12 earlier columns in two blocks, twice for each chunk of the current ones.
        let earlier_twice = [(0, 8), (8, 4), (0, 8), (8, 4)].map(|(o, w)| Chunk::Earlier(o, w));
        let expected: Vec<Chunk> = [(0, 8), (8, 8), (16, 5)]
            .into_iter()
            .flat_map(|(o, w)| earlier_twice.into_iter().chain([Chunk::Current(o, w)]))
            .collect();
        assert_eq!(reported, expected);
        assert!((&chunked - &whole).norm_max() <= 1e-13 * whole.norm_max());
        let overlap = mass_inner(earlier.as_ref(), mass, chunked.as_ref(), Par::Seq);
        assert!(overlap.norm_max() <= 1e-12 * current.norm_max());
        // An earlier part that fits in one chunk is one product, bit for bit.
        let mut one_block = current.clone();
        remove_projection_by_chunks(
            one_block.as_mut(),
            earlier.as_ref(),
            mass,
            Par::Seq,
            16,
            |_| {},
        );
        let mut whole_16 = current.clone();
        for offset in [0, 16] {
            let width = 16.min(q - offset);
            remove_mass_projection(
                whole_16.as_mut().subcols_mut(offset, width),
                earlier.as_ref(),
                mass,
                Par::Seq,
            );
        }
        assert_eq!(one_block, whole_16);
    }
}
