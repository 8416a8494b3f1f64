//! # tvf-discretizations
//!
//! Every discretization tvf ships, behind the seam of [`tvf_core::discretization`], and the
//! [`Catalog`] that lists them ([`Catalog::builtin`]; a program adds its own entries):
//!
//! - the finite-element complexes of the paper, [`Conforming`] and [`Nonconforming`]
//!   ([`FiniteElementComplex`] over the function spaces [`LagrangeP1`] (`S_h`, vertices) and
//!   [`CrouzeixRaviart`] (`S*_h`, edge midpoints) and the face fields [`FaceFields`] (`X_h`),
//!   with a [`MassLumping`], or with the consistent P1 mass [`consistent_p1_mass`] where P1
//!   appears: [`Conforming::consistent`] (`M0`), [`Nonconforming::consistent`] (`M2`, stored as
//!   its sparse inverse);
//! - primal forms sampled by Whitney interpolation ([`WhitneySampling`]), with two kinds of
//!   masses: discrete exterior calculus, [`DecComplex`] (diagonal Hodge stars, Delaunay meshes),
//!   and [`WhitneyGalerkin`] (the consistent P1 mass, the Whitney mass [`whitney_mass`] and
//!   `1/area`: Galerkin masses, every mesh);
//! - every triangle entry on the intrinsic Delaunay triangulation of the mesh
//!   ([`CatalogEntry::on_intrinsic_delaunay`]), built from its edge lengths: [`IntrinsicDec`],
//!   [`IntrinsicWhitneyGalerkin`], [`IntrinsicFiniteElement`], each face laid out as a
//!   [`PlanarTriangle`], fields sampled on the input faces through the correspondence;
//! - [`MatrixComplex`]: a complex from five matrices assembled elsewhere (checked);
//! - the Hodge decomposition [`HodgeDecomposer`] of any complex.
//!
//! Masses are [`Mass`](tvf_core::discretization::Mass)es, each stored in the form in which it is
//! sparse: a diagonal (every lumped mass, DEC's stars, `M2 = 1/area`), a sparse matrix (the
//! consistent P1 mass as `M0`, the Whitney mass), or the sparse inverse (the consistent P1
//! co-potential mass of `nonconforming-consistent`, whose `M2` is dense).
//!
//! ```
//! use tvf_core::discretization::HodgeOperators;
//! use tvf_core::generate::icosphere;
//! use tvf_discretizations::{catalog_entry, HodgeDecomposer};
//!
//! let mesh = icosphere(1); // 42 vertices, 120 edges, 80 faces
//! let complex = catalog_entry("conforming-barycentric")?.build(&mesh)?;
//! assert_eq!(complex.d0().shape(), (160, 42));   // G: 2F × V
//! assert_eq!(complex.d1().shape(), (120, 160));  // G*ᵀ J M_X: E × 2F
//! assert_eq!(complex.hodge_laplacian().shape(), (160, 160)); // L = M_X⁻¹ S
//!
//! // The same code on DEC 1-forms: fields are edge values.
//! let dec = catalog_entry("dec-circumcentric")?.build(&mesh)?;
//! assert_eq!(dec.d0().shape(), (120, 42));       // E × V incidence
//!
//! // Decompose a field: on a sphere there are no harmonic fields.
//! let field: Vec<f64> = (0..160).map(|i| (i as f64 * 0.37).sin()).collect();
//! let parts = HodgeDecomposer::new(complex.as_ref())?.decompose(&field)?;
//! let harmonic_norm = complex.field_inner(&parts.harmonic, &parts.harmonic).sqrt();
//! assert!(harmonic_norm < 1e-10);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Adding a discretization
//! Build the five matrices and implement [`HodgeComplex`](tvf_core::discretization::HodgeComplex)
//! (see [`WhitneyGalerkin`] for a complete example: its three masses, about 115 lines, over the
//! incidences, node spaces and Whitney sampling it shares with [`DecComplex`]), then make it a
//! [`CatalogEntry`]: one more entry in `builtin_catalog.rs` for tvf's own (every command, the
//! editor and papers/ read [`Catalog::builtin`], and the conformance suite in
//! `conformance/tests/` fails until the entry has its suite line), or, in a crate of your own,
//! `Catalog::builtin().with(entry)?` handed to `tvf_cli::run` (the example crate
//! `examples/own-discretization` does this). Finite-element
//! variants can reuse [`FiniteElementComplex::from_spaces`] with a new [`FunctionSpace`]:
//!
//! ```
//! use sprs::CsMat;
//! use tvf_core::discretization::{HodgeComplex, HodgeOperators, NodeKind};
//! use tvf_core::generate::icosphere;
//! use tvf_discretizations::{
//!     CrouzeixRaviart, FaceFields, FiniteElementComplex, FunctionSpace, LagrangeP1, MassLumping,
//!     PaperSpace,
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
//!     fn node_kind(&self) -> NodeKind { NodeKind::Vertices }
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
//!     "conforming-uniform-p1",
//!     &mesh,
//!     UniformP1::new(LagrangeP1::new(&mesh, lumping)?),
//!     CrouzeixRaviart::new(&mesh, lumping)?,
//!     FaceFields::new(&mesh)?,
//! )?;
//! // Every derived operator is available; d1 · d0 = 0 still holds (it does not involve M0).
//! let d1d0 = &*complex.d1() * &*complex.d0();
//! assert!(d1d0.data().iter().all(|x| x.abs() < 1e-12));
//! assert_eq!(complex.dirichlet_energy().shape(), (640, 640));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod boundary_conditions;
mod builtin_catalog;
mod catalog;
mod catalog_entry;
mod catalog_ids;
mod complex_id;
mod consistent_mass;
mod crouzeix_raviart;
mod dec_complex;
mod edge_averages;
mod error;
mod face_fields;
pub mod face_geometry;
mod finite_element_complex;
mod function_space;
mod gradient_assembly;
mod hodge_decomposition;
mod intrinsic_dec;
mod intrinsic_delaunay;
mod intrinsic_face_sampling;
mod intrinsic_finite_element;
mod intrinsic_input_faces;
mod intrinsic_nodes;
mod intrinsic_primal_forms;
mod intrinsic_sampling;
mod intrinsic_whitney_galerkin;
mod intrinsic_whitney_sampling;
mod lagrange_p1;
mod mass_lumping;
mod matrix_complex;
pub mod matrix_complex_nodes;
mod mixed_poisson;
mod nodal_evaluation;
mod paper_complexes;
mod pinned_poisson;
mod planar_triangle;
mod polygon_dec;
mod polygon_operators;
mod polygon_sampling;
mod primal_form_complex;
mod primal_forms;
mod sampled_complex;
mod whitney_galerkin;
mod whitney_mass;
mod whitney_sampling;

