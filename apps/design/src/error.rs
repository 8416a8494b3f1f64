//! Errors of tvf-design: invalid constraints (always naming the constraint id), unreadable
//! constraint files (naming the file), and dependent constraints in a spline session.

use std::path::PathBuf;
use thiserror::Error;
use tvf_solvers::SolverError;

/// A constraint that cannot be turned into rows on the given mesh and discretization.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ConstraintError {
    /// The `kind` is none of `vector`, `divergence`, `curl`.
    #[error("constraint '{id}': unknown kind '{kind}' (expected vector, divergence or curl)")]
    UnknownKind {
        /// Constraint id.
        id: String,
        /// The kind given.
        kind: String,
    },
    /// A face, vertex or edge index is out of range.
    #[error("constraint '{id}': {what} {index} is out of range (the mesh has {count} of them)")]
    OutOfRange {
        /// Constraint id.
        id: String,
        /// `face`, `vertex` or `edge`.
        what: &'static str,
        /// The index given.
        index: i64,
        /// How many there are.
        count: usize,
    },
    /// A face, vertex or edge index is negative.
    #[error("constraint '{id}': {what} {index} is negative (indices count from 0)")]
    NegativeIndex {
        /// Constraint id.
        id: String,
        /// `face`, `vertex` or `edge`.
        what: &'static str,
        /// The index given.
        index: i64,
    },
    /// Barycentric coordinates (corner weights) that are negative, non-finite, fewer than
    /// three or do not sum to 1.
    #[error(
        "constraint '{id}': barycentric coordinates {values:?} must be non-negative and sum to 1 \
         (one per corner of the face, at least three)"
    )]
    BadBarycentric {
        /// Constraint id.
        id: String,
        /// The coordinates given.
        values: Vec<f64>,
    },
    /// Barycentric coordinates whose number is not the face's number of corners.
    #[error(
        "constraint '{id}': face {face} has {corners} corners, but \"barycentric\" gives \
         {weights} weights (one per corner, in the face's corner order)"
    )]
    WrongCornerCount {
        /// Constraint id.
        id: String,
        /// The face.
        face: usize,
        /// Its corners.
        corners: usize,
        /// Weights given.
        weights: usize,
    },
    /// A value or weight is NaN or infinite (or a weight is not positive).
    #[error("constraint '{id}': {what} must be finite{extra}")]
    NotFinite {
        /// Constraint id.
        id: String,
        /// `value` or `weight`.
        what: &'static str,
        /// Extra explanation (e.g. " and positive").
        extra: &'static str,
    },
    /// A constraint whose id is empty, blank or holds control characters (a line break).
    #[error(
        "constraint {position} (counting from 0) has the id {id:?}: every constraint needs a \
         unique id that is not empty or blank and holds no control characters (errors and \
         residuals name it)"
    )]
    BadId {
        /// The constraint's place in the file's list.
        position: usize,
        /// The id.
        id: String,
    },
    /// Two constraints share an id.
    #[error("constraint id '{id}' is used twice")]
    DuplicateId {
        /// The repeated id.
        id: String,
    },
    /// The value has the wrong shape for the kind (a scalar for a vector, ...).
    #[error("constraint '{id}': a {kind} constraint needs {expected}")]
    BadValue {
        /// Constraint id.
        id: String,
        /// The kind.
        kind: &'static str,
        /// What the value must look like.
        expected: &'static str,
    },
    /// The location keys do not fit the kind (a vector at a vertex, none or several of
    /// face/vertex/edge, barycentric without face, ...).
    #[error("constraint '{id}': {problem}")]
    BadLocation {
        /// Constraint id.
        id: String,
        /// What is wrong.
        problem: String,
    },
    /// A `vertex` or `edge` key addresses nodes of a space the requested operator does not live
    /// in; `detail` says which key (or family) to use instead.
    #[error("constraint '{id}': {detail}")]
    NodeKindMismatch {
        /// Constraint id.
        id: String,
        /// What the operator's nodes are and which key fits.
        detail: String,
    },
    /// The discretization lacks what the constraint needs (sampling, point evaluation, the other
    /// family).
    #[error("constraint '{id}': {detail}")]
    Unsupported {
        /// Constraint id.
        id: String,
        /// What is missing.
        detail: String,
    },
    /// The constraint's row is identically zero (e.g. a node no face uses).
    #[error("constraint '{id}': its row is zero (the node is not used by any face)")]
    EmptyRow {
        /// Constraint id.
        id: String,
    },
    /// `family` is neither `decomposition` nor `other`.
    #[error("constraint '{id}': unknown family '{family}' (expected decomposition or other)")]
    UnknownFamily {
        /// Constraint id.
        id: String,
        /// The family given.
        family: String,
    },
}

