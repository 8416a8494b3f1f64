//! # tvf-figures
//!
//! The figures of Brandt et al., "Spectral Processing of Tangential Vector Fields" (CGF 2017),
//! as a library: the `tvf` CLI's demo page and `papers/`'s reproduction run the same code, so a
//! picture on the demo page is the paper's figure on the demo's mesh.
//!
//! - [`eigenfields_and_filtering`]: Figure 1 (eigenfield pairs), Figures 7 and 8 (filtering a
//!   noisy field, its spectrum).
//! - [`compression`]: Figure 9 (rate–distortion curves), Figure 10 (many small vortices),
//!   projection and reconstruction timings; [`compression_sequence`]: the time-dependent
//!   compression experiment and Figure 11.
//! - [`test_fields`]: the input fields, made from the mesh; [`seeded_constraints`]: seeded
//!   constraint sets for the design experiments.
//! - [`finding`]: [`Finding`] (one reproduced result: files, numbers, the paper's claim) and
//!   [`Experiment`] (mesh, complex, basis, output folder, view).
//! - [`demo`]: the demo page, run by `tvf demo` through a [`demo::DemoHost`].
//! - [`convergence_plot`]: the picture of a convergence study against exact spectra
//!   (`tvf convergence`, `papers/`'s discretization comparison).
//! - [`spectral_plots`]: the plots of `tvf analyze` (coefficient magnitudes) and
//!   `tvf rate-distortion` (rate–distortion curves); [`spectral_folders`]: the folders these
//!   commands write.
//! - [`panels`], [`constraint_markers`], [`numbers`], [`timing`]: drawing, marking, formatting
//!   and timing helpers the figures share.
//!
//! ```
//! use tvf_core::generate::icosphere;
//! use tvf_discretizations::{catalog_entry, DEFAULT_DISCRETIZATION};
//! use tvf_figures::test_fields::smooth_field;
//!
//! let mesh = tvf_core::SurfaceMesh::from(icosphere(2));
//! let complex = catalog_entry(DEFAULT_DISCRETIZATION)?.build(&mesh)?;
//! // A field with all three Hodge parts, one value per field coefficient of the complex.
//! let field = smooth_field(complex.as_ref(), &mesh);
//! assert_eq!(field.len(), 2 * mesh.face_count());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

pub mod compression;
pub mod compression_sequence;
pub mod constraint_markers;
pub mod convergence_plot;
pub mod demo;
pub mod eigenfields_and_filtering;
pub mod error;
pub mod finding;
pub mod numbers;
pub mod panels;
pub mod seeded_constraints;
pub mod spectral_folders;
pub mod spectral_plots;
pub mod test_fields;
pub mod timing;

pub use error::FigureError;
pub use finding::{Experiment, Finding};
