//! Every built-in triangle entry on the intrinsic Delaunay triangulation (`ENTRY+intrinsic-delaunay`
//! and `…-refine`): the core checks of the suite (`d1 d0 = 0`, positive definite masses summing
//! to the area, symmetric and positive semidefinite operators, the Hodge decomposition, a kernel
//! of the harmonic dimension `2g` or `2g + b − 1`, the spectrum as the union of the scalar
//! spectra, Lemma 1) on generated meshes, closed and with boundary under both conditions,
//! jittered and therefore mostly not Delaunay, shrinking a failure to a minimal mesh. DEC refines
//! (after flips alone its `⋆1` may be zero on cocircular or boundary edges, which it refuses).

use tvf_conformance::property_runner::{run_property, PropertyRequest};
use tvf_conformance::strategies::{mesh_specs, MeshNeeds};
use tvf_conformance::suite::property_cases;
use tvf_core::discretization::BoundaryCondition;
use tvf_core::TriangleMesh;
use tvf_discretizations::{catalog_entry, IntrinsicDelaunay};

/// Runs the core checks on the entry `id` with the intrinsic modifier `mode` under each boundary
/// condition, on `cases` generated meshes each.
fn passes_the_core_checks(id: &str, mode: IntrinsicDelaunay, cases: u32) {
    let entry = catalog_entry(id)
        .expect("built in")
        .on_intrinsic_delaunay(mode);
    for boundary in BoundaryCondition::ALL {
        let builder =
            |mesh: &TriangleMesh| entry.build_with(mesh, boundary).map_err(|e| e.to_string());
        let request = PropertyRequest::new(property_cases(cases), 43, MeshNeeds::default());
        let report = run_property(&builder, &request, &|_| {});
        if let Some(aborted) = report.aborted {
            panic!("{} ({boundary:?}): the run stopped: {aborted}", entry.id());
        }
        if let Some(counterexample) = report.counterexample {
            panic!(
                "{} ({boundary:?}): minimal failing mesh ({} faces): {}\n{}",
                entry.id(),
                counterexample.mesh.mesh.face_count(),
                counterexample.mesh.name,
                counterexample.report.failure_lines().join("\n")
            );
        }
    }
}

/// The entries other than DEC, with flips only and with refinement.
fn with_both_modes(id: &str) {
    for mode in IntrinsicDelaunay::ALL {
        passes_the_core_checks(id, mode, 6);
    }
}

#[test]
fn conforming_barycentric() {
    with_both_modes("conforming-barycentric");
}

#[test]
fn conforming_voronoi() {
    with_both_modes("conforming-voronoi");
}

#[test]
fn conforming_consistent() {
    with_both_modes("conforming-consistent");
}

#[test]
fn nonconforming_barycentric() {
    with_both_modes("nonconforming-barycentric");
}

#[test]
fn nonconforming_voronoi() {
    with_both_modes("nonconforming-voronoi");
}

#[test]
fn nonconforming_consistent() {
    with_both_modes("nonconforming-consistent");
}

#[test]
fn whitney_galerkin() {
    with_both_modes("whitney-galerkin");
}

#[test]
fn dec_refined() {
    for id in ["dec-barycentric", "dec-circumcentric"] {
        passes_the_core_checks(id, IntrinsicDelaunay::Refine, 6);
    }
}

/// The generated meshes are mostly not Delaunay: the checks above run on flipped and refined
/// triangulations, not on inputs the modifier leaves alone.
#[test]
fn most_generated_meshes_are_not_delaunay() {
    use tvf_conformance::proptest::strategy::{Strategy, ValueTree};
    use tvf_conformance::proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let strategy = mesh_specs(MeshNeeds::default());
    let (mut flipped, mut drawn) = (0, 0);
    for _ in 0..12 {
        let spec = strategy.new_tree(&mut runner).expect("a draw").current();
        let Ok(mesh) = spec.build() else { continue };
        drawn += 1;
        if !tvf_conformance::corpus::is_delaunay(&mesh.mesh) {
            flipped += 1;
        }
    }
    assert!(
        2 * flipped > drawn,
        "{flipped} of {drawn} draws not Delaunay"
    );
}
