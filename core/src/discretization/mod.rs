//! The seam: what a discretization of tangential vector fields provides — five matrices and a few
//! small capabilities — and every operator of the paper derived once from them.
//!
//! The paper's discrete Hodge decomposition is a short cochain complex with masses
//! (`docs/architecture.md`, `docs/conventions.md`):
//!
//! ```text
//! potentials --d0--> fields --d1--> co-potentials,      d1 · d0 = 0
//!     M0              M1              M2 (acts on d1's integrated output)
//! ```
//!
//! - [`HodgeComplex`]: its [`ComplexParts`] — the five matrices `d0`, `d1`, `M0`, `M1`, `M2`
//!   (each [`Mass`] a symmetric positive definite operator, diagonal or sparse), the nodes of the three spaces ([`NodeSpace`]), the topology, a stable
//!   id — and the optional
//!   capabilities [`FieldSampling`] (fields as 3D vectors at points), [`FieldRotation`] (`J`,
//!   which gives the other family of divergence and curl) and [`PointEvaluation`] (potentials at
//!   points). Object safe: catalogs hand out `Box<dyn HodgeComplex>`.
//! - [`HodgeOperators`]: blanket extension of every complex: divergence and curl, stiffness
//!   matrices, Dirichlet energy `S`, Hodge–Laplacian `L`, biharmonic `B`, the two scalar
//!   eigenproblems of Section 6 and the maps from (co-)potentials to fields — all from the five
//!   matrices, computed once and cached in the complex's [`OperatorCache`], each a
//!   [`LinearOperator`]: a sparse matrix where every mass involved is diagonal, else a
//!   composition applied through sparse products and mass solves.
//! - [`MatrixHash`]: hashes of the five matrices and of the nodes the boundary condition fixes
//!   ([`HodgeComplex::matrix_hash`], computed once per complex), which key basis files and
//!   cached bases so that a basis is never reused for changed matrices.
//!
//! Code downstream (spectral basis, filters, splines, design, rendering, the editor) is written
//! against these traits only. `tvf-discretizations` holds the implementations and the catalog.
//!
//! # Adding a discretization
//! Build the five matrices into [`ComplexParts`] (which checks their shapes) and implement
//! [`HodgeComplex`] by handing them out, plus the capabilities you offer; every operator of
//! [`HodgeOperators`] follows. The smallest variant wraps an existing complex and changes one
//! ingredient, here the co-potential mass `M2` (scaled by `1/factor`). New parts come with a
//! fresh [`OperatorCache`], so every derived operator — `L`, `S` and both eigenproblems alike —
//! sees the new `M2`; the conformance suite in `tests/` runs this very wrapper.
//!
//! ```
//! use tvf_core::discretization::*;
//!
//! /// Any complex with its co-potential inner product scaled by `factor` (so `M2` by 1/factor).
//! struct ScaledCoPotentials<H> {
//!     inner: H,
//!     parts: ComplexParts,
//! }
//!
//! impl<H: HodgeComplex> ScaledCoPotentials<H> {
//!     fn new(inner: H, factor: f64) -> Result<Self, DiscretizationError> {
//!         let m2 = inner.m2().scaled("M2 (scaled)", 1.0 / factor);
//!         let id = format!("{}-scaled-co-potentials", inner.id());
//!         let parts = inner.parts().with_co_potential_mass(id, m2)?;
//!         Ok(Self { inner, parts })
//!     }
//! }
//!
//! impl<H: HodgeComplex> HodgeComplex for ScaledCoPotentials<H> {
//!     fn parts(&self) -> &ComplexParts { &self.parts }
//!     fn sampling(&self) -> Option<&dyn FieldSampling> { self.inner.sampling() }
//! }
//!
//! /// Written once against the traits: works for the wrapper as for any other complex.
//! fn laplacian_size(complex: &dyn HodgeComplex) -> (usize, usize) {
//!     complex.hodge_laplacian().shape()
//! }
//! # fn _compiles<H: HodgeComplex>(h: H) -> (usize, usize) {
//! #     laplacian_size(&ScaledCoPotentials::new(h, 2.0).unwrap())
//! # }
//! ```
//!
//! # Units
//! Potentials are **pointwise** nodal values. Field coefficients are what the discretization says
//! (a tangent vector per face in its frame, a 1-form's integral along each edge); the sampling
//! capability turns them into pointwise 3D vectors. A matrix called "integrated" returns values
//! that are integrals over the node's lumped area.

mod capabilities;
mod complex_parts;
mod error;
mod face_frames;
mod hodge_complex;
mod hodge_operators;
mod linear_operator;
mod mass;
mod matrix_hash;
mod nodes;
mod operator_cache;
pub mod sparse;

pub use capabilities::{
    check_face_vectors, check_length, FieldRotation, FieldSampling, PointEvaluation,
    SamplingReproduction, TangentProjection,
};
pub use complex_parts::ComplexParts;
pub use error::DiscretizationError;
pub use face_frames::FaceFrames;
pub use hodge_complex::HodgeComplex;
pub use hodge_operators::{all_sparse, EigenStiffness, Eigenproblem, HodgeOperators};
pub use linear_operator::{Composition, Factor, LinearOperator};
pub use mass::{Mass, MassForm, MassStorage};
pub use matrix_hash::MatrixHash;
pub use nodes::{BoundaryCondition, ComplexTopology, NodeKind, NodeSpace};
pub use operator_cache::OperatorCache;

/// Marker in node → component maps for a node that no face uses (an unreferenced vertex).
pub const NO_COMPONENT: usize = usize::MAX;
