//! # tvf-conformance
//!
//! The conformance suite every discretization gets, as a library: the workspace's tests, the
//! Python package's `tvf.check` and crates of your own run it. Checks are written once against the seam of
//! [`tvf_core::discretization`] (`&dyn HodgeComplex` or `H: HodgeComplex + ?Sized`), in two
//! kinds:
//!
//! - **core checks** ([`suite`]) every complex must pass: `d1 d0 = 0`; shapes, nodes and
//!   masses (positive diagonals, or sparse matrices positive definite on the free nodes) with
//!   `1ᵀ M0 1 = area`; `S`, `B` and both stiffness matrices symmetric and positive
//!   semi-definite; `dim ker L = 2g` per component; the Hodge decomposition (`M1`-orthogonal
//!   parts summing back, the integrable part curl-free, the co-integrable part divergence-free);
//!   Lemma 1 eigenfields; the spectrum of `L` as the union of the two scalar spectra; a complete
//!   orthonormal eigenfield basis; sampling and point evaluation where offered; invariance under
//!   rigid motions and on jittered meshes (proptest);
//! - **accuracy checks** ([`accuracy`]) every builder of complexes gets by default, whatever its
//!   origin: consistency (patch) tests of linear functions on flat and curved patches
//!   ([`consistency_checks`]) and convergence of the lowest eigenvalues of both families on
//!   regular and jittered refinements of the sphere and the hemisphere, observed order ≥ 1.5
//!   ([`convergence_checks`]); what an entry lacks the capability for is reported as not
//!   applicable;
//! - **reference checks** ([`reference`](mod@reference)) a complex opts into: `cotan_formula` (stiffness
//!   matrices against the cotan, Crouzeix–Raviart or dual-graph formulas) or
//!   `potential_cotan_formula` (the potential stiffness alone), `rotation` (`J² = −I`,
//!   `Jᵀ M1 J = M1`), `face_fields`, `div_curl_formulas` (both families of divergence and curl
//!   against explicit sums), `co_potential_masses` (`1ᵀ M2⁻¹ 1 = area`), `galerkin_masses`
//!   (every mass the `L²` Gram matrix of what the complex evaluates and samples) and
//!   `sphere_spectrum` (convergence to `l(l+1)` on the unit sphere).
//!
//! Masses are [`tvf_core::discretization::Mass`]es and derived operators
//! [`tvf_core::discretization::LinearOperator`]s: the checks apply them, form them densely on
//! small meshes ([`dense`]: `LinearOperator::to_dense`, a mass applied to the identity) and solve
//! the generalized problems as symmetric-definite pencils (a Cholesky factor of a non-diagonal
//! mass), restricted to the free nodes of each space.
//!
//! Each core check measures first and asserts on [`check_outcome::CheckOutcome`]s;
//! [`check_report::core_check_report`] returns those outcomes as a report instead, for complexes
//! built elsewhere (the Python package's `tvf.check`); [`check_run_report`] words a run's
//! outcomes as text lines and JSON keys (`tvf check`).
//!
//! Property-based checking: [`strategies`] draws small mesh descriptions (genus 0–5, surfaces
//! with boundary, several components, jitter, slivers, rigid motions, Delaunay variants) that
//! proptest shrinks; [`property_runner::run_property`] runs the core checks and the measured
//! reference checks ([`reference_report`]) of a builder on `N` of them and shrinks a failure to a
//! minimal failing mesh (`tvf check`, the Python package's `tvf.check` with a builder).
//!
//! Polygon meshes: an entry that accepts them (`polygon-dec`) is also checked on the polygon
//! corpus ([`polygon_corpus`]: quad tori, cube-spheres, duals of triangle meshes, quad splits of
//! genus-`g` surfaces, jittered non-planar polygons, holes, two components) and on generated
//! polygon meshes ([`strategies::polygon_spec`], [`property_runner::run_polygon_property`]) by
//! [`polygon_suite`], with sampling and point evaluation checked as such an entry states them
//! ([`polygon_capability_checks`]); an entry that needs triangles must refuse them.
//!
//! The macro [`conformance_suite!`] instantiates the core suite (and any reference checks) for
//! one constructor in one line, over a [`corpus::Corpus`]: the general one, or the Delaunay one
//! for discretizations that need `cot α + cot β > 0`.
//!
//! ```
//! use tvf_discretizations::{catalog_entry, Conforming, MassLumping};
//! use tvf_conformance::corpus::Corpus;
//!
//! // Every core check, on the general corpus.
//! tvf_conformance::conformance_suite!(conforming_barycentric, |mesh| {
//!     Conforming::new(mesh, MassLumping::Barycentric)
//! });
//!
//! // A boxed complex from the catalog, on the Delaunay corpus, with two reference checks.
//! tvf_conformance::conformance_suite!(
//!     dec_circumcentric,
//!     |mesh| catalog_entry("dec-circumcentric").expect("in the catalog").build(mesh),
//!     corpus = Corpus::Delaunay,
//!     reference = [cotan_formula, co_potential_masses],
//! );
//! # fn main() {}
//! ```
//!
//! The constructor is any `Fn(&TriangleMesh) -> Result<H, E>` with `E: Debug` and `H` either a
//! `HodgeComplex + 'static` or a `Box<dyn HodgeComplex>`. A catalog entry (a
//! [`CatalogEntry`], built-in or of a crate of your own) gets the suite on its corpus and the
//! suite on meshes with boundary for both boundary conditions ([`open_suite`]) in one line:
//!
//! ```
//! use tvf_core::discretization::BoundaryCondition;
//! use tvf_discretizations::{BoxedComplex, CatalogEntry, Nonconforming, MassLumping};
//!
//! fn my_entry() -> CatalogEntry {
//!     CatalogEntry::new(
//!         "nonconforming-voronoi",
//!         "the nonconforming decomposition, Voronoi masses",
//!         |mesh, boundary| -> Result<BoxedComplex, _> {
//!             Ok(Box::new(Nonconforming::with_boundary(mesh, MassLumping::Voronoi, boundary)?))
//!         },
//!     )
//!     .with_boundary_condition(BoundaryCondition::Tangential, "P1 co-potentials zero")
//! }
//!
//! tvf_conformance::conformance_suite!(my_discretization, entry = my_entry());
//! # fn main() {}
//! ```
//!
//! Every built-in entry has its suite line in
//! `conformance/tests/conformance/catalog_suites.rs` through [`catalog_suites!`], which fails
//! when one is missing.
//! Dense eigenvalue checks run when `n1 ≤` [`corpus::DENSE_LIMIT`], dense eigenvector checks when
//! `n1 ≤` [`corpus::EIGENVECTOR_LIMIT`]; on larger and real meshes the kernel dimension is checked
//! through the rank of harmonic projections (the suite) and, in [`check_report`] (`tvf check`,
//! `tvf.check`), every eigenvalue check through the sparse eigensolver and inertia counts
//! ([`inertia_checks`]: semi-definiteness, the kernel, the spectrum union as counting functions,
//! Lemma 1 on the lowest eigenpairs; for complexes with diagonal masses).
//!
//! What the checks of one complex compute alike — its dense spectra, `S` and `B` formed densely,
//! the eigenfields of Lemma 1, the prefactored Hodge decomposer — is computed once per complex
//! and shared ([`check_cache::CheckCache`]); the convergence checks take the lowest eigenvalues
//! from the sparse eigensolver ([`lowest_eigenvalues`]); the Delaunay flips of the corpora and
//! strategies are updated edge by edge ([`lawson_flips`]). Where the test binary's time goes:
//! `docs/performance.md`, "The conformance tests".
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod accuracy;
pub mod accuracy_meshes;
pub mod algebra_checks;
pub mod capability_checks;
pub mod check_cache;
pub mod check_outcome;
pub mod check_report;
pub mod check_run_report;
pub mod consistency_checks;
pub mod convergence_checks;
pub mod corpus;
pub mod decomposition_checks;
pub mod dense;
pub mod galerkin_mass_checks;
pub mod inertia_checks;
pub mod lawson_flips;
pub mod lowest_eigenvalues;
pub mod open_suite;
pub mod polygon_capability_checks;
pub mod polygon_corpus;
pub mod polygon_operations;
pub mod polygon_suite;
pub mod property_runner;
pub mod reference;
pub mod reference_formulas;
pub mod reference_report;
pub mod scaled_co_potentials;
pub mod spectral_checks;
pub mod strategies;
pub mod suite;
mod suite_macro;

