//! The corpora are what they claim: genera agree with the meshes, the Delaunay corpus (and its
//! jittered property-test meshes) is Delaunay and builds every catalog entry.

use tvf_conformance::corpus::{is_delaunay, staggered_torus, Corpus};
use tvf_discretizations::{builtin_catalog, catalog_entry};

#[test]
fn genera_and_closedness_match_the_meshes() {
    for corpus in [Corpus::General, Corpus::Delaunay] {
        for mesh in corpus.meshes(true).iter().chain(&corpus.motion_meshes()) {
            assert!(mesh.mesh.is_closed(), "{} is not closed", mesh.name);
            assert_eq!(mesh.mesh.genus(), mesh.genus, "{}: genus", mesh.name);
        }
    }
}

#[test]
fn the_delaunay_corpus_is_delaunay_and_builds_every_entry() {
    let meshes = Corpus::Delaunay.meshes(true);
    let jittered = (0..4).map(|seed| Corpus::Delaunay.jittered_mesh(seed * 7919));
    for mesh in meshes.into_iter().chain(jittered) {
        assert!(is_delaunay(&mesh.mesh), "{} is not Delaunay", mesh.name);
        for entry in builtin_catalog() {
            let complex = entry
                .build(&mesh.mesh)
                .unwrap_or_else(|e| panic!("{} on {}: {e}", entry.id(), mesh.name));
            assert_eq!(complex.id(), entry.id());
        }
    }
}

#[test]
fn the_general_corpus_has_non_delaunay_meshes() {
    let refused = Corpus::General
        .meshes(false)
        .iter()
        .filter(|m| !is_delaunay(&m.mesh))
        .count();
    assert!(refused >= 5, "only {refused} non-Delaunay meshes");
}

/// The general corpus has slivers (an angle below 1° and one above 175°) and jittered meshes
/// that are not Delaunay, and every entry without a Delaunay precondition builds on each
/// (`whitney-galerkin` among them) while DEC refuses it.
#[test]
fn entries_without_a_delaunay_precondition_build_on_slivers_and_jittered_meshes() {
    let meshes = Corpus::General.meshes(false);
    let slivers = meshes
        .iter()
        .filter(|m| {
            let (low, high) = m.mesh.angle_range_deg();
            low < 1.0 && high > 175.0
        })
        .count();
    assert!(slivers >= 1, "no mesh with slivers");
    let jittered = meshes
        .iter()
        .filter(|m| m.name.starts_with("jittered") && !is_delaunay(&m.mesh))
        .count();
    assert!(jittered >= 1, "no jittered mesh that is not Delaunay");
    for mesh in meshes.iter().filter(|m| !is_delaunay(&m.mesh)) {
        for entry in builtin_catalog() {
            let built = entry.build(&mesh.mesh);
            assert_eq!(
                built.is_ok(),
                !entry.needs_delaunay(),
                "{} on {}",
                entry.id(),
                mesh.name
            );
        }
    }
    assert!(!catalog_entry("whitney-galerkin").unwrap().needs_delaunay());
}

#[test]
fn the_staggered_torus_has_acute_triangles_only() {
    let mesh = staggered_torus(1.0, 0.4, 24, 10);
    assert_eq!(mesh.genus(), 1);
    assert!(mesh.signed_volume() > 0.0, "normals point inwards");
    let (_, max_angle) = mesh.angle_range_deg();
    assert!(max_angle < 90.0, "largest angle {max_angle}°");
}

#[test]
fn the_open_corpora_have_boundary_and_their_stated_topology() {
    for corpus in [Corpus::Open, Corpus::OpenDelaunay] {
        for mesh in corpus.meshes(true).iter().chain(&corpus.motion_meshes()) {
            assert!(!mesh.mesh.is_closed(), "{} is closed", mesh.name);
            assert_eq!(mesh.mesh.genus(), mesh.genus, "{}: genus", mesh.name);
            assert_eq!(
                mesh.component_harmonic_dimensions().iter().sum::<usize>(),
                mesh.harmonic_dimension,
                "{}: 2g + b − 1",
                mesh.name
            );
        }
    }
    let jittered = (0..4).map(|seed| Corpus::OpenDelaunay.jittered_mesh(seed * 7919));
    for mesh in Corpus::OpenDelaunay
        .meshes(true)
        .into_iter()
        .chain(jittered)
    {
        assert!(is_delaunay(&mesh.mesh), "{} is not Delaunay", mesh.name);
    }
}
