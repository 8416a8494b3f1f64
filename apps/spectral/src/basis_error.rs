//! [`BasisError`]: why a Fourier basis could not be computed.

use crate::SpectralBasisError;
use thiserror::Error;
use tvf_discretizations::DecompositionError;
use tvf_solvers::SolverError;

/// What can go wrong in [`crate::compute_basis`].
#[derive(Debug, Clone, PartialEq, Error)]
pub enum BasisError {
    /// The request cannot be met (e.g. more fields than the space has, a negative bound).
    #[error("invalid basis request: {0}")]
    InvalidRequest(String),
    /// The harmonic projection failed (a Poisson factorization).
    #[error("harmonic fields: {0}")]
    Harmonic(#[from] DecompositionError),
    /// An eigensolver failed.
    #[error("{problem} eigenproblem: {source}")]
    Eigen {
        /// Which eigenproblem: "potential" or "co-potential".
        problem: &'static str,
        /// The solver's error.
        source: SolverError,
    },
    /// The lowest eigenvalues, one per connected component whose constants are in the kernel,
    /// are not numerically zero: the complex's node spaces do not match its kernel.
    #[error(
        "{problem} eigenproblem: expected {components} zero eigenvalues (one per component), but \
         eigenvalue {value:e} is not small against the first non-zero one {first_nonzero:e}"
    )]
    KernelMismatch {
        /// Which eigenproblem.
        problem: &'static str,
        /// Connected components (expected kernel dimension).
        components: usize,
        /// The offending supposedly-zero eigenvalue.
        value: f64,
        /// The first eigenvalue kept as non-zero.
        first_nonzero: f64,
    },
    /// The assembled basis is inconsistent (a bug, reported instead of panicking).
    #[error(transparent)]
    Basis(#[from] SpectralBasisError),
}
