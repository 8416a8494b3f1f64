//! One spectrum slice: block Krylov–Schur (thick-restart block Lanczos with full
//! reorthogonalisation) on the shift-inverted operator `OP = (A − σM)⁻¹ M`, which is
//! self-adjoint in the M inner product (`M` diagonal or sparse SPD; for a mixed pencil the
//! solve goes through a matrix on the edges or a saddle matrix, see `shift_factor.rs`). Eigenvalues λ of `(A, M)` near σ become the
//! largest-magnitude eigenvalues `θ = 1/(λ − σ)` of `OP`.
//!
//! State (all M-orthonormal, mutually M-orthogonal):
//! - `locked`: converged eigenvectors of this slice;
//! - `V` (`n × m`, "expanded"): `OP V = V H + U G` with symmetric `H` (`m × m`);
//! - `U` (`n × r`, "unexpanded"): the next block to which `OP` is applied.
//!
//! Expanding applies `OP` to `U` with one blocked solve, orthogonalises the result with block
//! Gram–Schmidt (the update by `V` with the coefficients the Krylov relation gives, where the
//! cancellation is, then DGKS-checked passes against locked and `V` together, usually one; the
//! two are fused into two sweeps over the rows, see
//! [`super::mass_orthogonal::project_out_after_known`]), and appends `U` to `V`. The locked
//! vectors' eigenvalues are recomputed afterwards by the driver's
//! Rayleigh–Ritz against `A` (see `rayleigh_ritz.rs` for why the Ritz values `θ` alone are not
//! accurate enough).
//!
//! At a restart the Rayleigh–Ritz pairs of `H` are sorted by `|θ|`; converged wanted ones are locked (their
//! couplings `‖G y‖ ≤ tol·|θ|` are dropped), the best unconverged ones are kept
//! (`V ← V Y`, `H ← Θ`, `G ← G Y`), and the rest is purged. Once at most half of the slice's
//! pairs are still missing, the expansion checks every [`COMPLETION_CHECK_BLOCKS`] blocks whether
//! the Ritz pairs of `H` already complete the slice, and stops there instead of filling the
//! basis, which saves solves (on average half a cycle's; measured in `docs/performance.md`).

use super::mass::Mass;
use super::mass_orthogonal::{
    orthonormalize_block, project_out_after_known, random_orthonormal_block,
};
use super::shift_factor::{SaddleScratch, ShiftFactor};
use super::symmetric_products::gather_times;
use super::tall_products::{mass_inner, tall_times, tall_times_in_place};
use crate::error::SolverError;
use crate::huge_pages::reserve_values_on_huge_pages;
use crate::packed_rows::{contiguous, contiguous_columns_mut, pack_columns, Row, WIDTH};
use crate::symmetric_eigen::symmetric_eigen;
use faer::linalg::matmul::matmul;
use faer::reborrow::{IntoConst, Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par};
use rand_chacha::ChaCha8Rng;

/// What one slice must find.
pub(crate) struct SliceProblem<'a> {
    /// The factorization at σ (of `A − σM`, or of a mixed pencil's matrix, see `shift_factor.rs`).
    pub factor: &'a ShiftFactor,
    /// `M`, rows in the pencil's input order.
    pub mass: Mass<'a>,
    /// The shift σ.
    pub sigma: f64,
    /// The interval's lower end: eigenvalues `≤ lower_bound` belong to another interval and
    /// never count.
    pub lower_bound: f64,
    /// Number of eigenvalues in `(lower_bound, σ)` (from the inertia counts).
    pub lower_needed: usize,
    /// Number of eigenvalues in `[σ, upper_bound)` (from the inertia counts).
    pub upper_target: usize,
    /// The interval's upper end: only eigenvalues below it count towards `upper_target` (an
    /// exact count from inertia). Converged pairs just above it may still be locked (they
    /// deflate the slice) and are discarded by the caller.
    pub upper_bound: f64,
}

/// Algorithm parameters of a slice.
pub(crate) struct SliceSettings {
    pub block_size: usize,
    pub tolerance: f64,
    pub max_restarts: usize,
    pub max_basis: usize,
    pub parallelism: Par,
}

/// What a slice found: `columns` converged eigenvectors, after one inverse-iteration step, in
/// the first `n × columns` values of the slice's [`SliceMemory`] ([`SliceMemory::vectors`];
/// unsorted: their eigenvalues are recomputed by the driver's final Rayleigh–Ritz against `A`,
/// which is more accurate than the Ritz values `θ`).
pub(crate) struct SliceOutcome {
    pub columns: usize,
    pub solves: usize,
}

/// Growable `n × count` column store in borrowed memory (column-major values): it is written
/// only as columns are appended, and grows (by reallocation, never by a zeroed copy) only when
/// a slice locks more columns than the memory has room for.
struct ColumnStore<'m> {
    values: &'m mut Vec<f64>,
    n: usize,
    columns: usize,
}

impl<'m> ColumnStore<'m> {
    /// An empty store of columns of `n` rows in `values` (sized by [`SliceMemory::fit`]).
    fn new(values: &'m mut Vec<f64>, n: usize) -> Self {
        Self {
            values,
            n,
            columns: 0,
        }
    }

    fn view(&self) -> MatRef<'_, f64> {
        let len = self.n * self.columns;
        MatRef::from_column_major_slice(&self.values[..len], self.n, self.columns)
    }

    /// Appends the Ritz vectors `V y_j` for the columns `j ∈ chosen` of `y` (`V: n × m`,
    /// `y: m × m`), formed in place.
    fn append_ritz_vectors(
        &mut self,
        v: MatRef<'_, f64>,
        y: &Mat<f64>,
        chosen: &[usize],
        par: Par,
    ) {
        if chosen.is_empty() {
            return;
        }
        let y_chosen = Mat::from_fn(v.ncols(), chosen.len(), |i, j| y[(i, chosen[j])]);
        self.append_product(v, y_chosen.as_ref(), par);
    }

    /// Appends the columns of `V Y` (`V: n × m`, `Y: m × c`), formed in place.
    fn append_product(&mut self, v: MatRef<'_, f64>, y: MatRef<'_, f64>, par: Par) {
        let (start, end) = (self.n * self.columns, self.n * (self.columns + y.ncols()));
        if self.values.len() < end {
            self.values.resize(end, 0.0);
        }
        let new =
            MatMut::from_column_major_slice_mut(&mut self.values[start..end], self.n, y.ncols());
        tall_times(new, Accum::Replace, v, y, 1.0, par);
        self.columns += y.ncols();
    }
}

