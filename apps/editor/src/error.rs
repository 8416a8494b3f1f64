//! [`EditorError`]: everything the editor can refuse or fail at, with the HTTP status it maps to.

use thiserror::Error;
use tvf_design::{ConstraintError, ConstraintFileError, DesignError};

/// An error of the editor: a bad request (4xx) or a failure of the server (5xx).
#[derive(Debug, Error)]
pub enum EditorError {
    /// The request is malformed (bad JSON, unknown operation, missing field).
    #[error("bad request: {reason}")]
    BadRequest {
        /// What is wrong.
        reason: String,
    },
    /// The request does not come from the editor's own page (foreign `Host` or `Origin`, no
    /// or a wrong session token; see [`crate::access`]).
    #[error("forbidden: {reason}")]
    Forbidden {
        /// Why.
        reason: String,
    },
    /// The client did not send its request in time.
    #[error("timed out waiting for {what}")]
    Timeout {
        /// What was being read.
        what: &'static str,
    },
    /// Too many connections or uploads at once; the request was not read.
    #[error("the server is busy ({what}); try again")]
    Busy {
        /// What is exhausted.
        what: &'static str,
    },
    /// No such page or endpoint.
    #[error("not found: {path}")]
    NotFound {
        /// The requested path.
        path: String,
    },
    /// The endpoint exists but not for this HTTP method.
    #[error("method {method} not allowed for {path}")]
    MethodNotAllowed {
        /// The method used.
        method: String,
        /// The path.
        path: String,
    },
    /// A constraint record that does not fit the mesh (index out of range, bad barycentric
    /// coordinates, ...).
    #[error(transparent)]
    Constraint(#[from] ConstraintError),
    /// A constraint set that does not parse or validate.
    #[error(transparent)]
    ConstraintFile(#[from] ConstraintFileError),
    /// The spline session refused the edit (a dependent or conflicting constraint, an unknown
    /// or duplicate id, a bad ω); the state is unchanged.
    #[error(transparent)]
    Design(#[from] DesignError),
    /// Undo with an empty history.
    #[error("nothing to undo")]
    NothingToUndo,
    /// A basis size outside `1..=d`.
    #[error("basis size {requested} is out of range: choose 1 to {available}")]
    BadBasisSize {
        /// The size asked for.
        requested: usize,
        /// The size of the loaded basis.
        available: usize,
    },
    /// A request larger than the server accepts (its head, its headers, its body).
    #[error("the request is too large: {count} {what}, at most {limit} are accepted")]
    RequestTooLarge {
        /// What was counted (e.g. "request body bytes").
        what: &'static str,
        /// The count.
        count: usize,
        /// The most accepted.
        limit: usize,
    },
    /// A count that does not fit the binary format of the mesh, field or fur payloads.
    #[error("too many {what} for the binary format: {count}")]
    TooLarge {
        /// What was counted.
        what: &'static str,
        /// The count.
        count: usize,
    },
    /// A malformed binary payload (decoding on the client side).
    #[error("malformed payload: {reason}")]
    BadPayload {
        /// What is wrong.
        reason: String,
    },
    /// Rendering or exporting fur failed.
    #[error(transparent)]
    Render(#[from] tvf_render::RenderError),
    /// The mesh's discretization could not be built (a degenerate face).
    #[error("cannot build the operators of the mesh: {0}")]
    Discretization(String),
    /// The server could not listen or an I/O operation failed.
    #[error("{what}: {source}")]
    Io {
        /// What was being done.
        what: String,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// The editing engine thread has stopped (after a panic or at shutdown).
    #[error("the editing engine has stopped")]
    EngineStopped,
}

impl EditorError {
    /// The HTTP status code for this error: 400 for malformed input, 403 for a request from
    /// elsewhere than the editor's page, 404/405 for unknown endpoints or ids, 408 for a request
    /// sent too slowly, 503 when busy, 409 for edits the current state refuses, 422 for a field
    /// that is not finite, 413 for a request larger than the server accepts, 500 otherwise.
    pub fn status_code(&self) -> u16 {
        match self {
            EditorError::BadRequest { .. }
            | EditorError::Constraint(_)
            | EditorError::ConstraintFile(_)
            | EditorError::BadBasisSize { .. }
            | EditorError::BadPayload { .. } => 400,
            EditorError::Forbidden { .. } => 403,
            EditorError::NotFound { .. } => 404,
            EditorError::Timeout { .. } => 408,
            EditorError::Busy { .. } => 503,
            EditorError::MethodNotAllowed { .. } => 405,
            EditorError::Design(DesignError::UnknownId { .. }) => 404,
            EditorError::Design(
                DesignError::BadParameter { .. } | DesignError::OmegaTooLarge { .. },
            ) => 400,
            EditorError::Design(DesignError::NotFinite { .. }) => 422,
            EditorError::Design(
                DesignError::Dependent { .. }
                | DesignError::NotRepresentable { .. }
                | DesignError::DuplicateId { .. },
            )
            | EditorError::NothingToUndo => 409,
            EditorError::RequestTooLarge { .. } => 413,
            EditorError::TooLarge { .. } => 500,
            EditorError::Design(_)
            | EditorError::Render(_)
            | EditorError::Discretization(_)
            | EditorError::Io { .. }
            | EditorError::EngineStopped => 500,
        }
    }

    /// Ids of the constraints involved, for a dependent or conflicting constraint (shown on the
    /// page next to the message).
    pub fn involved_ids(&self) -> Vec<String> {
        match self {
            EditorError::Design(DesignError::Dependent { id, involved, .. }) => {
                std::iter::once(id.clone())
                    .chain(involved.iter().cloned())
                    .collect()
            }
            EditorError::Design(DesignError::NotRepresentable { id, .. }) => vec![id.clone()],
            _ => Vec::new(),
        }
    }
}
