//! Options, progress reports and results of [`crate::lowest_eigenpairs`] and
//! [`crate::lowest_eigenpairs_of`].

use super::pencil::Pencil;
use super::statistics::SolverStatistics;
use faer::{Mat, MatRef, Par};
use std::fmt;

/// Progress of one request of [`crate::lowest_eigenpairs_of`], reported after every restart of
/// every interval and when an interval is done.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EigenProgress {
    /// Index of the request.
    pub request: usize,
    /// Eigenpairs found so far (converged in an interval still running, or in a finished one).
    pub found: usize,
    /// Eigenpairs of finished intervals (complete by their inertia counts).
    pub confirmed: usize,
    /// Number of eigenpairs requested.
    pub wanted: usize,
    /// Sparse factorizations of the request's pencil so far (counting included).
    pub factorizations: usize,
    /// Single-vector solves with its factorizations so far (a block of `r` counts `r`).
    pub solves: usize,
}

/// Tuning knobs of the eigensolver. `Default` gives the recommended values.
#[derive(Clone, Copy)]
pub struct EigenOptions<'a> {
    /// Seed of the random start blocks of [`crate::lowest_eigenpairs`] (requests of
    /// [`crate::lowest_eigenpairs_of`] carry their own); equal seeds give identical results.
    pub seed: u64,
    /// Convergence tolerance: a Ritz pair `(θ, u)` of the shift-inverted operator
    /// `(A − σM)⁻¹M` is accepted when `‖OP u − θ u‖_M ≤ tolerance · |θ|`. Default `1e-10`: the
    /// eigenvalues come from a Rayleigh–Ritz against `A`, whose error is quadratic in the
    /// vectors' (on kitten, eight and hand the spectrum agrees with a run at `1e-12` to
    /// `5·10⁻¹⁴` relative), and the inverse-iteration step every locked vector takes brings the
    /// eigenfield residuals below `1e-8`; `1e-12` cost 7 % more solves for nothing measurable.
    pub tolerance: f64,
    /// Number of vectors per Krylov block (and per blocked solve). Default 8.
    pub block_size: usize,
    /// Restarts of one interval before it is split at its shift and its halves are solved
    /// with new shifts (at most three times). Default 25; an interval of 96 eigenpairs
    /// typically needs 2–5 (bumpy-torus-x4's Crouzeix–Raviart problem, k = 1000: 420–560
    /// solves of blocks of 8 per interval).
    pub max_restarts: usize,
    /// Problems with `n ≤ dense_threshold` (or `3k ≥ n`) use the dense solver. Default 400.
    pub dense_threshold: usize,
    /// Threads of the dense products with the tall Krylov bases inside one interval (split by
    /// rows; products with fewer than 8192 rows run on one thread). Results agree with a
    /// single-threaded run to rounding (not bitwise: partial sums are added in another order).
    /// Default `Par::rayon(0)` (all of rayon's threads).
    pub parallelism: Par,
    /// Intervals solved at the same time, each a task of rayon's pool with its own factorization
    /// and sequential solves (the result is the same for every thread count). Default: the
    /// number of rayon's threads.
    pub threads: usize,
    /// Target number of eigenpairs per interval (one factorization at its midpoint, one at its
    /// upper end). Smaller intervals mean smaller Krylov bases (dense work grows with the square
    /// of the basis) but more factorizations and more work at interval ends. Default 96.
    pub interval_size: usize,
    /// Bytes the work memory of the intervals solved at the same time (their Krylov bases,
    /// locked vectors and operator buffers, `n` rows each) may take together: a job waits
    /// until its slice fits next to the running ones, and where one slice alone would not
    /// fit, the pencil's intervals are made smaller (see `slice_memory.rs`). `None` (the
    /// default): [`crate::default_slice_memory`], a sixth of the physical memory unless the
    /// process set another (the command line: `TVF_SLICE_MEMORY`, e.g. `4G`). Binds only on large meshes (a slice of 96 pairs of a million-face
    /// co-potential pencil is 4.4 GB); the result does not depend on it unless it lowers the
    /// interval size. With [`Self::finished`] it also decides where the eigenvectors wait to be
    /// handed on: in memory when all of them take at most a quarter of it, else in a temporary
    /// file ([`crate::streamed_eigenvectors_in_memory`]).
    pub slice_memory: Option<usize>,
    /// Eigenpairs whose relative eigenfield residual `√(sᵀ A s / λ) / λ`,
    /// `s = M⁻¹(A x − λ M x)` (the residual of the Hodge–Laplacian eigenfield `D x/√λ` when
    /// `A = Dᵀ W D`), exceeds this and ten times its rounding floor (see
    /// [`Eigenpairs::field_residual_floors`]) get one inverse-iteration step with their interval's
    /// factorization (more steps, up to three, while a step halves the residual). Default
    /// `1e-9`, a tenth of what the basis tests demand; residuals of a few `1e-9` can be the
    /// rounding floor of the vectors themselves. `f64::INFINITY` switches refinement off.
    pub refinement_target: f64,
    /// Called on the calling thread with a progress report after every restart; `None` for
    /// silence.
    pub progress: Option<&'a dyn Fn(&EigenProgress)>,
    /// Where eigenvectors go as soon as they are final, while other intervals are still being
    /// solved, so that they are never all in memory: `None` (the default) keeps them all in
    /// [`Eigenpairs::vectors`]. With a sink, every request's first `count` eigenvectors are
    /// handed to it once each, in ascending column order per request (called on the calling
    /// thread), their memory is given back right after, and [`Eigenpairs::vectors`] has no
    /// columns (`n × 0`); eigenvalues, residuals and statistics are returned as without one,
    /// and the vectors handed over are bit for bit those the result would hold. An error of the
    /// sink stops the computation with [`crate::SolverError::Stopped`].
    pub finished: Option<&'a EigenvectorSink<'a>>,
}