/// The rows of `vectors` (in elimination order: row `i` is input row `order[i]`) put in input
/// order, column by column in place (one column of scratch space).
fn put_in_input_order(mut vectors: MatMut<'_, f64>, order: Option<&[usize]>) {
    let Some(order) = order else {
        return;
    };
    let mut column = vec![0.0; vectors.nrows()];
    for j in 0..vectors.ncols() {
        let mut target = vectors.rb_mut().col_mut(j);
        for (value, stored) in column.iter_mut().zip(target.rb().iter()) {
            *value = *stored;
        }
        for (&value, &row) in column.iter().zip(order) {
            target[row] = value;
        }
    }
}

/// Packed rows reused by every [`apply_operator`] of a slice (`n` rows each).
#[derive(Default)]
struct OperatorScratch {
    /// The block `U`, packed.
    block: Vec<Row>,
    /// `M U`, overwritten by the solve with `OP U`.
    solution: Vec<Row>,
    /// `M OP U` for a sparse `M` (empty otherwise).
    weighted: Vec<Row>,
    /// The edges' or the saddle system of a mixed pencil (empty otherwise).
    saddle: Vec<Row>,
    /// The refined solves of a mixed pencil's inverse-iteration step (empty otherwise).
    refined: SaddleScratch,
}

impl OperatorScratch {
    #[cfg(test)]
    fn new(n: usize) -> Self {
        let mut scratch = Self::default();
        scratch.fit(n);
        scratch
    }

    /// Makes both buffers `n` rows long (their values are overwritten before they are read).
    fn fit(&mut self, n: usize) {
        self.block.resize(n, [0.0; WIDTH]);
        self.solution.resize(n, [0.0; WIDTH]);
    }
}

/// The work memory of a slice, handed to the next slice by the driver (see
/// [`super::workspace_pool`]): the Krylov basis, the locked vectors (the slice's result, which
/// the driver copies out before it hands the memory on) and the operator's buffers.
#[derive(Default)]
pub(crate) struct SliceMemory {
    /// Values of the Krylov basis (column-major), sized by [`fit_memory`].
    basis: Vec<f64>,
    /// Values of the locked vectors (column-major), sized by [`fit_memory`].
    locked: Vec<f64>,
    scratch: OperatorScratch,
    /// The widest slice this memory is expected to serve ([`Self::expect`]).
    expected: ExpectedSlice,
}

/// The widest slice a [`SliceMemory`] will serve: its dimension `n`, eigenpairs and block.
#[derive(Default, Clone, Copy)]
struct ExpectedSlice {
    n: usize,
    wanted: usize,
    block: usize,
}

/// Columns of the Krylov basis of a slice that must find `wanted` eigenpairs in blocks of
/// `block` vectors: `2·wanted + 4·block` expanded columns and three unexpanded blocks.
pub(crate) fn basis_columns(wanted: usize, block: usize) -> usize {
    2 * wanted + 4 * block + 3 * block
}

/// Columns of a slice's locked vectors: the `wanted` eigenpairs and up to two blocks of
/// converged pairs just outside its interval.
pub(crate) fn locked_columns(wanted: usize, block: usize) -> usize {
    wanted + 2 * block
}

impl SliceMemory {
    /// The `n × columns` eigenvectors the last slice found ([`SliceOutcome`]) and, beside
    /// them, the slice's Krylov basis (idle once the slice is
    /// done) as scratch (stale values) for their Rayleigh–Ritz and refinement: all of it, at
    /// least `2·n·columns` values (grown only if the basis was narrower: it holds
    /// `2·wanted + 7·block` columns, the locked vectors `wanted + 2·block`, so it never is for
    /// the slice that found them).
    pub(crate) fn vectors_and_scratch(
        &mut self,
        n: usize,
        columns: usize,
    ) -> (MatMut<'_, f64>, &mut [f64]) {
        let scratch_len = 2 * n * columns;
        if self.basis.len() < scratch_len {
            self.basis.resize(scratch_len, 0.0);
        }
        (
            MatMut::from_column_major_slice_mut(&mut self.locked[..n * columns], n, columns),
            &mut self.basis,
        )
    }

    /// The `n × columns` Krylov basis, an empty store for `locked` locked vectors and the
    /// operator buffers of a slice, in this memory fitted for them ([`Self::fit`]).
    fn parts(
        &mut self,
        n: usize,
        columns: usize,
        locked: usize,
    ) -> (MatMut<'_, f64>, ColumnStore<'_>, &mut OperatorScratch) {
        self.fit(n, columns, locked);
        let basis = MatMut::from_column_major_slice_mut(&mut self.basis[..n * columns], n, columns);
        (
            basis,
            ColumnStore::new(&mut self.locked, n),
            &mut self.scratch,
        )
    }

    /// Declares the widest slice this memory will serve (a pencil of dimension `n`, `wanted`
    /// eigenpairs, blocks of `block`): from then on its memory is reserved for that slice
    /// whenever it has to grow, so that the slices of one pencil, whose intervals differ in
    /// width, reuse the memory a narrower one touched instead of each wider one reserving and
    /// touching all of it afresh (see [`fit_memory`]).
    pub(crate) fn expect(&mut self, n: usize, wanted: usize, block: usize) {
        self.expected = ExpectedSlice { n, wanted, block };
    }

    /// The columns `columns(wanted, block)` of the expected slice if its dimension is `n`
    /// (else 0: nothing reserved beyond what is asked for).
    fn expected_columns(&self, n: usize, columns: fn(usize, usize) -> usize) -> usize {
        let ExpectedSlice {
            n: m,
            wanted,
            block,
        } = self.expected;
        if m == n {
            columns(wanted, block)
        } else {
            0
        }
    }

    /// Room for an `n × columns` basis (stale values: every column is written before it is
    /// read; see [`fit_memory`]), `locked` locked vectors and operator buffers of `n` rows.
    fn fit(&mut self, n: usize, columns: usize, locked: usize) {
        let len = n * columns;
        let room = n * self.expected_columns(n, basis_columns);
        fit_memory(&mut self.basis, len, room);
        let locked_room = n * self.expected_columns(n, locked_columns);
        fit_memory(&mut self.locked, n * locked, locked_room);
        if self.basis.len() < len {
            self.basis.resize(len, 0.0);
        }
        self.scratch.fit(n);
    }
}

