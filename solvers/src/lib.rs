//! # tvf-solvers
//!
//! Sparse Cholesky, generalized symmetric eigensolvers and dense updates (knows matrices, not meshes).
//!
//! - [`SparseCholesky`]: supernodal sparse Cholesky (faer) with symbolic reuse and blocked solves.
//! - [`SparseLdlt`]: the underlying `LDLᵀ` factorization of indefinite shifted matrices, with
//!   [`Inertia`] (Sylvester's law) for eigenvalue counting.
//! - [`lowest_eigenpairs`], [`lowest_eigenpairs_of`]: lowest eigenpairs of one or several
//!   pencils `A x = λ M x` (spectrum intervals with exact inertia counts, solved concurrently by
//!   shift-and-invert block Krylov–Schur, refined where the residual misses the target).
//! - [`Pencil`]: a pencil and its factorizations (each shift factored once, shared by counting,
//!   solving and refinement), [`Pencil::count_below`] counts eigenvalues below a threshold,
//!   [`Pencil::spectrum_upper_bound`] bounds the spectrum; [`SolverStatistics`] reports
//!   factorizations, solves and time per phase. Three kinds of pencils:
//!   - diagonal mass ([`Pencil::new`]): `A` sparse, `M` a positive diagonal (lumped masses);
//!   - sparse mass ([`Pencil::with_mass`] with [`MassMatrix::Sparse`]): `M` sparse SPD
//!     (consistent Galerkin masses); shifts factor `A − σM` on the union pattern, `M⁻¹` is a
//!     sparse Cholesky factorization of `M`;
//!   - mixed ([`Pencil::mixed`]): `d1 W⁻¹ d1ᵀ ψ = μ N ψ` with `W` sparse SPD (e.g. the Whitney
//!     1-form mass) and `N` diagonal or sparse SPD; the dense `A` is never formed: shifts factor
//!     the saddle matrix `[[−W, d1ᵀ], [d1, −σN]]`, whose negative pivots less `n1` count the
//!     eigenvalues below σ, and `A x` goes through a sparse Cholesky factorization of `W`.
//! - [`dense_generalized_eigen`], [`dense_generalized_eigen_with_mass`]: dense reference
//!   eigensolvers with a diagonal or a dense SPD mass (test oracle, small problems), on
//!   [`symmetric_eigen`]: faer's dense symmetric eigensolver with every residual checked (its
//!   QR algorithm where divide and conquer misses round-off).
//! - [`DenseCholesky`]: dense Cholesky with rank-one update/downdate and bordered updates.
//! - [`convert`]: `sprs → faer` conversions.
//! - [`iterative_refinement`]: refined sparse solves (conjugate gradients preconditioned by a
//!   factorization) with residuals in double-double arithmetic.
//! - [`sparse_pattern`]: CSR patterns that grow, for numeric refactorizations.
//! - [`FactorParallelism`]: one thread or all of them for a factorization, by its flop count.
//! - [`ordering`]: fill-reducing orderings ([`FillOrdering`]: AMD or METIS nested dissection).
#![warn(missing_docs)]
// Index loops mirror the matrix formulas (L[i][k], x[i]) in the numeric kernels.
#![allow(clippy::needless_range_loop)]

mod calling_thread;
pub mod convert;
mod dense_cholesky;
mod dense_eigen;
mod eigen;
mod error;
mod factor_parallelism;
mod huge_pages;
pub mod iterative_refinement;
mod kernel_dispatch;
pub mod ordering;
mod packed_ldlt_solve;
mod packed_rows;
mod packed_solve_split;
mod process_clock;
mod sparse_cholesky;
mod sparse_ldlt;
pub mod sparse_pattern;
mod symmetric_eigen;

pub use dense_cholesky::DenseCholesky;
pub use dense_eigen::{dense_generalized_eigen, dense_generalized_eigen_with_mass};
pub use eigen::{
    default_slice_memory, keep_columns, lowest_eigenpairs, lowest_eigenpairs_of, parse_byte_count,
    process_cpu_seconds, set_default_slice_memory, streamed_eigenvectors_in_memory, EigenOptions,
    EigenProgress, EigenRequest, EigenSolution, Eigenpairs, EigenvectorSink, FinishedEigenvectors,
    MassMatrix, Pencil, Phase, PhaseStatistics, RequestError, ShiftCount, SolverStatistics,
};
pub use error::SolverError;
pub use factor_parallelism::{FactorParallelism, SEQUENTIAL_FLOP_LIMIT};
pub use iterative_refinement::SolveReport;
pub use ordering::FillOrdering;
pub use sparse_cholesky::SparseCholesky;
pub use sparse_ldlt::{FactorPattern, Inertia, SparseLdlt};
pub use symmetric_eigen::symmetric_eigen;
