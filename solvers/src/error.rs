//! Error type shared by every solver in this crate.

use thiserror::Error;

/// Everything that can go wrong in `tvf-solvers` because of the input (never because of a bug).
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SolverError {
    /// The matrix is not square.
    #[error("matrix is not square: {rows} rows, {cols} columns")]
    NotSquare {
        /// Number of rows.
        rows: usize,
        /// Number of columns.
        cols: usize,
    },
    /// Two operands (or an operand and a factorization) have incompatible sizes.
    #[error("dimension mismatch in {context}: expected {expected}, got {actual}")]
    DimensionMismatch {
        /// What was being combined.
        context: &'static str,
        /// Expected size.
        expected: usize,
        /// Size that was given.
        actual: usize,
    },
    /// A matrix or vector entry is NaN or infinite.
    #[error("non-finite entry ({value}) in {context} at row {row}, column {col}")]
    NonFinite {
        /// Which input contained the entry.
        context: &'static str,
        /// Row of the entry (0 for vectors).
        row: usize,
        /// Column of the entry (0 for vectors).
        col: usize,
        /// The offending value.
        value: f64,
    },
    /// The (possibly shifted) matrix is not numerically positive definite.
    ///
    /// `pivot` is the row/column of the input matrix (original numbering) whose pivot was
    /// not positive during the elimination.
    #[error(
        "matrix is not positive definite (non-positive pivot {value:e} at row/column {pivot})"
    )]
    NotPositiveDefinite {
        /// Row/column (original numbering) where the elimination met a non-positive pivot.
        pivot: usize,
        /// Value of that pivot (0 if the elimination stopped on an exact zero).
        value: f64,
    },
    /// A matrix of the input that must be symmetric positive definite is not (numerically):
    /// a sparse mass matrix, or the `W` of a mixed pencil.
    #[error(
        "{matrix} is not positive definite (non-positive pivot {value:e} at row/column {pivot})"
    )]
    MatrixNotPositiveDefinite {
        /// Which matrix: `"mass matrix"`, `"W"`, …
        matrix: &'static str,
        /// Row/column (original numbering) where the elimination met a non-positive pivot.
        pivot: usize,
        /// Value of that pivot (0 if the elimination stopped on an exact zero).
        value: f64,
    },
    /// An indefinite `LDLᵀ` factorization met an exactly zero pivot (the matrix is singular
    /// or the shift coincides with an eigenvalue).
    #[error("singular matrix: zero pivot at row/column {pivot}")]
    Singular {
        /// Row/column (original numbering) of the zero pivot.
        pivot: usize,
    },
    /// `refactor` was called with a matrix whose sparsity pattern differs from the one analysed.
    #[error("sparsity pattern differs from the one used in the symbolic analysis")]
    PatternMismatch,
    /// The diagonal mass matrix has a non-positive entry.
    #[error("mass matrix entry {index} is not positive ({value})")]
    MassNotPositive {
        /// Index of the entry.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// More eigenpairs were requested than the problem has.
    #[error("requested {requested} eigenpairs but the problem has dimension {dimension}")]
    TooManyEigenpairs {
        /// Requested number.
        requested: usize,
        /// Matrix dimension.
        dimension: usize,
    },
    /// The eigensolver did not converge within its iteration budget.
    #[error("eigensolver did not converge: {reason}")]
    NoConvergence {
        /// Human-readable description of what failed.
        reason: String,
    },
    /// The caller's sink of finished eigenvectors ([`crate::EigenOptions::finished`]) failed,
    /// e.g. writing them to a file.
    #[error("{reason}")]
    Stopped {
        /// What the sink said.
        reason: String,
    },
    /// faer reported an allocation or index overflow failure.
    #[error("sparse factorization failed: {0}")]
    Factorization(String),
}