/// Makes `values` hold room for `len` values: memory that is too small is released and
/// reserved afresh on huge pages, for `room` values if that is more (the widest slice expected,
/// see [`SliceMemory::expect`]; reserved memory that is never touched costs no physical
/// memory); memory more than twice too large for both (a slice of the other, smaller pencil
/// after the large one) is shrunk in place (glibc shrinks a large allocation with `mremap`,
/// without moving it), so the pages it keeps are ones it has touched already (fresh pages cost
/// a kernel fault and zeroing each, see `interval_slicing.rs`). Kept oversized, the memory of
/// the large pencil's slices would stay for the small pencil's (GBs per thread at a million
/// faces while the last intervals fill the eigenvectors, which raises the peak; numbers in
/// `docs/performance.md`). Reserved only for `len`, every slice wider than the one before
/// touched its whole basis afresh (four Krylov bases of the `bunny-closed.obj` basis where two
/// would do; measured in `docs/performance.md`).
fn fit_memory(values: &mut Vec<f64>, len: usize, room: usize) {
    let room = room.max(len);
    if values.capacity() < len {
        *values = Vec::new();
        *values = reserve_values_on_huge_pages(room);
    } else if values.capacity() > 2 * room {
        values.truncate(len);
        values.shrink_to(room);
    }
}

/// What [`apply_operator`] measured on the way.
struct Applied {
    /// M-norms of the columns of `Z = OP U` (`r`).
    norms: Vec<f64>,
    /// `Uᵀ M Z` (`r × r`).
    own: Mat<f64>,
}

/// `z ← OP U = (A − σM)⁻¹ M U` for the block `u` (`n × r`, rows in elimination order), [`WIDTH`]
/// columns at a time ([`solve_chunk`], [`unpack_chunk`]), with the M-norms of `Z` and
/// `Uᵀ M Z` (for `r ≤ WIDTH` from the unpacking pass; a wider block takes one product).
fn apply_operator(
    factor: &ShiftFactor,
    mass: Mass<'_>,
    u: MatRef<'_, f64>,
    mut z: MatMut<'_, f64>,
    scratch: &mut OperatorScratch,
    par: Par,
) -> Applied {
    let r = u.ncols();
    let mut squared = vec![0.0; r];
    let mut own_rows = [[0.0; WIDTH]; WIDTH];
    for first in (0..r).step_by(WIDTH) {
        let width = WIDTH.min(r - first);
        solve_chunk(factor, mass, u.subcols(first, width), scratch, false);
        let own = (r <= WIDTH).then_some(&mut own_rows);
        let chunk = unpack_chunk(mass, z.rb_mut().subcols_mut(first, width), scratch, own);
        squared[first..first + width].copy_from_slice(&chunk[..width]);
    }
    let own = if r <= WIDTH {
        Mat::from_fn(r, r, |a, b| own_rows[a][b])
    } else {
        mass_inner(u, mass, z.rb(), par)
    };
    Applied {
        norms: squared.iter().map(|s| s.sqrt()).collect(),
        own,
    }
}

/// Packs the columns of `u` (`n × width`, `width ≤ WIDTH`) into `scratch.block` and `M U` into
/// `scratch.solution` in one pass, then overwrites the latter with `(A − σM)⁻¹ M U`.
fn solve_chunk(
    factor: &ShiftFactor,
    mass: Mass<'_>,
    u: MatRef<'_, f64>,
    scratch: &mut OperatorScratch,
    refined: bool,
) {
    let columns: Vec<&[f64]> = u.col_iter().map(contiguous).collect();
    pack_columns(&columns, &mut scratch.block);
    match mass {
        Mass::Diagonal(mass) => {
            for ((scaled, row), m) in scratch.solution.iter_mut().zip(&scratch.block).zip(mass) {
                *scaled = std::array::from_fn(|j| m * row[j]);
            }
        }
        Mass::Sparse(m) => gather_times(m, &scratch.block, &mut scratch.solution),
    }
    if refined {
        factor.solve_rows_refined(&mut scratch.solution, &mut scratch.refined);
    } else {
        factor.solve_rows(&mut scratch.solution, &mut scratch.saddle);
    }
}

/// Writes the solved chunk `scratch.solution` into the columns of `z` (`n × width`) and returns
/// their squared M-norms; with `own`, also adds `Uᵀ M Z` of the packed `scratch.block` to it.
fn unpack_chunk(
    mass: Mass<'_>,
    z: MatMut<'_, f64>,
    scratch: &mut OperatorScratch,
    own: Option<&mut [Row; WIDTH]>,
) -> Row {
    match mass {
        Mass::Diagonal(mass) => {
            let weighted = scratch
                .solution
                .iter()
                .zip(mass)
                .map(|(solved, m)| std::array::from_fn(|j| m * solved[j]));
            unpack_rows(z, scratch, weighted, own)
        }
        Mass::Sparse(m) => {
            scratch
                .weighted
                .resize(scratch.solution.len(), [0.0; WIDTH]);
            gather_times(m, &scratch.solution, &mut scratch.weighted);
            unpack_rows(z, scratch, scratch.weighted.iter().copied(), own)
        }
    }
}

/// [`unpack_chunk`] given the rows of `M Z` (`weighted`, one per row of `scratch.solution`).
fn unpack_rows(
    mut z: MatMut<'_, f64>,
    scratch: &OperatorScratch,
    weighted: impl Iterator<Item = Row>,
    mut own: Option<&mut [Row; WIDTH]>,
) -> Row {
    let mut targets = contiguous_columns_mut(z.rb_mut());
    let mut squared = [0.0; WIDTH];
    for (i, ((solved, row), weighted)) in scratch
        .solution
        .iter()
        .zip(&scratch.block)
        .zip(weighted)
        .enumerate()
    {
        for (j, target) in targets.iter_mut().enumerate() {
            target[i] = solved[j];
        }
        for j in 0..WIDTH {
            squared[j] += weighted[j] * solved[j];
        }
        if let Some(own) = own.as_deref_mut() {
            for (a, own_row) in own.iter_mut().enumerate() {
                for j in 0..WIDTH {
                    own_row[j] += row[a] * weighted[j];
                }
            }
        }
    }
    squared
}

/// One inverse-iteration step on every column of the locked vectors `x` (`n × s`, elimination
/// order), in place: `X ← (A − σM)⁻¹ M X`, columns M-normalised. It damps the rounding noise the
/// Krylov vectors carry at high frequencies, which the eigenfields would amplify, by
/// `|λ − σ| / |λ_m − σ|` per component (see `refinement.rs`): after it most pairs meet the
/// eigenfield target. Costs `s` solves.
///
/// Errors: [`SolverError::NoConvergence`] if a column vanishes.
fn inverse_iteration_step(
    factor: &ShiftFactor,
    mass: Mass<'_>,
    mut x: MatMut<'_, f64>,
    scratch: &mut OperatorScratch,
) -> Result<(), SolverError> {
    for first in (0..x.ncols()).step_by(WIDTH) {
        let width = WIDTH.min(x.ncols() - first);
        solve_chunk(factor, mass, x.rb().subcols(first, width), scratch, true);
        let mut chunk = x.rb_mut().subcols_mut(first, width);
        let squared = unpack_chunk(mass, chunk.rb_mut(), scratch, None);
        for (j, column) in chunk.col_iter_mut().enumerate() {
            let norm = squared[j].sqrt();
            if !(norm.is_finite() && norm > 0.0) {
                return Err(SolverError::NoConvergence {
                    reason: "an inverse-iteration step lost a locked vector".into(),
                });
            }
            column.iter_mut().for_each(|value| *value /= norm);
        }
    }
    Ok(())
}