/// What [`EigenOptions::finished`] calls with each batch of final eigenvectors; an error
/// stops the computation.
pub type EigenvectorSink<'a> = dyn Fn(&FinishedEigenvectors<'_>) -> Result<(), String> + 'a;

/// Final eigenvectors handed to [`EigenOptions::finished`]: columns
/// `first..first + values.len()` of request `request`'s result (kernel included).
#[derive(Debug, Clone, Copy)]
pub struct FinishedEigenvectors<'v> {
    /// Index of the request.
    pub request: usize,
    /// Column of the first of them in the request's result.
    pub first: usize,
    /// Their eigenvalues, ascending.
    pub values: &'v [f64],
    /// The eigenvectors, `n × values.len()`, `M`-orthonormal.
    pub vectors: MatRef<'v, f64>,
}

impl Default for EigenOptions<'_> {
    fn default() -> Self {
        Self {
            seed: 0x7466_7665_6967_656e,
            tolerance: 1e-10,
            block_size: 8,
            max_restarts: 25,
            dense_threshold: 400,
            parallelism: Par::rayon(0),
            threads: rayon::current_num_threads(),
            interval_size: 96,
            slice_memory: None,
            refinement_target: 1e-9,
            progress: None,
            finished: None,
        }
    }
}

impl fmt::Debug for EigenOptions<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("EigenOptions")
            .field("seed", &self.seed)
            .field("tolerance", &self.tolerance)
            .field("block_size", &self.block_size)
            .field("max_restarts", &self.max_restarts)
            .field("dense_threshold", &self.dense_threshold)
            .field("parallelism", &self.parallelism)
            .field("threads", &self.threads)
            .field("interval_size", &self.interval_size)
            .field("slice_memory", &self.slice_memory)
            .field("refinement_target", &self.refinement_target)
            .field("progress", &self.progress.map(|_| "callback"))
            .field("finished", &self.finished.map(|_| "sink"))
            .finish()
    }
}

/// Lowest eigenpairs of `A x = λ M x`.
#[derive(Debug, Clone)]
pub struct Eigenpairs {
    /// Eigenvalues in ascending order (length `k`).
    pub values: Vec<f64>,
    /// `n × k` eigenvectors, column `j` for `values[j]`, M-orthonormal: `Xᵀ M X = I` (for a
    /// mixed pencil the `n2 × k` vectors ψ, N-orthonormal); `n × 0` when they went to
    /// [`EigenOptions::finished`] instead.
    pub vectors: Mat<f64>,
    /// Relative residuals `‖A x_j − λ_j M x_j‖₂ / (‖A‖ ‖x_j‖₂)`. For a pencil with a stored `A`
    /// (diagonal or sparse mass) `‖A‖ = ‖A‖₁`, the maximum absolute column sum (an upper bound
    /// of `‖A‖₂`); for a mixed pencil (`A = d1 W⁻¹ d1ᵀ`, not stored) `‖A‖` is an estimate of
    /// `‖A‖₂` by block power iteration (see [`Pencil::mixed`]).
    pub residuals: Vec<f64>,
    /// Relative eigenfield residuals (see [`EigenOptions::refinement_target`]); 0 for the kernel.
    pub field_residuals: Vec<f64>,
    /// The rounding floor of each field residual: what the rounding of `A x` alone makes it
    /// (on meshes with slivers it can be far above the target; such pairs are not refined).
    pub field_residual_floors: Vec<f64>,
    /// Factorizations and solves of the pencil by phase (counts made before the call
    /// included); from [`crate::lowest_eigenpairs`] also the wall-clock and processor seconds of
    /// each phase.
    pub statistics: SolverStatistics,
}

impl Eigenpairs {
    /// The pairs of `pencil` with their residuals (see the fields).
    pub(crate) fn new(
        pencil: &Pencil<'_>,
        values: Vec<f64>,
        vectors: Mat<f64>,
        residuals: Vec<f64>,
        field_residuals: Vec<f64>,
        field_residual_floors: Vec<f64>,
    ) -> Self {
        Self {
            values,
            vectors,
            residuals,
            field_residuals,
            field_residual_floors,
            statistics: pencil.statistics(),
        }
    }
}