pub use proptest;
pub use tvf_core;
pub use tvf_discretizations;

use corpus::{Corpus, CorpusMesh};
use tvf_core::TriangleMesh;
use tvf_discretizations::{BoxedComplex, CatalogEntry};

/// How the suite builds a complex: the constructor of a suite line, its result boxed and its
/// error formatted.
pub type Constructor<'a> = &'a dyn Fn(&TriangleMesh) -> Result<BoxedComplex, String>;

/// Identity that fixes a closure's signature to `Fn(&TriangleMesh) -> Result<H, E>` (so that
/// `|mesh| Conforming::new(mesh, ...)` needs no type annotation inside the macro).
pub fn constructor<H, E, F>(f: F) -> F
where
    F: Fn(&TriangleMesh) -> Result<H, E>,
{
    f
}

/// Builds the complex of a corpus mesh, panicking with the mesh's name on error.
pub fn build(constructor: Constructor, mesh: &CorpusMesh) -> BoxedComplex {
    constructor(&mesh.mesh).unwrap_or_else(|e| panic!("{}: construction failed: {e}", mesh.name))
}

/// The built-in catalog entry `id` (the suite lines of [`catalog_suites!`]); panics with the
/// known ids on an id the built-in catalog does not know.
pub fn builtin_entry(id: &str) -> CatalogEntry {
    tvf_discretizations::catalog_entry(id)
        .unwrap_or_else(|e| panic!("{e}"))
        .clone()
}

