//! Errors of the discretization layer.

use thiserror::Error;

/// What can go wrong when building or applying a discretization.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum DiscretizationError {
    /// A vector or list has the wrong length.
    #[error("{what}: expected {expected} entries, found {found}")]
    DimensionMismatch {
        /// What was being passed (e.g. "per-face vectors").
        what: &'static str,
        /// The length the discretization needs.
        expected: usize,
        /// The length that was given.
        found: usize,
    },
    /// A face with zero (or non-finite) area: gradients are undefined on it.
    #[error("face {face} is degenerate (area {area:e}); gradients are undefined on it")]
    DegenerateFace {
        /// Index of the face.
        face: usize,
        /// Its area.
        area: f64,
    },
    /// An input value is NaN or infinite.
    #[error("{what} contains a non-finite value at index {index}")]
    NonFinite {
        /// What was being passed.
        what: &'static str,
        /// The first offending index.
        index: usize,
    },
    /// A face index is out of range.
    #[error("face {face} is out of range (the mesh has {face_count} faces)")]
    FaceOutOfRange {
        /// The requested face.
        face: usize,
        /// Number of faces.
        face_count: usize,
    },
}
