//! # tvf-discretizations
//!
//! The two discretizations of the paper behind the traits of
//! [`tvf_core::discretization`]: the function spaces [`LagrangeP1`] (`S_h`, vertices) and
//! [`CrouzeixRaviart`] (`S*_h`, edge midpoints), the face fields [`FaceFields`] (`X_h`), the
//! mass lumpings [`MassLumping`], the Hodge complexes [`Conforming`] and [`Nonconforming`], and
//! the Hodge decomposition [`HodgeDecomposer`] for any complex.
//!
//! ```
//! use tvf_core::discretization::{HodgeComplex, HodgeOperators};
//! use tvf_core::generate::icosphere;
//! use tvf_discretizations::{Conforming, HodgeDecomposer, MassLumping};
//!
//! let mesh = icosphere(1); // 42 vertices, 120 edges, 80 faces
//! let complex = Conforming::new(&mesh, MassLumping::Barycentric)?;
//! assert_eq!(complex.d0().shape(), (160, 42));   // G: 2F × V
//! assert_eq!(complex.d1().shape(), (120, 160));  // G*ᵀ J M_X: E × 2F
//! let laplacian = complex.hodge_laplacian();     // L = M_X⁻¹ S, 2F × 2F
//! assert_eq!(laplacian.shape(), (160, 160));
//!
//! // Decompose a field: on a sphere there are no harmonic fields.
//! let field: Vec<f64> = (0..160).map(|i| (i as f64 * 0.37).sin()).collect();
//! let parts = HodgeDecomposer::new(&complex)?.decompose(&field)?;
//! let harmonic_norm = complex.field_inner(&parts.harmonic, &parts.harmonic).sqrt();
//! assert!(harmonic_norm < 1e-10);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Adding a third discretization
//! A discretization is one implementation of [`HodgeComplex`] (or of [`FunctionSpace`] /
//! [`FieldSpace`](tvf_core::discretization::FieldSpace), assembled with
//! [`FiniteElementComplex::from_spaces`]); every operator then comes from the blanket
//! [`HodgeOperators`](tvf_core::discretization::HodgeOperators), and the conformance suite in
//! `tests/` checks it with one line, `conformance_suite!(my_name, |mesh| MyComplex::new(mesh));`.
//!
//! Example: the conforming complex with a different P1 mass, here lumped by *uniform* weights
//! (every vertex gets the mean vertex area): a new potential space wrapping [`LagrangeP1`].
//!
//! ```
//! use sprs::CsMat;
//! use tvf_core::discretization::{FunctionSpace, HodgeComplex, HodgeOperators};
//! use tvf_core::generate::icosphere;
//! use tvf_discretizations::{
//!     CrouzeixRaviart, FaceFields, FiniteElementComplex, LagrangeP1, MassLumping, Topology,
//! };
//!
//! /// P1 with every vertex weighted by the mean vertex area.
//! struct UniformP1 {
//!     inner: LagrangeP1,
//!     mass: Vec<f64>,
//! }
//!
//! impl UniformP1 {
//!     fn new(inner: LagrangeP1) -> Self {
//!         let mean = inner.mass().iter().sum::<f64>() / inner.dimension() as f64;
//!         let mass = vec![mean; inner.dimension()];
//!         Self { inner, mass }
//!     }
//! }
//!
//! impl FunctionSpace for UniformP1 {
//!     fn name(&self) -> &str { "P1, uniform mass" }
//!     fn dimension(&self) -> usize { self.inner.dimension() }
//!     fn mass(&self) -> &[f64] { &self.mass }
//!     fn gradient(&self) -> &CsMat<f64> { self.inner.gradient() }
//!     fn interpolation_weights(&self, face: usize, b: [f64; 3]) -> Vec<(usize, f64)> {
//!         self.inner.interpolation_weights(face, b)
//!     }
//!     fn node_positions(&self) -> Vec<[f64; 3]> { self.inner.node_positions() }
//!     fn node_components(&self) -> &[usize] { self.inner.node_components() }
//!     fn component_count(&self) -> usize { self.inner.component_count() }
//! }
//!
//! let mesh = icosphere(2);
//! let lumping = MassLumping::Barycentric;
//! let complex = FiniteElementComplex::from_spaces(
//!     "conforming, uniform P1 mass",
//!     UniformP1::new(LagrangeP1::new(&mesh, lumping)?),
//!     CrouzeixRaviart::new(&mesh, lumping)?,
//!     FaceFields::new(&mesh)?,
//!     Topology::of(&mesh),
//! )?;
//! // Every derived operator is available; d1 · d0 = 0 still holds (it does not involve M0).
//! let d1d0 = &*complex.d1() * &*complex.d0();
//! assert!(d1d0.data().iter().all(|x| x.abs() < 1e-12));
//! let s = complex.dirichlet_energy();
//! assert_eq!(s.shape(), (640, 640));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

mod crouzeix_raviart;
mod error;
mod face_fields;
pub mod face_geometry;
mod finite_element_complex;
mod gradient_assembly;
mod hodge_decomposition;
mod lagrange_p1;
mod mass_lumping;
mod pinned_poisson;

pub use crouzeix_raviart::CrouzeixRaviart;
pub use error::DecompositionError;
pub use face_fields::FaceFields;
pub use finite_element_complex::{Conforming, FiniteElementComplex, Nonconforming, Topology};
pub use hodge_decomposition::{HodgeDecomposer, HodgeParts};
pub use lagrange_p1::LagrangeP1;
pub use mass_lumping::MassLumping;
pub use pinned_poisson::PinnedPoisson;