/// Expansion steps (blocks) between two completion checks of a slice's last cycle: each check
/// is a dense eigen-decomposition of `H` (a few hundred square), about the cost of a step.
const COMPLETION_CHECK_BLOCKS: usize = 2;

/// The Ritz pairs of `H` (`m × m`) and what a Rayleigh–Ritz does with them.
struct RitzPairs {
    /// Ritz values `θ` of `OP` (`m`).
    theta: Vec<f64>,
    /// Eigenvectors of `H` (`m × m`, columns).
    y: Mat<f64>,
    /// `G Y` (`r × m`): the couplings of the Ritz vectors to the unexpanded block.
    gy: Mat<f64>,
    /// Converged pairs among the `window` largest `|θ|`, to lock.
    lock: Vec<usize>,
    /// Unconverged pairs, largest `|θ|` first, to keep at a thick restart.
    keep: Vec<usize>,
    /// Pairs of `lock` inside the interval below σ and above σ.
    inside: (usize, usize),
}

/// Rayleigh–Ritz of `H` with couplings `G` (`r × m`), given the pairs the slice has found
/// below (`lower_found`) and above (`upper_found`) σ. A pair is converged when its coupling
/// `‖G y‖ ≤ tolerance · |θ|`. Exact counts on both sides of a central shift: the wanted pairs are
/// (about) the largest `|θ|`, and converged pairs just outside the interval are locked too (they
/// deflate the slice instead of returning after every restart). `θ = 0` is purged.
fn ritz_pairs(
    h: MatRef<'_, f64>,
    g: MatRef<'_, f64>,
    problem: &SliceProblem<'_>,
    settings: &SliceSettings,
    (lower_found, upper_found): (usize, usize),
) -> Result<RitzPairs, SolverError> {
    let (theta, y) = symmetric_eigen(h)?;
    let m = theta.len();
    let mut gy = Mat::<f64>::zeros(g.nrows(), m);
    matmul(gy.as_mut(), Accum::Replace, g, y.as_ref(), 1.0, Par::Seq);
    let residual: Vec<f64> = (0..m)
        .map(|j| {
            (0..gy.nrows())
                .map(|i| gy[(i, j)] * gy[(i, j)])
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let lower_remaining = problem.lower_needed - lower_found;
    let upper_remaining = problem.upper_target.saturating_sub(upper_found);
    let window = lower_remaining + upper_remaining + settings.block_size.max(1);
    let mut order: Vec<usize> = (0..m).filter(|&i| theta[i] != 0.0).collect();
    order.sort_by(|&a, &b| theta[b].abs().total_cmp(&theta[a].abs()));
    let (mut lock, mut keep) = (Vec::new(), Vec::new());
    let mut inside = (0, 0);
    for (rank, &i) in order.iter().enumerate() {
        if residual[i] > settings.tolerance * theta[i].abs() {
            keep.push(i);
        } else if rank < window {
            lock.push(i);
            let lambda = problem.sigma + 1.0 / theta[i];
            if lambda < problem.sigma {
                inside.0 += usize::from(lambda > problem.lower_bound);
            } else if lambda < problem.upper_bound {
                inside.1 += 1;
            }
        }
    }
    Ok(RitzPairs {
        theta,
        y,
        gy,
        lock,
        keep,
        inside,
    })
}

/// Runs block Krylov–Schur until `lower_needed` eigenvalues in `(lower_bound, σ)` and
/// `upper_target` eigenvalues above σ are locked, then takes one inverse-iteration step on the
/// locked vectors ([`inverse_iteration_step`]; its solves are counted). `on_restart(locked,
/// solves)` is called after every restart.
///
/// The Krylov vectors are kept in the factorization's elimination order (for a mixed pencil,
/// the order of its `x` unknowns in it: see `shift_factor.rs`), so the solves need no gather
/// or scatter through the permutation; a diagonal `M` is permuted once per slice, a sparse one
/// once per pencil (`P M Pᵀ`, [`ShiftFactor::krylov_mass`]). The returned vectors are in the
/// input order.
pub(crate) fn run_slice(
    problem: &SliceProblem<'_>,
    settings: &SliceSettings,
    memory: &mut SliceMemory,
    rng: &mut ChaCha8Rng,
    on_restart: &mut dyn FnMut(usize, usize),
) -> Result<SliceOutcome, SolverError> {
    let order = problem.factor.krylov_order();
    let permuted_mass = permuted_diagonal_mass(problem.mass, order);
    let (mass, n) = krylov_mass(problem, permuted_mass.as_deref());
    let par = settings.parallelism;
    let block = settings.block_size.max(1);
    let wanted = problem.lower_needed + problem.upper_target;
    let max_basis = basis_limit(n, wanted, block, settings.max_basis)?;

    // Pairs locked so far in `(lower_bound, σ)` and in `[σ, upper_bound)`.
    let mut found = (0usize, 0usize);
    let mut solves = 0usize;

    if wanted == 0 {
        return Ok(SliceOutcome { columns: 0, solves });
    }
    let columns = max_basis + 3 * block;
    let (mut basis, mut locked, scratch) = memory.parts(n, columns, locked_columns(wanted, block));
    let start = random_orthonormal_block(n, block, &[], mass, rng, par)?;
    let mut krylov = KrylovSchur::start(basis.rb_mut(), start.as_ref());

    let ritz = |krylov: &KrylovSchur, found| {
        ritz_pairs(
            krylov.h.as_ref(),
            krylov.g.as_ref(),
            problem,
            settings,
            found,
        )
    };
    let restart = Restart {
        problem,
        mass,
        block,
        max_basis,
        par,
    };
    let mut restarted = false;
    for _restart in 0..settings.max_restarts {
        // ---- expansion ----
        let step = KrylovStep {
            factor: problem.factor,
            mass,
            locked: locked.view(),
            par,
        };
        // In the slice's last cycle, stop expanding as soon as the Ritz pairs complete it
        // instead of always filling the basis (on average half a cycle of solves saved).
        let check_completion = restarted && 2 * remaining(problem, found) <= wanted;
        let complete = |krylov: &KrylovSchur| {
            let pairs = ritz(krylov, found)?;
            Ok(found.0 + pairs.inside.0 >= problem.lower_needed
                && found.1 + pairs.inside.1 >= problem.upper_target)
        };
        solves += step.expansion_cycle(
            basis.rb_mut(),
            &mut krylov,
            (scratch, rng),
            max_basis,
            check_completion.then_some(&complete),
        )?;
        restarted = true;

        // ---- Rayleigh–Ritz ----
        let pairs = ritz(&krylov, found)?;
        let window = remaining(problem, found) + block;
        found.0 += pairs.inside.0;
        found.1 += pairs.inside.1;
        locked.append_ritz_vectors(basis.rb().subcols(0, krylov.mv), &pairs.y, &pairs.lock, par);
        on_restart(locked.columns, solves);
        check_lower_count(problem, found)?;
        if found.0 == problem.lower_needed && found.1 >= problem.upper_target {
            return finish_slice(problem.factor, mass, locked, scratch, order, solves);
        }

        restart.run(
            &mut krylov,
            basis.rb_mut(),
            pairs,
            window,
            found,
            locked.view(),
            rng,
        )?;
    }
    Err(not_converged(problem, settings, found))
}

/// The thick restart of a slice after a Rayleigh–Ritz, with what stays fixed while the slice
/// runs: its problem, `M` in the Krylov vectors' order, the block size, the largest expanded
/// basis and the parallelism of the products.
struct Restart<'a> {
    problem: &'a SliceProblem<'a>,
    mass: Mass<'a>,
    block: usize,
    max_basis: usize,
    par: Par,
}

impl Restart<'_> {
    /// Restarts `krylov` onto the best unconverged Ritz `pairs` (as many as `window`, the pairs
    /// still wanted plus a block, and at least half the basis, leaving room for `U` and one
    /// more block); where eigenvalues counted by inertia are still missing after the pairs
    /// `found` and no Ritz value stands for them, adds a block of fresh random directions,
    /// M-orthogonal to the `locked` vectors and the basis.
    #[allow(clippy::too_many_arguments)]
    fn run(
        &self,
        krylov: &mut KrylovSchur,
        mut basis: MatMut<'_, f64>,
        pairs: RitzPairs,
        window: usize,
        found: (usize, usize),
        locked: MatRef<'_, f64>,
        rng: &mut ChaCha8Rng,
    ) -> Result<(), SolverError> {
        let (problem, block, par) = (self.problem, self.block, self.par);
        let keep_target = window
            .max(self.max_basis / 2)
            .min(self.max_basis.saturating_sub(krylov.mu + block));
        let mut keep = pairs.keep;
        keep.truncate(keep_target);
        krylov.thick_restart(
            basis.rb_mut(),
            &pairs.theta,
            &pairs.y,
            &pairs.gy,
            &keep,
            par,
        );

        // Missing eigenvalues counted by inertia (below σ; above σ too when the upper end is
        // an exact count) without any Ritz approximation in the basis (e.g. a multiplicity
        // larger than the block size): bring in fresh random directions.
        let missing = remaining(problem, found);
        let newly_locked = pairs.inside.0 + pairs.inside.1;
        if missing > 0
            && newly_locked == 0
            && candidates_inside(problem, &pairs.theta, &keep) < missing
            && krylov.mu + block <= 3 * block
        {
            let current = basis.rb().subcols(0, krylov.mv + krylov.mu);
            let n = basis.nrows();
            let fresh =
                random_orthonormal_block(n, block, &[locked, current], self.mass, rng, par)?;
            krylov.append_unexpanded(basis.rb_mut(), fresh.as_ref());
        }
        Ok(())
    }
}

