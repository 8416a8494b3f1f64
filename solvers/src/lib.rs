//! # tvf-solvers
//!
//! Sparse Cholesky, generalized symmetric eigensolvers and dense updates (knows matrices, not meshes).
//!
//! - [`SparseCholesky`]: supernodal sparse Cholesky (faer) with symbolic reuse and blocked solves.
//! - [`SparseLdlt`]: the underlying `LDLᵀ` factorization of indefinite shifted matrices, with
//!   [`Inertia`] (Sylvester's law) for eigenvalue counting.
//! - [`lowest_eigenpairs`]: lowest k eigenpairs of `A x = λ M x` (shift-and-invert block
//!   Krylov–Schur, spectrum slicing, inertia-verified completeness).
//! - [`dense_generalized_eigen`]: dense reference eigensolver (test oracle, small problems).
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

pub mod convert;
mod dense_cholesky;
mod dense_eigen;
mod eigen;
mod error;
mod factor_parallelism;
pub mod iterative_refinement;
pub mod ordering;
mod sparse_cholesky;
mod sparse_ldlt;
pub mod sparse_pattern;

pub use dense_cholesky::DenseCholesky;
pub use dense_eigen::dense_generalized_eigen;
pub use eigen::{lowest_eigenpairs, EigenOptions, EigenProgress, Eigenpairs};
pub use error::SolverError;
pub use factor_parallelism::{FactorParallelism, SEQUENTIAL_FLOP_LIMIT};
pub use iterative_refinement::SolveReport;
pub use ordering::FillOrdering;
pub use sparse_cholesky::SparseCholesky;
pub use sparse_ldlt::{Inertia, SparseLdlt};
