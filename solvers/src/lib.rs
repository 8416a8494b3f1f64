//! # tvf-solvers
//!
//! Sparse Cholesky, generalized symmetric eigensolvers and dense updates (knows matrices, not meshes).
#![warn(missing_docs)]