/// The largest expanded basis of a slice of dimension `n` that must lock `wanted` pairs with
/// blocks of `block` vectors: `max_basis`, less where `n` leaves no room for it (the basis,
/// the unexpanded blocks and the locked vectors must be linearly independent).
///
/// Errors: [`SolverError::NoConvergence`] when not even two blocks fit (the dense solver's
/// problem).
fn basis_limit(
    n: usize,
    wanted: usize,
    block: usize,
    max_basis: usize,
) -> Result<usize, SolverError> {
    let room = n.saturating_sub(wanted + 3 * block);
    let max_basis = max_basis.min(room);
    if max_basis < 2 * block {
        return Err(SolverError::NoConvergence {
            reason: format!(
                "problem too small for the Krylov basis (n = {n}); use the dense solver"
            ),
        });
    }
    Ok(max_basis)
}

/// Checks the pairs `found` below σ against the inertia count, which they must not exceed.
fn check_lower_count(problem: &SliceProblem<'_>, found: (usize, usize)) -> Result<(), SolverError> {
    if found.0 > problem.lower_needed {
        return Err(SolverError::NoConvergence {
            reason: format!(
                "inertia mismatch at shift {:e}: found {} new eigenvalues below it, inertia allows {}",
                problem.sigma, found.0, problem.lower_needed
            ),
        });
    }
    Ok(())
}

/// The error of a slice that did not lock all its pairs within its restarts.
fn not_converged(
    problem: &SliceProblem<'_>,
    settings: &SliceSettings,
    found: (usize, usize),
) -> SolverError {
    SolverError::NoConvergence {
        reason: format!(
            "slice at shift {:e} did not converge in {} restarts (locked {} of {} eigenpairs below the shift, {} of {} above)",
            problem.sigma,
            settings.max_restarts,
            found.0,
            problem.lower_needed,
            found.1,
            problem.upper_target
        ),
    }
}

/// Pairs still missing after `found` `(below σ, above σ)` were locked: all below σ that the
/// inertia counts, and the rest of the upper target.
fn remaining(problem: &SliceProblem<'_>, (lower_found, upper_found): (usize, usize)) -> usize {
    problem.lower_needed - lower_found + problem.upper_target.saturating_sub(upper_found)
}

/// How many of the kept Ritz values `theta[keep]` stand for eigenvalues `σ + 1/θ` strictly
/// inside the interval.
fn candidates_inside(problem: &SliceProblem<'_>, theta: &[f64], keep: &[usize]) -> usize {
    keep.iter()
        .filter(|&&i| {
            let lambda = problem.sigma + 1.0 / theta[i];
            lambda < problem.upper_bound && lambda > problem.lower_bound
        })
        .count()
}

