//! tvf-solvers' integration tests: dense and sparse Cholesky, orderings, the eigensolver on
//! diagonal, sparse and mixed pencils. `common` holds the shared test matrices.

mod common;
mod dense_cholesky;
mod eigen;
mod galerkin;
mod ordering;
mod sparse_cholesky;