/// A constraint file that cannot be read, parsed or validated.
#[derive(Debug, Error)]
pub enum ConstraintFileError {
    /// The file cannot be read.
    #[error("{path}: cannot read: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file is not valid JSON or does not have the constraint-set shape.
    #[error("{path}: {source}")]
    Json {
        /// The file.
        path: PathBuf,
        /// The parser's message (with line and column).
        source: serde_json::Error,
    },
    /// A constraint is invalid.
    #[error("{path}: {source}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong, naming the constraint id.
        source: ConstraintError,
    },
    /// `omega` is negative or not finite.
    #[error("{path}: omega must be finite and non-negative, got {omega}")]
    BadOmega {
        /// The file.
        path: PathBuf,
        /// The value given.
        omega: f64,
    },
    /// The file names a mesh fingerprint that differs from the mesh's.
    #[error(
        "{path}: written for mesh fingerprint {expected}, but the mesh has fingerprint {actual}"
    )]
    FingerprintMismatch {
        /// The file.
        path: PathBuf,
        /// The fingerprint in the file.
        expected: String,
        /// The mesh's fingerprint.
        actual: String,
    },
}

/// What can go wrong in a spline session or a soft design.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DesignError {
    /// A constraint row depends linearly on the active constraints (in the reduced space): it is
    /// either redundant (its value agrees) or conflicting (it does not). The session is unchanged.
    #[error(
        "constraint '{id}' is {} on {involved:?} in the reduced space (relative pivot {relative_pivot:.1e}); it was not added",
        if *.conflicting { "conflicting: it depends linearly" } else { "redundant: it depends linearly" }
    )]
    Dependent {
        /// The constraint that could not be added.
        id: String,
        /// Active constraints it depends on (largest contributions first).
        involved: Vec<String>,
        /// Whether the implied value differs from the prescribed one.
        conflicting: bool,
        /// `pivot² / diagonal` of the bordered factorization (0 = exactly dependent).
        relative_pivot: f64,
    },
    /// A constraint the reduced space cannot hold on its own (its rows vanish in it or depend
    /// on each other there): the basis is too small or misses the constraint's location.
    #[error(
        "constraint '{id}' cannot be met in the reduced space of {basis_size} basis fields: \
         {detail} (use a larger basis); it was not added"
    )]
    NotRepresentable {
        /// The constraint.
        id: String,
        /// Number of basis fields.
        basis_size: usize,
        /// What happens to its rows.
        detail: String,
    },
    /// An id that is already active was added again.
    #[error("constraint id '{id}' is already active")]
    DuplicateId {
        /// The id.
        id: String,
    },
    /// An id that is not active was removed or modified.
    #[error("no active constraint with id '{id}'")]
    UnknownId {
        /// The id.
        id: String,
    },
    /// Sizes do not fit (rows of another mesh, a value vector of the wrong length, ...).
    #[error("{what}: expected {expected}, got {actual}")]
    DimensionMismatch {
        /// What was being checked.
        what: &'static str,
        /// Expected size.
        expected: usize,
        /// Given size.
        actual: usize,
    },
    /// The basis is empty or has no positive eigenvalue to regularise harmonic fields with.
    #[error("unusable basis: {0}")]
    BadBasis(String),
    /// `omega` or the regularisation is negative or not finite.
    #[error("{what} must be finite and non-negative, got {value}")]
    BadParameter {
        /// Parameter name.
        what: &'static str,
        /// Value given.
        value: f64,
    },
    /// A solved field or a constraint residual is NaN or infinite.
    #[error("constraint '{id}': {problem}; {cause}")]
    NotFinite {
        /// The constraint whose residual is not finite, or the one with the largest values.
        id: String,
        /// What is not finite.
        problem: String,
        /// The likely cause.
        cause: String,
    },
    /// `omega` is so large that the reduced energy of an eigenfield is not a normal `f64`.
    #[error(
        "omega {omega:e} is too large for this basis: the energy of the eigenfield with \
         eigenvalue {eigenvalue:e} overflows f64 arithmetic"
    )]
    OmegaTooLarge {
        /// The weight given.
        omega: f64,
        /// The eigenvalue whose energy is out of range.
        eigenvalue: f64,
    },
    /// A dense system that must be positive definite is not (numerically).
    #[error("{0} is not positive definite")]
    NotPositiveDefinite(String),
    /// A sparse or dense factorization failed (e.g. the system is not positive definite).
    #[error("factorization failed: {0}")]
    Solver(#[from] SolverError),
}