/// A diagonal `M` permuted into the factorization's elimination order `order` (`None`: no
/// permutation, or a sparse `M`, which the factorization permutes itself).
fn permuted_diagonal_mass(mass: Mass<'_>, order: Option<&[usize]>) -> Option<Vec<f64>> {
    match mass {
        Mass::Diagonal(mass) => order.map(|order| order.iter().map(|&row| mass[row]).collect()),
        Mass::Sparse(_) => None,
    }
}

/// `M` in the order of the Krylov vectors (the diagonal permuted by the caller, see
/// [`permuted_diagonal_mass`]; a sparse one `P M Pᵀ` from the factorization when it has one)
/// and the dimension `n` of the vectors.
fn krylov_mass<'a>(problem: &SliceProblem<'a>, permuted: Option<&'a [f64]>) -> (Mass<'a>, usize) {
    match (problem.mass, problem.factor.krylov_mass()) {
        (Mass::Diagonal(mass), _) => {
            let mass = permuted.unwrap_or(mass);
            (Mass::Diagonal(mass), mass.len())
        }
        (Mass::Sparse(m), krylov) => {
            let m = krylov.unwrap_or(m);
            (Mass::Sparse(m), m.nrows())
        }
    }
}

/// The slice is complete: one inverse-iteration step on the `locked` vectors (its solves
/// counted in the returned `solves`, added to the `solves` so far), which are then put in input
/// order.
fn finish_slice(
    factor: &ShiftFactor,
    mass: Mass<'_>,
    locked: ColumnStore<'_>,
    scratch: &mut OperatorScratch,
    order: Option<&[usize]>,
    solves: usize,
) -> Result<SliceOutcome, SolverError> {
    let (n, columns) = (locked.n, locked.columns);
    let mut vectors =
        MatMut::from_column_major_slice_mut(&mut locked.values[..n * columns], n, columns);
    inverse_iteration_step(factor, mass, vectors.rb_mut(), scratch)?;
    let solves = solves + columns * factor.refined_solve_cost();
    put_in_input_order(vectors, order);
    Ok(SliceOutcome { columns, solves })
}

/// The Krylov–Schur decomposition `OP V = V H + U G` in the first columns of the basis: `V`
/// the first `mv` (expanded), `U` the next `mu` (unexpanded); `H` is `mv × mv` (symmetric),
/// `G` is `mu × mv`.
struct KrylovSchur {
    h: Mat<f64>,
    g: Mat<f64>,
    mv: usize,
    mu: usize,
}

/// Whether the Ritz pairs of a decomposition complete the slice.
type CompletionCheck<'c> = dyn Fn(&KrylovSchur) -> Result<bool, SolverError> + 'c;

/// What one expansion step works with: the factorization, `M` (in the Krylov vectors' order),
/// the locked vectors (`n × locked`) and the parallelism of the products.
struct KrylovStep<'a> {
    factor: &'a ShiftFactor,
    mass: Mass<'a>,
    locked: MatRef<'a, f64>,
    par: Par,
}

impl KrylovStep<'_> {
    /// One expansion cycle: expands `krylov` block by block ([`Self::expand`]) while the basis
    /// has room (`mv + mu ≤ max_basis`); with `complete`, every [`COMPLETION_CHECK_BLOCKS`]
    /// blocks it asks whether the Ritz pairs already complete the slice and stops if so.
    /// Returns the number of solves.
    fn expansion_cycle(
        &self,
        mut basis: MatMut<'_, f64>,
        krylov: &mut KrylovSchur,
        (scratch, rng): (&mut OperatorScratch, &mut ChaCha8Rng),
        max_basis: usize,
        complete: Option<&CompletionCheck<'_>>,
    ) -> Result<usize, SolverError> {
        let mut solves = 0;
        let mut steps_since_check = 0usize;
        while krylov.mv + krylov.mu <= max_basis {
            solves += krylov.mu;
            self.expand(basis.rb_mut(), krylov, scratch, rng)?;
            steps_since_check += 1;
            if let Some(complete) = complete {
                if steps_since_check >= COMPLETION_CHECK_BLOCKS {
                    steps_since_check = 0;
                    if complete(krylov)? {
                        break;
                    }
                }
            }
        }
        Ok(solves)
    }

    /// Expands `krylov` by one block: `Z = OP U` (one blocked solve of `mu` columns), formed in
    /// place in the basis columns right after `U`, orthonormalised against the locked vectors
    /// and `[V, U]`; `U` joins `V` and the new block becomes `U` (`H` and `G` bordered).
    fn expand(
        &self,
        mut basis: MatMut<'_, f64>,
        krylov: &mut KrylovSchur,
        scratch: &mut OperatorScratch,
        rng: &mut ChaCha8Rng,
    ) -> Result<(), SolverError> {
        let (mv, mu) = (krylov.mv, krylov.mu);
        let (mass, par) = (self.mass, self.par);
        let m_new = mv + mu;
        let (current, mut free) = basis.rb_mut().split_at_col_mut(m_new);
        let current = current.into_const();
        let mut z = free.rb_mut().subcols_mut(0, mu);
        let applied = apply_operator(
            self.factor,
            mass,
            current.subcols(mv, mu),
            z.rb_mut(),
            scratch,
            par,
        );
        let bases = [self.locked, current];
        // OP U lies almost entirely in span(V) (that is the Krylov relation), while its
        // components along the deflated and locked eigenvectors are tiny in exact
        // arithmetic. So the big cancellation is against V alone: one classical pass against
        // V first, then the full (DGKS-checked) passes against everything, which mostly stop
        // after one pass. Two full passes over [D, L, V] cost twice the dominant term.
        // Coefficients along V are known from the Krylov relation (OP V = V H + U G, OP
        // M-self-adjoint, so Vᵀ M OP U = Gᵀ); only the block's own ones are computed.
        let g = &krylov.g;
        let mut first_pass = Mat::<f64>::zeros(m_new, mu);
        for j in 0..mu {
            for i in 0..mv {
                first_pass[(i, j)] = g[(j, i)];
            }
        }
        first_pass
            .as_mut()
            .subrows_mut(mv, mu)
            .copy_from(&applied.own);
        let (mut coefficients, gram) =
            project_out_after_known(z.rb_mut(), current, first_pass.as_ref(), &bases, mass, par);
        coefficients[1] += &first_pass;
        let c = &coefficients[1];
        let next = orthonormalize_block(z, gram, &applied.norms, &bases, mass, rng, par)?;
        let mut h_new = Mat::<f64>::zeros(m_new, m_new);
        h_new
            .as_mut()
            .submatrix_mut(0, 0, mv, mv)
            .copy_from(&krylov.h);
        for j in 0..mu {
            for i in 0..mv {
                let value = 0.5 * (c[(i, j)] + g[(j, i)]);
                h_new[(i, mv + j)] = value;
                h_new[(mv + j, i)] = value;
            }
            for i in 0..mu {
                h_new[(mv + i, mv + j)] = 0.5 * (c[(mv + i, j)] + c[(mv + j, i)]);
            }
        }
        let mut g_new = Mat::<f64>::zeros(mu, m_new);
        g_new.as_mut().submatrix_mut(0, mv, mu, mu).copy_from(&next);
        krylov.h = h_new;
        krylov.g = g_new;
        krylov.mv = m_new;
        Ok(())
    }
}

