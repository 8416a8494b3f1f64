//! # tvf-papers
//!
//! Reproductions of papers' tables and figures, one module per paper (see `papers/README.md`):
//! [`brandt2017`] reproduces Brandt et al., "Spectral Processing of Tangential Vector Fields"
//! (CGF 2017). [`discretization_comparison`] runs every discretization of the catalog
//! ([`registry::compared_discretizations`]) through the convergence study of `tvf convergence`
//! ([`tvf_convergence`]) on icospheres; a discretization added to the catalog is
//! compared without another line.
//!
//! The pieces run on generated meshes as well as on the paper's:
//!
//! ```
//! use tvf_papers::discretization_comparison::{run, ComparisonConfig};
//! use tvf_papers::step_log::StepLog;
//! use tvf_papers::registry::compared_discretizations;
//!
//! let config = ComparisonConfig { levels: vec![1, 2], max_degree: 2 };
//! let results = run(&compared_discretizations()[..1], &config, &StepLog::new(true))?;
//! // The eigenvalue error falls under refinement.
//! assert!(results.rows[1].integrable_error < results.rows[0].integrable_error);
//! # Ok::<(), tvf_figures::FigureError>(())
//! ```
#![warn(missing_docs)]

pub mod brandt2017;
pub mod discretization_comparison;
pub mod markdown;
pub mod registry;
pub mod step_log;
