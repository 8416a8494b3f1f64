//! Errors of the mesh readers and writers: which file, where in it, and what is wrong.

use crate::MeshError;
use std::fmt;
use std::path::PathBuf;
use thiserror::Error;

/// A mesh file could not be turned into a valid [`crate::TriangleMesh`].
///
/// Displays as `path:line: problem` (or `path: problem` where no line applies, e.g. binary
/// PLY or whole-mesh checks).
#[derive(Debug, Clone, PartialEq, Error)]
pub struct LoadError {
    /// The file (as given; for in-memory parsing, the name the caller chose).
    pub path: PathBuf,
    /// 1-based line of the problem in a text file, where one applies.
    pub line: Option<usize>,
    /// What is wrong.
    pub kind: LoadErrorKind,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{line}: {}", self.path.display(), self.kind),
            None => write!(f, "{}: {}", self.path.display(), self.kind),
        }
    }
}

/// The problem behind a [`LoadError`].
#[derive(Debug, Clone, PartialEq, Error)]
pub enum LoadErrorKind {
    /// The file could not be read (missing, a directory, no permission, ...).
    #[error("cannot read the file: {reason}")]
    Unreadable {
        /// The operating system's message.
        reason: String,
    },
    /// The extension is none of `obj`, `off`, `ply`.
    #[error("unknown mesh format '{extension}' (expected .obj, .off or .ply)")]
    UnknownFormat {
        /// The extension found (empty if none).
        extension: String,
    },
    /// A text format contains bytes that are not UTF-8 text (binary data).
    #[error("not a text file: invalid UTF-8 data")]
    NotText,
    /// A text format saved as UTF-16 (it starts with a UTF-16 byte-order mark).
    #[error("the file is UTF-16 text: save it as UTF-8")]
    Utf16,
    /// The file is empty or holds only comments and whitespace.
    #[error("the file is empty")]
    Empty,
    /// Malformed syntax.
    #[error("parse error: {message}")]
    Parse {
        /// What was expected and what was found.
        message: String,
    },
    /// The file ends before everything its header declares.
    #[error("the file ends early: {message}")]
    Truncated {
        /// What was still missing.
        message: String,
    },
    /// Data after everything the header declares.
    #[error("unexpected data after the declared elements: {message}")]
    TrailingData {
        /// What was found.
        message: String,
    },
    /// A valid file using a variant tvf does not read (e.g. a 4D OFF file).
    #[error("unsupported: {feature}")]
    Unsupported {
        /// The unsupported feature.
        feature: String,
    },
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate")]
    NonFiniteCoordinate {
        /// 0-based vertex index in the file.
        vertex: usize,
    },
    /// A face refers to a vertex that does not exist.
    #[error("vertex index {index} is out of range: the file has {vertex_count} vertices")]
    IndexOutOfRange {
        /// The index as written in the file (1-based or negative in OBJ, 0-based in OFF/PLY).
        index: i64,
        /// Number of vertices in the file.
        vertex_count: usize,
    },
    /// A face with fewer than three corners.
    #[error("a face has {corners} corners; at least 3 are needed")]
    FaceTooSmall {
        /// Number of corners found.
        corners: usize,
    },
    /// The faces do not form a valid surface (indices are the file's 0-based vertices and faces,
    /// in order).
    #[error("{0}")]
    Mesh(#[from] MeshError),
}
