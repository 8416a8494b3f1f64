//! Reference checks a complex opts into with `reference = [...]` or `reference_checks = ...` in
//! [`crate::conformance_suite!`] (a built-in catalog entry: its
//! [`catalog_reference_checks`](crate::reference_report::catalog_reference_checks)): explicit
//! formulas and properties that only some discretizations have. Each function runs one check on
//! every mesh of a corpus (the shared meshes included), except [`sphere_spectrum`], which runs
//! on the unit icosphere; [`run_checks`] runs a list of them, given as [`ReferenceCheck`]s.

use crate::algebra_checks::max_abs;
use crate::capability_checks::{check_div_curl_formulas, check_face_fields, check_rotation};
use crate::corpus::{Corpus, CorpusMesh};
use crate::galerkin_mass_checks::check_galerkin_masses;
use crate::reference_formulas::{assert_operator_equals, explicit_stiffness};
use crate::reference_report::ReferenceCheck;
use crate::spectral_checks::check_sphere_spectrum;
use crate::{build, for_each_mesh, Constructor};
use tvf_core::discretization::{HodgeComplex, HodgeOperators, LinearOperator, NodeSpace};
use tvf_core::TriangleMesh;

/// Runs every check of `checks`, in order, on the complexes of `constructor` over `corpus`
/// (naming each on stderr, so that a failing test shows which one failed).
pub fn run_checks(checks: &[ReferenceCheck], constructor: Constructor, corpus: Corpus) {
    for &check in checks {
        eprintln!("reference check {}", check.name());
        let run = match check {
            ReferenceCheck::CotanFormula => cotan_formula,
            ReferenceCheck::PotentialCotanFormula => potential_cotan_formula,
            ReferenceCheck::DivCurlFormulas => div_curl_formulas,
            ReferenceCheck::CoPotentialMasses => co_potential_masses,
            ReferenceCheck::FaceFields => face_fields,
            ReferenceCheck::GalerkinMasses => galerkin_masses,
            ReferenceCheck::Rotation => rotation,
            ReferenceCheck::SphereSpectrum => sphere_spectrum,
        };
        run(constructor, corpus);
    }
}

/// Runs `check` on the complex of `constructor` on every mesh of `corpus`, the shared meshes
/// included.
fn on_every_mesh(
    constructor: Constructor,
    corpus: Corpus,
    check: impl Fn(&(dyn HodgeComplex + 'static), &CorpusMesh),
) {
    for_each_mesh(corpus, true, |mesh| {
        check(build(constructor, mesh).as_ref(), mesh)
    });
}

/// Both stiffness matrices equal their explicit formulas by node kind (relative 1e-10): cotan
/// on vertices (P1, DEC 0-forms), Crouzeix–Raviart on edges, the dual-graph Laplacian on faces
/// (DEC 2-forms). Panics for a space of face frames.
pub fn cotan_formula(constructor: Constructor, corpus: Corpus) {
    on_every_mesh(constructor, corpus, |complex, mesh| {
        check_potential_stiffness_formula(complex, &mesh.mesh);
        check_stiffness_formula(
            "co-potential",
            complex.co_potential_nodes(),
            complex.co_potential_stiffness(),
            &mesh.mesh,
        );
    });
}

/// The potential stiffness `d0ᵀ M1 d0` alone equals its explicit formula by node kind
/// (relative 1e-10): for complexes whose co-potential stiffness has no explicit sparse formula
/// (the mixed RT0–P0 stiffness of Whitney forms with their Galerkin mass).
pub fn potential_cotan_formula(constructor: Constructor, corpus: Corpus) {
    on_every_mesh(constructor, corpus, |complex, mesh| {
        check_potential_stiffness_formula(complex, &mesh.mesh)
    });
}

/// The potential stiffness of `complex` equals the explicit stiffness of its node kind.
fn check_potential_stiffness_formula(complex: &dyn HodgeComplex, mesh: &TriangleMesh) {
    check_stiffness_formula(
        "potential",
        complex.potential_nodes(),
        &LinearOperator::Sparse(complex.potential_stiffness().clone()),
        mesh,
    );
}

/// `stiffness` equals the explicit stiffness of the node kind of `nodes` on `mesh`.
fn check_stiffness_formula(
    which: &str,
    nodes: &NodeSpace,
    stiffness: &LinearOperator,
    mesh: &TriangleMesh,
) {
    let expected = explicit_stiffness(nodes.kind, mesh).unwrap_or_else(|| {
        panic!(
            "{which} space on {}: no explicit stiffness formula",
            nodes.kind.name()
        )
    });
    assert!(max_abs(&expected) > 0.0, "empty explicit stiffness");
    assert_operator_equals(
        &format!("{which} stiffness vs the {} formula", nodes.kind.name()),
        stiffness,
        &expected,
    );
}

/// Every mass is the Galerkin mass of what the complex evaluates and samples
/// ([`check_galerkin_masses`]).
pub fn galerkin_masses(constructor: Constructor, corpus: Corpus) {
    on_every_mesh(constructor, corpus, check_galerkin_masses);
}

/// `J² = −I`, `Jᵀ M1 J = M1`, `J` rotates sampled vectors by +π/2
/// ([`check_rotation`]).
pub fn rotation(constructor: Constructor, corpus: Corpus) {
    on_every_mesh(constructor, corpus, check_rotation);
}

/// Fields are piecewise constant face vectors with `M1 = (A_t, A_t)` ([`check_face_fields`]).
pub fn face_fields(constructor: Constructor, corpus: Corpus) {
    on_every_mesh(constructor, corpus, check_face_fields);
}

/// Divergence and curl of both families equal their explicit formulas
/// ([`check_div_curl_formulas`]).
pub fn div_curl_formulas(constructor: Constructor, corpus: Corpus) {
    on_every_mesh(constructor, corpus, check_div_curl_formulas);
}

/// The co-potential masses partition the area: `1ᵀ M2⁻¹ 1 = area` (relative 1e-12).
pub fn co_potential_masses(constructor: Constructor, corpus: Corpus) {
    on_every_mesh(constructor, corpus, |complex, mesh| {
        let total = complex.m2().inverse().total();
        let area = mesh.mesh.total_area();
        assert!(
            (total - area).abs() <= 1e-12 * area,
            "Σ M2⁻¹ = {total}, the mesh's area is {area}"
        );
    });
}

/// On the unit icosphere(2) (320 faces; Delaunay, so in every corpus) the lowest six
/// eigenvalues of `L` are ≈ 2 and the seventh is above 5 ([`check_sphere_spectrum`]): the
/// complex approximates the smooth Hodge–Laplacian. The corpus is not used.
pub fn sphere_spectrum(constructor: Constructor, _corpus: Corpus) {
    let sphere =
        crate::corpus::CorpusMesh::new("icosphere(2)", tvf_core::generate::icosphere(2), 0);
    check_sphere_spectrum(build(constructor, &sphere).as_ref());
}
