//! Errors of the Hodge decomposition.

use thiserror::Error;
use tvf_core::discretization::DiscretizationError;
use tvf_solvers::SolverError;

/// What can go wrong when decomposing a field.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum DecompositionError {
    /// Bad input (wrong length, non-finite values, a value where the boundary condition fixes
    /// zero).
    #[error(transparent)]
    Discretization(#[from] DiscretizationError),
    /// A Poisson factorization failed.
    #[error("Poisson solve failed: {0}")]
    Solver(#[from] SolverError),
}