impl KrylovSchur {
    /// The empty decomposition (`V` empty) whose `U` is the M-orthonormal block `start`, put in
    /// the first columns of the basis.
    fn start(mut basis: MatMut<'_, f64>, start: MatRef<'_, f64>) -> Self {
        let block = start.ncols();
        basis.rb_mut().subcols_mut(0, block).copy_from(start);
        Self {
            h: Mat::<f64>::zeros(0, 0),
            g: Mat::<f64>::zeros(block, 0),
            mv: 0,
            mu: block,
        }
    }

    /// Thick restart onto the Ritz pairs `keep` (indices into `theta`, the Ritz values, and the
    /// columns of `y`, the Ritz vectors of `H`, and of `gy = G Y`): `V ← V Y_keep` in place,
    /// `U` moved right after it, `H ← Θ_keep`, `G ← (G Y)_keep`.
    fn thick_restart(
        &mut self,
        mut basis: MatMut<'_, f64>,
        theta: &[f64],
        y: &Mat<f64>,
        gy: &Mat<f64>,
        keep: &[usize],
        par: Par,
    ) {
        let (mv, mu) = (self.mv, self.mu);
        let p = keep.len();
        let y_keep = Mat::from_fn(mv, p, |i, j| y[(i, keep[j])]);
        tall_times_in_place(basis.rb_mut().subcols_mut(0, mv), y_keep.as_ref(), par);
        // `U` moved left column by column (`p ≤ mv`, so each column lands on one already moved
        // or on `V`'s): no copy of it, `n × mu` fresh values per restart otherwise.
        if p < mv {
            for j in 0..mu {
                let (left, right) = basis.rb_mut().split_at_col_mut(mv + j);
                left.col_mut(p + j).copy_from(right.col(0));
            }
        }
        self.h = Mat::from_fn(p, p, |i, j| if i == j { theta[keep[i]] } else { 0.0 });
        self.g = Mat::from_fn(mu, p, |i, j| gy[(i, keep[j])]);
        self.mv = p;
    }

