//! Options, progress reports and results of [`crate::lowest_eigenpairs`].

use faer::{Mat, Par};
use std::fmt;

/// Progress of [`crate::lowest_eigenpairs`], reported after every restart of every slice.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EigenProgress {
    /// Eigenpairs found so far (confirmed by an inertia count or still tentative).
    pub found: usize,
    /// Eigenpairs whose completeness has been confirmed by an inertia count.
    pub confirmed: usize,
    /// Number of eigenpairs requested.
    pub wanted: usize,
    /// Shifts (spectrum slices) used so far.
    pub slices: usize,
    /// Sparse factorizations computed so far.
    pub factorizations: usize,
    /// Single-vector solves with a factorization so far (a block of `r` counts `r`).
    pub solves: usize,
}

/// Tuning knobs of [`crate::lowest_eigenpairs`]. `Default` gives the recommended values.
#[derive(Clone, Copy)]
pub struct EigenOptions<'a> {
    /// Seed of the random start blocks; equal seeds give identical results.
    pub seed: u64,
    /// Convergence tolerance: a Ritz pair `(θ, u)` of the shift-inverted operator
    /// `(A − σM)⁻¹M` is accepted when `‖OP u − θ u‖_M ≤ tolerance · |θ|`. Default `1e-12`.
    pub tolerance: f64,
    /// Number of vectors per Krylov block (and per blocked solve). Default 8.
    pub block_size: usize,
    /// Target number of new eigenpairs per spectrum slice of the sequential driver
    /// (`concurrent_slices = 0`; one factorization each). Default 128.
    pub slice_size: usize,
    /// Maximum number of restarts per slice before giving up. Default 1000.
    pub max_restarts: usize,
    /// Problems with `n ≤ dense_threshold` (or `3k ≥ n`) use the dense solver. Default 400.
    pub dense_threshold: usize,
    /// Threads for the dense block operations (Gram–Schmidt, restarts, Rayleigh–Ritz), for the
    /// blocked solves and for the factorizations. The dense products with the tall Krylov bases
    /// are split by rows (each thread streams its own rows of the basis) and a block of
    /// right-hand sides by columns (each thread runs a sequential supernodal solve on its
    /// columns: faer's parallel solve synchronises per supernode, which costs more than it gains
    /// on surface meshes). Products with fewer than 8192 rows run on one thread. Results agree with a
    /// single-threaded run to rounding (not bitwise: partial sums are added in another order).
    /// Default `Par::rayon(0)` (all of rayon's threads): 500 cotan eigenpairs of bunny-closed
    /// took 8.9 s on two threads against 13.0 s on one (issue 4).
    pub parallelism: Par,
    /// Number of spectrum intervals solved concurrently, each on its own thread with its own
    /// factorization. `0` selects the sequential driver (shift after shift, each placed from
    /// what the previous one found); `≥ 1` cuts the spectrum into intervals with exact
    /// eigenvalue counts (inertia) first and solves them independently on that many threads
    /// (the result is the same for every thread count). Default 0: the interval driver is 1.7–1.8×
    /// faster on bunny-closed (k = 500, quiet machine) but was seen to spend many minutes in one
    /// interval of bumpy-torus-x4's Crouzeix–Raviart problem (issue 4), so it is opt-in for now.
    pub concurrent_slices: usize,
    /// Target number of eigenpairs per interval of the independent-interval driver
    /// (`concurrent_slices ≥ 1`; two factorizations each, one at its midpoint and one at its
    /// upper end). Smaller intervals mean smaller Krylov bases (dense work grows with the
    /// square of the basis) but more factorizations and more work at interval ends. Default 96.
    pub interval_size: usize,
    /// Called with a progress report after every restart; `None` for silence.
    pub progress: Option<&'a dyn Fn(&EigenProgress)>,
}

impl Default for EigenOptions<'_> {
    fn default() -> Self {
        Self {
            seed: 0x7466_7665_6967_656e,
            tolerance: 1e-12,
            block_size: 8,
            slice_size: 128,
            max_restarts: 1000,
            dense_threshold: 400,
            parallelism: Par::rayon(0),
            concurrent_slices: 0,
            interval_size: 96,
            progress: None,
        }
    }
}

impl fmt::Debug for EigenOptions<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("EigenOptions")
            .field("seed", &self.seed)
            .field("tolerance", &self.tolerance)
            .field("block_size", &self.block_size)
            .field("slice_size", &self.slice_size)
            .field("max_restarts", &self.max_restarts)
            .field("dense_threshold", &self.dense_threshold)
            .field("parallelism", &self.parallelism)
            .field("concurrent_slices", &self.concurrent_slices)
            .field("interval_size", &self.interval_size)
            .field("progress", &self.progress.map(|_| "callback"))
            .finish()
    }
}

/// Lowest eigenpairs of `A x = λ M x`.
#[derive(Debug, Clone)]
pub struct Eigenpairs {
    /// Eigenvalues in ascending order (length `k`).
    pub values: Vec<f64>,
    /// `n × k` eigenvectors, column `j` for `values[j]`, M-orthonormal: `Xᵀ M X = I`.
    pub vectors: Mat<f64>,
    /// Relative residuals `‖A x_j − λ_j M x_j‖₂ / (‖A‖₁ ‖x_j‖₂)`, where `‖A‖₁` is the
    /// maximum absolute column sum (an upper bound of `‖A‖₂`).
    pub residuals: Vec<f64>,
    /// Sparse factorizations computed (one per shift, plus retries).
    pub factorizations: usize,
    /// Single-vector solves (a block solve of `r` right-hand sides counts `r`).
    pub solves: usize,
}
