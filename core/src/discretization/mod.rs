//! The discretization traits: what a discretization of tangential vector fields must provide, and
//! every operator of the paper derived once from it.
//!
//! The paper's discrete Hodge decomposition is a short cochain complex with diagonal masses
//! (`shared/docs/ARCHITECTURE.md`):
//!
//! ```text
//! potentials --d0--> fields --d1--> co-potentials,      d1 · d0 = 0 (closed meshes)
//!   mass M0         mass M1       mass M2⁻¹ (M2 acts on d1's integrated output)
//! ```
//!
//! - [`FunctionSpace`]: a space of scalar functions (P1 on vertices, Crouzeix–Raviart on edge
//!   midpoints, ...): dimension, lumped mass, gradient into face fields, interpolation.
//! - [`FieldSpace`]: the piecewise constant tangent fields `X_h`: frames, `J`, `M_X`, conversion
//!   to and from one 3D vector per face.
//! - [`HodgeComplex`]: pairs a potential space and a co-potential space over a field space and
//!   hands out `d0`, `d1`, `M0`, `M1`, `M2`.
//! - [`HodgeOperators`]: blanket extension of every [`HodgeComplex`]: divergence and curl (both
//!   families), stiffness matrices, Dirichlet energy `S`, Hodge–Laplacian `L`, biharmonic `B`,
//!   the two eigenproblems of Section 6 and the maps from (co-)potentials to fields.
//!
//! Code downstream (spectral basis, filters, splines) is written against these traits only, so
//! that the conforming and the nonconforming decomposition, and any discretization added later,
//! are interchangeable. `tvf-discretizations` holds the implementations and shows, in its crate
//! docs, how to add a third one.
//!
//! # Units
//! Field coefficients are *pointwise* (a tangent vector per face). Function coefficients are
//! *pointwise* nodal values. A matrix called "integrated" returns values that are integrals over
//! the node's lumped area (multiply a pointwise quantity by the mass to get the integrated one).

mod error;
mod field_space;
mod function_space;
mod hodge_complex;
mod hodge_operators;
pub mod sparse;

pub use error::DiscretizationError;
pub use field_space::{FieldSpace, TangentProjection};
pub use function_space::FunctionSpace;
pub use hodge_complex::HodgeComplex;
pub use hodge_operators::{Eigenproblem, HodgeOperators};

/// Marker in node → component maps for a node that no face uses (an unreferenced vertex).
pub const NO_COMPONENT: usize = usize::MAX;
