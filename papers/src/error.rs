//! [`PaperError`]: everything that can stop a reproduction, with the step it happened in.

use std::path::PathBuf;
use thiserror::Error;

/// An error of the reproduction harness. Library errors are wrapped as they are; file errors
/// name the file.
#[derive(Debug, Error)]
pub enum PaperError {
    /// A mesh file could not be read or is not a valid mesh.
    #[error(transparent)]
    Load(#[from] tvf_core::io::LoadError),
    /// A discretization could not be assembled (e.g. a degenerate face).
    #[error(transparent)]
    Discretization(#[from] tvf_core::discretization::DiscretizationError),
    /// A discretization id the catalog does not know.
    #[error(transparent)]
    UnknownDiscretization(#[from] tvf_discretizations::UnknownDiscretization),
    /// The eigenfield basis could not be computed.
    #[error(transparent)]
    Basis(#[from] tvf_spectral::BasisError),
    /// A field did not fit a basis.
    #[error(transparent)]
    SpectralBasis(#[from] tvf_spectral::SpectralBasisError),
    /// A spectral filter was rejected.
    #[error(transparent)]
    Filter(#[from] tvf_spectral::FilterError),
    /// A drawn filter curve was rejected.
    #[error(transparent)]
    FilterCurve(#[from] tvf_spectral::FilterSpecError),
    /// Compression failed.
    #[error(transparent)]
    Compression(#[from] tvf_spectral::CompressionError),
    /// A design system failed.
    #[error(transparent)]
    Design(#[from] tvf_design::DesignError),
    /// A constraint could not be compiled.
    #[error(transparent)]
    Constraint(#[from] tvf_design::ConstraintError),
    /// A picture could not be drawn or saved.
    #[error(transparent)]
    Render(#[from] tvf_render::RenderError),
    /// A result file could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// An experiment was asked for something it cannot do.
    #[error("{0}")]
    Invalid(String),
}