    /// Appends the M-orthonormal block `fresh` (orthogonal to everything in the basis) to `U`
    /// (its rows of `G` are zero).
    fn append_unexpanded(&mut self, mut basis: MatMut<'_, f64>, fresh: MatRef<'_, f64>) {
        let (mv, mu, block) = (self.mv, self.mu, fresh.ncols());
        basis.rb_mut().subcols_mut(mv + mu, block).copy_from(fresh);
        let mut g_new = Mat::<f64>::zeros(mu + block, mv);
        g_new.as_mut().subrows_mut(0, mu).copy_from(&self.g);
        self.g = g_new;
        self.mu += block;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eigen::shift_factor::KrylovFrame;
    use crate::ordering::FillOrdering;
    use crate::sparse_ldlt::SparseLdlt;
    use faer::sparse::{SparseColMat, Triplet};

    /// `A − σM` for the weighted 5-point Laplacian `A` of a `side × side` grid and a diagonal
    /// `M`: (upper triangle, dense full matrix, diagonal of `M`).
    fn shifted_grid(side: usize, sigma: f64) -> (SparseColMat<usize, f64>, Mat<f64>, Vec<f64>) {
        let n = side * side;
        let mass: Vec<f64> = (0..n).map(|i| 0.5 + (i % 3) as f64 / 4.0).collect();
        let mut dense = Mat::from_fn(n, n, |i, j| if i == j { -sigma * mass[i] } else { 0.0 });
        for i in 0..side {
            for j in 0..side {
                for (a, b) in [
                    (i * side + j, (i + 1) * side + j),
                    (i * side + j, i * side + j + 1),
                ] {
                    if (b == a + side && i + 1 < side) || (b == a + 1 && j + 1 < side) {
                        let w = 1.0 + ((a * 7 + b * 3) % 5) as f64 / 4.0;
                        dense[(a, b)] -= w;
                        dense[(b, a)] -= w;
                        dense[(a, a)] += w;
                        dense[(b, b)] += w;
                    }
                }
            }
        }
        let triplets: Vec<Triplet<usize, usize, f64>> = (0..n)
            .flat_map(|j| (0..=j).map(move |i| (i, j)))
            .filter(|&(i, j)| dense[(i, j)] != 0.0)
            .map(|(i, j)| Triplet::new(i, j, dense[(i, j)]))
            .collect();
        let upper = SparseColMat::try_new_from_triplets(n, n, &triplets).expect("valid triplets");
        (upper, dense, mass)
    }

    /// `OP U` on packed rows in elimination order solves `(A − σM) Z = M U`, and the M-norms and
    /// `Uᵀ M Z` measured while unpacking are the direct ones, for a block of one chunk and one
    /// of two; the inverse-iteration step returns M-normalised `OP X`.
    #[test]
    fn operator_on_packed_rows_solves_the_shifted_system() {
        let (upper, dense, mass) = shifted_grid(23, 0.9);
        let n = mass.len();
        let ldlt = SparseLdlt::with_ordering(upper.as_ref(), FillOrdering::NestedDissection)
            .expect("factors");
        let frame = KrylovFrame::standard(&ldlt, None).expect("a frame");
        let factor = ShiftFactor::new(ldlt, 0.9, std::sync::Arc::new(frame));
        let order = factor.krylov_order().expect("an ordering").to_vec();
        let permuted_values: Vec<f64> = order.iter().map(|&row| mass[row]).collect();
        let permuted_mass = Mass::Diagonal(&permuted_values);
        let mut scratch = OperatorScratch::new(n);
        for r in [5, 11] {
            let u = Mat::from_fn(n, r, |i, j| ((i * 7 + j * 13) % 23) as f64 / 11.0 - 1.0);
            let mut z = Mat::<f64>::zeros(n, r);
            let applied = apply_operator(
                &factor,
                permuted_mass,
                u.as_ref(),
                z.as_mut(),
                &mut scratch,
                Par::Seq,
            );
            let input = |x: &Mat<f64>| {
                Mat::from_fn(n, r, |i, j| {
                    x[(
                        order.iter().position(|&o| o == i).expect("a permutation"),
                        j,
                    )]
                })
            };
            let (u_input, z_input) = (input(&u), input(&z));
            let mu = Mat::from_fn(n, r, |i, j| mass[i] * u_input[(i, j)]);
            let residual = &dense * &z_input - &mu;
            assert!(residual.norm_max() <= 1e-10 * mu.norm_max(), "r = {r}");
            let own = mass_inner(u.as_ref(), permuted_mass, z.as_ref(), Par::Seq);
            assert!(
                (&applied.own - &own).norm_max() <= 1e-12 * own.norm_max(),
                "r = {r}"
            );
            for (j, norm) in applied.norms.iter().enumerate() {
                let direct = (0..n)
                    .map(|i| permuted_values[i] * z[(i, j)] * z[(i, j)])
                    .sum::<f64>()
                    .sqrt();
                assert!((norm - direct).abs() <= 1e-12 * direct, "r = {r}");
            }
            let mut x = u.clone();
            inverse_iteration_step(&factor, permuted_mass, x.as_mut(), &mut scratch)
                .expect("no column vanishes");
            for (j, norm) in applied.norms.iter().enumerate() {
                for i in 0..n {
                    assert!((x[(i, j)] - z[(i, j)] / norm).abs() <= 1e-12 * z.norm_max() / norm);
                }
            }
        }
    }

    /// With a sparse mass (`P M Pᵀ` of the frame, the Krylov order): `OP U` solves
    /// `(A − σM) Z = M U`, and the M-norms and `Uᵀ M Z` of the unpacking pass are the dense ones.
    #[test]
    fn operator_with_a_sparse_mass_solves_the_shifted_system() {
        let side = 19;
        let (a_upper, a_dense, _) = shifted_grid(side, 0.0);
        let n = side * side;
        let sigma = 0.7;
        let mut m_dense = Mat::from_fn(n, n, |i, j| {
            if i == j {
                0.5 + (i % 3) as f64 / 4.0
            } else {
                0.0
            }
        });
        for a in 0..n {
            for b in [a + 1, a + side] {
                if b < n && (b != a + 1 || (a + 1) % side != 0) {
                    m_dense[(a, b)] = 0.1;
                    m_dense[(b, a)] = 0.1;
                }
            }
        }
        let triplets = |upper_only: bool| -> Vec<Triplet<usize, usize, f64>> {
            (0..n)
                .flat_map(|j| (0..n).map(move |i| (i, j)))
                .filter(|&(i, j)| m_dense[(i, j)] != 0.0 && (!upper_only || i <= j))
                .map(|(i, j)| Triplet::new(i, j, m_dense[(i, j)]))
                .collect()
        };
        let m_upper = SparseColMat::try_new_from_triplets(n, n, &triplets(true)).expect("valid");
        let m_full = SparseColMat::try_new_from_triplets(n, n, &triplets(false)).expect("valid");
        let shifted = crate::convert::ShiftedPattern::new(&a_upper, &m_upper)
            .expect("same size")
            .at(sigma);
        let ldlt = SparseLdlt::with_ordering(shifted.as_ref(), FillOrdering::NestedDissection)
            .expect("factors");
        let frame = KrylovFrame::standard(&ldlt, Some(m_full.as_ref())).expect("a frame");
        let factor = ShiftFactor::new(ldlt, sigma, std::sync::Arc::new(frame));
        let order = factor.krylov_order().expect("an ordering").to_vec();
        let mass = Mass::Sparse(factor.krylov_mass().expect("a sparse mass"));
        let permuted_m = Mat::from_fn(n, n, |i, j| m_dense[(order[i], order[j])]);
        let shifted_dense = &a_dense - &m_dense * faer::Scale(sigma);
        let mut scratch = OperatorScratch::new(n);
        for r in [6, 10] {
            let u = Mat::from_fn(n, r, |i, j| ((i * 5 + j * 11) % 19) as f64 / 9.0 - 1.0);
            let mut z = Mat::<f64>::zeros(n, r);
            let applied = apply_operator(
                &factor,
                mass,
                u.as_ref(),
                z.as_mut(),
                &mut scratch,
                Par::Seq,
            );
            let mut u_input = Mat::<f64>::zeros(n, r);
            let mut z_input = Mat::<f64>::zeros(n, r);
            for (i, &row) in order.iter().enumerate() {
                for j in 0..r {
                    u_input[(row, j)] = u[(i, j)];
                    z_input[(row, j)] = z[(i, j)];
                }
            }
            let mu = &m_dense * &u_input;
            let residual = &shifted_dense * &z_input - &mu;
            assert!(residual.norm_max() <= 1e-10 * mu.norm_max(), "r = {r}");
            let own = u.transpose() * &permuted_m * &z;
            assert!(
                (&applied.own - &own).norm_max() <= 1e-12 * own.norm_max(),
                "r = {r}"
            );
            let direct = z.transpose() * &permuted_m * &z;
            for (j, norm) in applied.norms.iter().enumerate() {
                let expected = direct[(j, j)].sqrt();
                assert!((norm - expected).abs() <= 1e-12 * expected, "r = {r}");
            }
        }
    }

    /// Memory expected for a pencil's widest slice is reserved for it at the first (narrower)
    /// slice, so that a wider one reuses it; a slice of a much smaller pencil shrinks it, and
    /// without an expectation only the asked-for room is reserved.
    #[test]
    fn slice_memory_is_reserved_for_the_widest_expected_slice() {
        let (n, block) = (1000, 8);
        let mut memory = SliceMemory::default();
        memory.expect(n, 40, block);
        memory.fit(n, basis_columns(30, block), locked_columns(30, block));
        let reserved = memory.basis.capacity();
        assert!(reserved >= n * basis_columns(40, block));
        let start = memory.basis.as_ptr();
        memory.fit(n, basis_columns(40, block), locked_columns(40, block));
        assert_eq!(
            memory.basis.as_ptr(),
            start,
            "the wider slice reuses the memory"
        );
        assert_eq!(memory.basis.capacity(), reserved);

        memory.expect(n / 4, 40, block);
        memory.fit(n / 4, basis_columns(40, block), locked_columns(40, block));
        assert!(memory.basis.capacity() <= 2 * (n / 4) * basis_columns(40, block));

        let mut unexpected = SliceMemory::default();
        unexpected.fit(n, basis_columns(30, block), locked_columns(30, block));
        assert!(unexpected.basis.capacity() < n * basis_columns(40, block));
    }
}
