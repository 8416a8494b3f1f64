//! [`FigureError`]: everything that can stop a reproduction, with the step it happened in.

use std::path::PathBuf;
use thiserror::Error;

/// An error of a figure, the demo page or the reproduction harness. Library errors are wrapped
/// as they are; file errors name the file.
#[derive(Debug, Error)]
pub enum FigureError {
    /// A mesh file could not be read or is not a valid mesh.
    #[error(transparent)]
    Load(#[from] tvf_core::io::LoadError),
    /// A discretization could not be assembled (e.g. a degenerate face).
    #[error(transparent)]
    Discretization(#[from] tvf_core::discretization::DiscretizationError),
    /// The catalog could not build a complex (unknown id, or the mesh refused).
    #[error(transparent)]
    Catalog(#[from] tvf_discretizations::CatalogBuildError),
    /// A discretization id the catalog does not know.
    #[error(transparent)]
    UnknownDiscretization(#[from] tvf_discretizations::UnknownDiscretization),
    /// The eigenfield basis could not be computed.
    #[error(transparent)]
    Basis(#[from] tvf_spectral::BasisError),
    /// A field did not fit a basis.
    #[error(transparent)]
    SpectralBasis(#[from] tvf_spectral::SpectralBasisError),
    /// A field could not be decomposed.
    #[error(transparent)]
    Decomposition(#[from] tvf_discretizations::DecompositionError),
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
    /// A constraint file could not be read, or does not fit the mesh.
    #[error(transparent)]
    ConstraintFile(#[from] tvf_design::ConstraintFileError),
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
    /// An error of the program running the demo (e.g. the CLI's basis cache).
    #[error(transparent)]
    Host(Box<dyn std::error::Error + Send + Sync>),
    /// An error of one step, with the step or the input it happened in.
    #[error("{context}")]
    InContext {
        /// The step or input (e.g. "demo step 'Hodge decomposition'", a mesh name).
        context: String,
        /// What went wrong.
        #[source]
        source: Box<FigureError>,
    },
}
