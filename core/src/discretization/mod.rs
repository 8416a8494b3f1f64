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
//! # Adding a discretization
//! Implement [`HodgeComplex`] (usually by assembling spaces, see
//! `tvf_discretizations::FiniteElementComplex::from_spaces`, whose crate docs run a complete
//! example) and every operator of [`HodgeOperators`] follows. The smallest possible variant wraps
//! an existing complex and changes one ingredient, here the co-potential mass `M2`:
//!
//! ```
//! use sprs::CsMat;
//! use tvf_core::discretization::{HodgeComplex, HodgeOperators};
//!
//! /// Any complex with its co-potential inner product scaled by `factor` (so `M2` by 1/factor).
//! struct ScaledCoPotentials<H> {
//!     inner: H,
//!     m2: Vec<f64>,
//! }
//!
//! impl<H: HodgeComplex> ScaledCoPotentials<H> {
//!     fn new(inner: H, factor: f64) -> Self {
//!         let m2 = inner.m2().iter().map(|m| m / factor).collect();
//!         Self { inner, m2 }
//!     }
//! }
//!
//! impl<H: HodgeComplex> HodgeComplex for ScaledCoPotentials<H> {
//!     type Potentials = H::Potentials;
//!     type CoPotentials = H::CoPotentials;
//!     type Fields = H::Fields;
//!     fn name(&self) -> String { format!("{} (scaled co-potentials)", self.inner.name()) }
//!     fn potentials(&self) -> &H::Potentials { self.inner.potentials() }
//!     fn co_potentials(&self) -> &H::CoPotentials { self.inner.co_potentials() }
//!     fn fields(&self) -> &H::Fields { self.inner.fields() }
//!     fn d1(&self) -> &CsMat<f64> { self.inner.d1() }
//!     fn m2(&self) -> &[f64] { &self.m2 }
//!     fn harmonic_dimension(&self) -> usize { self.inner.harmonic_dimension() }
//!     fn has_boundary(&self) -> bool { self.inner.has_boundary() }
//! }
//!
//! /// Written once against the traits: works for the wrapper as for any other complex.
//! fn laplacian_size<H: HodgeComplex>(complex: &H) -> (usize, usize) {
//!     complex.hodge_laplacian().shape()
//! }
//! # fn _compiles<H: HodgeComplex>(h: H) -> (usize, usize) {
//! #     laplacian_size(&ScaledCoPotentials::new(h, 2.0))
//! # }
//! ```
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
