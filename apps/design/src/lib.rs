//! # tvf-design
//!
//! Tangential vector field splines (hard constraints, Section 7 of the paper) and
//! soft-constrained design (Fisher et al. 2007, Section 8.4), full and reduced.
//!
//! - [`Constraint`]: a vector in a face, a divergence or a curl value at a node or a point;
//!   [`ConstraintSet`] reads the JSON format; [`ConstraintAssembler`] turns constraints into rows
//!   `C̃` of any [`HodgeComplex`](tvf_core::discretization::HodgeComplex).
//! - [`ReducedBasis`]: the eigenfields `U` row-major, with `x = U v` in `f64` and `f32`.
//! - [`SplineSession`]: the reduced spline editor (bordered dense Cholesky of `C D⁻¹ Cᵀ`);
//!   [`reference_spline`]: the full-resolution spline for checking it.
//! - [`FullSoftDesign`] (sparse `LDLᵀ` of an augmented system, symbolic reuse, iterative
//!   refinement; any masses: diagonal, consistent, Whitney) and [`ReducedSoftDesign`] (dense
//!   Cholesky with low-rank updates).
//! - [`DesignProblem`]: a mesh and its constraint file as `tvf spline` and `tvf design` run them
//!   (timed solves: [`timed_spline`], [`timed_reduced_design`], [`timed_full_design`]; their
//!   report lines and JSON keys: [`ResidualReport`], [`TimedFullDesign`]).
//!
//! ```
//! use tvf_core::generate::icosphere;
//! use tvf_design::{Constraint, ConstraintAssembler, Location, Target};
//! use tvf_discretizations::{Conforming, MassLumping};
//!
//! let mesh = icosphere(1);
//! let complex = Conforming::new(&mesh, MassLumping::Barycentric)?;
//! let assembler = ConstraintAssembler::new(&complex, &mesh);
//! let source = Constraint::new("source", Target::Divergence(2.0), Location::Vertex(5));
//! let compiled = assembler.compile(&source)?;
//! assert_eq!(compiled.rows.len(), 1); // one row of div_h
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod assembler;
mod augmented_system;
mod checked_constraint_file;
mod constraint;
mod constraint_file;
mod design_problem;
mod design_report;
mod diagonal_system;
mod error;
mod galerkin_blocks;
mod galerkin_soft;
mod reduced_basis;
mod reference_spline;
mod regularization;
mod soft_full;
mod soft_options;
mod soft_reduced;
mod soft_system;
mod solution_check;
mod spline;
mod timed_full_design;
mod timed_reduced_solve;

pub use assembler::ConstraintAssembler;
pub use constraint::{
    CompiledConstraint, Constraint, Location, OperatorFamily, RowOrigin, SparseRow, Target,
};
pub use constraint_file::{ConstraintSet, DEFAULT_OMEGA};
pub use design_problem::{DesignProblem, DesignRunError, ProblemSummary};
pub use design_report::{ReducedDesignTimes, ResidualReport};
pub use error::{ConstraintError, ConstraintFileError, DesignError};
pub use reduced_basis::{FieldScalar, ReducedBasis, ReducedBasisF32, RowMajorFields};
pub use reference_spline::{reference_spline, ReferenceSpline};
pub use regularization::default_regularization;
pub use soft_full::{FactorTimings, FullSoftDesign, DEFAULT_FULL_ORDERING};
pub use soft_options::SoftOptions;
pub use soft_reduced::ReducedSoftDesign;
pub use solution_check::{checked_residuals, worst_residual};
pub use spline::{residual, ConstraintResidual, SplineSession, DEFAULT_DEPENDENCY_TOLERANCE};
pub use timed_full_design::{
    parse_fill_ordering, timed_full_design, TimedFullDesign, FULL_SOLVE_TARGET,
};
pub use timed_reduced_solve::{timed_reduced_design, timed_spline, TimedReducedSolve};
pub use tvf_solvers::{FactorParallelism, FillOrdering, SolveReport, SEQUENTIAL_FLOP_LIMIT};
