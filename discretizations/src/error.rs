//! Errors of the Hodge decomposition.

use thiserror::Error;
use tvf_core::discretization::DiscretizationError;
use tvf_solvers::SolverError;

/// What can go wrong when decomposing a field.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum DecompositionError {
    /// The mesh has boundary edges: `d1 · d0 ≠ 0` there, so the three parts would not be
    /// orthogonal and the decomposition is not defined (the paper treats closed meshes).
    #[error("the Hodge decomposition needs a closed mesh; this mesh has boundary edges")]
    Boundary,
    /// Bad input (wrong length, non-finite values).
    #[error(transparent)]
    Discretization(#[from] DiscretizationError),
    /// A Poisson factorization failed.
    #[error("Poisson solve failed: {0}")]
    Solver(#[from] SolverError),
}