pub use boundary_conditions::{
    boundary_nodes, component_boundary_loops, drop_columns, drop_rows, mesh_topology,
    with_dirichlet_boundary,
};
pub use builtin_catalog::polygon_dec_entry;
pub use catalog::{
    build_complex, builtin_catalog, catalog_entry, default_discretization, is_kebab_case, Catalog,
    CatalogBuildError, CatalogError, UnknownDiscretization, DEFAULT_DISCRETIZATION,
    DEFAULT_POLYGON_DISCRETIZATION,
};
pub use catalog_entry::{BoxedComplex, CatalogEntry, EntryConstructor, ANY_MESH};
pub use catalog_ids::{
    parse_boundary_condition, requested_catalog_id, DEFAULT_DECOMPOSITION_PART, DEFAULT_MASS_PART,
};
pub use complex_id::{complex_id, split_complex_id};
pub use consistent_mass::consistent_p1_mass;
pub use crouzeix_raviart::CrouzeixRaviart;
pub use dec_complex::{edge_hodge_star, DecComplex, HodgeStars, DELAUNAY_TOLERANCE};
pub use error::DecompositionError;
pub use face_fields::FaceFields;
pub use finite_element_complex::{Conforming, FiniteElementComplex, Nonconforming};
pub use function_space::FunctionSpace;
pub use hodge_decomposition::{HodgeDecomposer, HodgeParts};
pub use intrinsic_dec::IntrinsicDec;
pub use intrinsic_delaunay::{
    intrinsic_entry_id, parse_intrinsic_delaunay, split_intrinsic_id, IntrinsicConstructor,
    IntrinsicDelaunay, IntrinsicInput,
};
pub use intrinsic_face_sampling::{IntrinsicFaceSampling, IntrinsicFaceVectors};
pub use intrinsic_finite_element::{ElementFamily, IntrinsicFiniteElement};
pub use intrinsic_primal_forms::IntrinsicPrimalFormComplex;
pub use intrinsic_sampling::{IntrinsicEvaluation, IntrinsicReconstruction, IntrinsicSampling};
pub use intrinsic_whitney_galerkin::IntrinsicWhitneyGalerkin;
pub use intrinsic_whitney_sampling::{IntrinsicWhitneyForms, IntrinsicWhitneySampling};
pub use lagrange_p1::LagrangeP1;
pub use mass_lumping::MassLumping;
pub use matrix_complex::{ComplexMatrices, MatrixComplex, MatrixSampling, COMPLEX_TOLERANCE};
pub use matrix_complex_nodes::{FixedNodes, StatedNodeKinds};
pub use nodal_evaluation::NodalEvaluation;
pub use paper_complexes::{PaperPair, PaperSpace, SpaceMasses};
pub use pinned_poisson::PinnedPoisson;
pub use planar_triangle::PlanarTriangle;
pub use polygon_dec::{polygon_dec_id, PolygonDec, DEFAULT_STABILISATION};
pub use polygon_operators::PolygonOperators;
pub use polygon_sampling::{PolygonEvaluation, PolygonSampling};
pub use primal_form_complex::{inverse_face_areas, PrimalFormComplex};
pub use primal_forms::{PrimalFormEvaluation, PrimalForms};
pub use sampled_complex::SampledComplex;
pub use whitney_galerkin::{GalerkinMasses, WhitneyGalerkin};
pub use whitney_mass::whitney_mass;
pub use whitney_sampling::WhitneySampling;
