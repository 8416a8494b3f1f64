//! Errors of the renderer, the plots and the exporters.

use std::path::PathBuf;
use thiserror::Error;

/// Everything that can go wrong while rendering, plotting, growing fur or exporting.
#[derive(Debug, Error)]
pub enum RenderError {
    /// A per-face array does not have one entry per face.
    #[error("{what} has {actual} entries, but the mesh has {expected} faces")]
    FaceCountMismatch {
        /// Which input (for example "field" or "face scalar").
        what: String,
        /// Number of faces of the mesh.
        expected: usize,
        /// Number of entries given.
        actual: usize,
    },
    /// A value that must be finite is NaN or infinite.
    #[error("{what} has a non-finite value at index {index}")]
    NonFinite {
        /// Which input.
        what: String,
        /// First offending index.
        index: usize,
    },
    /// An image size that cannot be rendered.
    #[error(
        "image size {width}x{height} is invalid (each side must be between 16 and 16384 pixels)"
    )]
    InvalidSize {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
    },
    /// An option with a value outside its allowed range.
    #[error("option {name} = {value} is invalid: {reason}")]
    InvalidOption {
        /// Option name.
        name: &'static str,
        /// The value given, formatted.
        value: String,
        /// What is allowed.
        reason: &'static str,
    },
    /// A plot without any point it can draw.
    #[error("plot has no drawable data: {0}")]
    NoPlotData(String),
    /// A name that the export format cannot hold.
    #[error("name {name:?} cannot be written to {format}: {reason}")]
    InvalidName {
        /// The name given.
        name: String,
        /// Export format.
        format: &'static str,
        /// Why it is refused.
        reason: &'static str,
    },
    /// Reading or writing a file failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The discretization cannot give what a picture needs (its sampling, its point
    /// evaluation, or a field of the wrong size).
    #[error(transparent)]
    Discretization(#[from] tvf_core::discretization::DiscretizationError),
    /// PNG encoding failed.
    #[error("cannot encode PNG {path}: {message}")]
    Png {
        /// The file.
        path: PathBuf,
        /// The encoder's message.
        message: String,
    },
}

/// Checks that a per-face array has `expected` entries.
pub(crate) fn check_face_count(
    what: &str,
    expected: usize,
    actual: usize,
) -> Result<(), RenderError> {
    if expected == actual {
        Ok(())
    } else {
        Err(RenderError::FaceCountMismatch {
            what: what.to_string(),
            expected,
            actual,
        })
    }
}

/// Checks that every component of every vector is finite.
pub(crate) fn check_finite_vectors(what: &str, values: &[[f64; 3]]) -> Result<(), RenderError> {
    match values.iter().position(|v| v.iter().any(|x| !x.is_finite())) {
        None => Ok(()),
        Some(index) => Err(RenderError::NonFinite {
            what: what.to_string(),
            index,
        }),
    }
}

/// Checks that every value is finite.
pub(crate) fn check_finite_scalars(what: &str, values: &[f64]) -> Result<(), RenderError> {
    match values.iter().position(|x| !x.is_finite()) {
        None => Ok(()),
        Some(index) => Err(RenderError::NonFinite {
            what: what.to_string(),
            index,
        }),
    }
}