/// Fails unless `covered` (the ids with a suite line) lists every id of the built-in catalog
/// exactly once and nothing else.
pub fn assert_catalog_covered(covered: &[&str]) {
    let ids: Vec<&str> = tvf_discretizations::builtin_catalog().ids().collect();
    let missing: Vec<&str> = ids
        .iter()
        .copied()
        .filter(|id| !covered.contains(id))
        .collect();
    assert!(
        missing.is_empty(),
        "catalog entries without a conformance suite line: {missing:?}"
    );
    let unknown: Vec<&str> = covered
        .iter()
        .copied()
        .filter(|id| !ids.contains(id))
        .collect();
    assert!(
        unknown.is_empty(),
        "suite lines for unknown ids: {unknown:?}"
    );
    for id in covered {
        let lines = covered.iter().filter(|x| *x == id).count();
        assert_eq!(lines, 1, "{id} has {lines} suite lines");
    }
}

/// Runs `check` on every mesh of `corpus` (and, if `with_shared`, the shared meshes that are
/// present), naming the mesh on stderr so that a failure can be traced to it.
pub fn for_each_mesh(corpus: Corpus, with_shared: bool, mut check: impl FnMut(&CorpusMesh)) {
    for mesh in &corpus.meshes(with_shared) {
        eprintln!("checking {} ({} faces)", mesh.name, mesh.mesh.face_count());
        check(mesh);
    }
}

/// Boxing of a suite line's complex, whether the constructor returns a concrete complex or
/// already a `Box<dyn HodgeComplex>` (method resolution picks [`__private::AlreadyBoxed`] for the
/// latter and [`__private::NeedsBox`] otherwise; used by the macros only).
#[doc(hidden)]
pub mod __private {
    use std::cell::RefCell;
    use tvf_core::discretization::HodgeComplex;
    use tvf_discretizations::BoxedComplex;

    /// A built complex waiting to be boxed.
    pub struct Boxing<T>(RefCell<Option<T>>);

    impl<T> Boxing<T> {
        /// Holds `value`.
        pub fn new(value: T) -> Self {
            Self(RefCell::new(Some(value)))
        }

        fn take(&self) -> T {
            self.0.borrow_mut().take().expect("boxed once")
        }
    }

    /// Chosen when the constructor returns a `Box<dyn HodgeComplex>`.
    pub trait AlreadyBoxed {
        /// The box itself.
        fn boxed(&self) -> BoxedComplex;
    }

    impl AlreadyBoxed for Boxing<BoxedComplex> {
        fn boxed(&self) -> BoxedComplex {
            self.take()
        }
    }

    /// Chosen when the constructor returns a concrete complex.
    pub trait NeedsBox {
        /// The complex, boxed.
        fn boxed(&self) -> BoxedComplex;
    }

    impl<H: HodgeComplex + 'static> NeedsBox for &Boxing<H> {
        fn boxed(&self) -> BoxedComplex {
            Box::new(self.take())
        }
    }
}
