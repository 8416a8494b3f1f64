//! # tvf-tests
//!
//! The conformance suite every discretization gets. Generic checks are written once against the
//! traits of [`tvf_core::discretization`]; the macro [`conformance_suite!`] instantiates all of
//! them for one discretization, over the corpus of [`corpus`], in one line:
//!
//! ```
//! use tvf_discretizations::{Conforming, MassLumping};
//!
//! tvf_tests::conformance_suite!(conforming_barycentric, |mesh| {
//!     Conforming::new(mesh, MassLumping::Barycentric)
//! });
//! # fn main() {}
//! ```
//!
//! The constructor is any `Fn(&SurfaceMesh) -> Result<H, E>` with `H: HodgeComplex` and
//! `E: Debug`. Dense eigenvalue checks run on meshes with `2F ≤` [`corpus::DENSE_LIMIT`]; the
//! kernel dimension on larger and real meshes is checked through the rank of harmonic projections.
#![warn(missing_docs)]

pub mod algebra_checks;
pub mod corpus;
pub mod decomposition_checks;
pub mod dense;
pub mod reference_formulas;
pub mod spectral_checks;
mod suite_macro;

pub use proptest;
pub use tvf_core;
pub use tvf_discretizations;

/// Identity that fixes a closure's signature to `Fn(&SurfaceMesh) -> Result<H, E>` (so that
/// `|mesh| Conforming::new(mesh, ...)` needs no type annotation inside the macro).
pub fn constructor<H, E, F>(f: F) -> F
where
    F: Fn(&tvf_core::SurfaceMesh) -> Result<H, E>,
{
    f
}

/// Builds a complex with `constructor`, panicking with the mesh name on error (test helper).
pub fn build_complex<H, E, F>(constructor: &F, mesh: &corpus::CorpusMesh) -> H
where
    E: std::fmt::Debug,
    F: Fn(&tvf_core::SurfaceMesh) -> Result<H, E>,
{
    constructor(&mesh.mesh).unwrap_or_else(|e| panic!("{}: construction failed: {e:?}", mesh.name))
}

/// Runs `check` on every mesh of the generated corpus (and, if `with_shared`, the real meshes),
/// naming the mesh in any failure.
pub fn for_each_mesh(with_shared: bool, mut check: impl FnMut(&corpus::CorpusMesh)) {
    let mut meshes = corpus::generated_corpus();
    if with_shared {
        meshes.extend(corpus::shared_corpus());
    }
    for mesh in &meshes {
        eprintln!("checking {} ({} faces)", mesh.name, mesh.mesh.face_count());
        check(mesh);
    }
}
