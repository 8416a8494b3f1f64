//! Polygon meshes: the polygon corpus and strategies are what they state (polygon meshes of the
//! stated genus and boundary, shrinking within polygon meshes), polygon-dec has `2g` harmonic
//! fields on closed duals and quad surfaces of genus 0–5, and the polygon sampling checks catch
//! a sampling built on other geometry.

use tvf_conformance::polygon_corpus::{open_polygon_corpus, polygon_corpus};
use tvf_conformance::polygon_operations::{jittered, quad_split};
use tvf_conformance::property_runner::{check_polygon_mesh, run_polygon_property, PropertyRequest};
use tvf_conformance::proptest::prelude::*;
use tvf_conformance::strategies::{polygon_mesh_specs, MeshNeeds, PolygonShape};
use tvf_core::discretization::HodgeComplex;
use tvf_core::generate::{dual, genus_surface};
use tvf_core::SurfaceMesh;
use tvf_discretizations::{catalog_entry, component_boundary_loops, HodgeDecomposer};

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn generated_polygon_meshes_have_the_stated_topology(spec in polygon_mesh_specs(false)) {
        let mesh = spec.build().unwrap();
        prop_assert!(!mesh.mesh.is_triangle_mesh(), "{}", mesh.name);
        prop_assert_eq!(mesh.component_genera().iter().sum::<usize>(), mesh.genus);
        prop_assert_eq!(
            mesh.component_harmonic_dimensions().iter().sum::<usize>(),
            mesh.harmonic_dimension
        );
        prop_assert_eq!(mesh.mesh.component_count(), spec.components.len());
    }

    #[test]
    fn closed_only_polygon_meshes_are_closed(spec in polygon_mesh_specs(true)) {
        let mesh = spec.build().unwrap();
        prop_assert!(component_boundary_loops(&mesh.mesh).iter().all(|&b| b == 0));
    }
}

#[test]
fn the_polygon_corpora_are_polygon_meshes_of_the_stated_topology() {
    for (meshes, closed) in [(polygon_corpus(), true), (open_polygon_corpus(), false)] {
        for mesh in meshes {
            assert!(!mesh.mesh.is_triangle_mesh(), "{}", mesh.name);
            assert_eq!(mesh.mesh.is_closed(), closed, "{}", mesh.name);
            assert_eq!(mesh.mesh.genus(), mesh.genus, "{}: genus", mesh.name);
            let dimensions: usize = mesh.component_harmonic_dimensions().iter().sum();
            assert_eq!(dimensions, mesh.harmonic_dimension, "{}", mesh.name);
        }
    }
}

#[test]
fn a_failure_shrinks_to_a_minimal_polygon_mesh_written_with_its_polygons() {
    // A builder that refuses every mesh with a boundary: the minimal failing mesh is the
    // simplest open shape, alone, unjittered and unmoved — still a polygon mesh.
    let entry = catalog_entry("polygon-dec").unwrap();
    let builder = |mesh: &SurfaceMesh| -> Result<Box<dyn HodgeComplex>, String> {
        if mesh.is_closed() {
            entry.build(mesh).map_err(|e| e.to_string())
        } else {
            Err("refuses meshes with boundary".to_string())
        }
    };
    let request = PropertyRequest::new(64, 1, MeshNeeds::default());
    let report = run_polygon_property(&builder, &request, &|_| {});
    let counterexample = report.counterexample.expect("an open mesh is drawn");
    assert_eq!(
        counterexample.spec.components.len(),
        1,
        "{:?}",
        counterexample.spec
    );
    assert_eq!(counterexample.spec.jitter.amplitude, 0.0);
    assert_eq!(counterexample.spec.motion, None);
    assert_eq!(
        counterexample.spec.components[0],
        PolygonShape::DualDisk { rings: 2 },
        "the simplest open polygon shape"
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("counterexample.obj");
    tvf_core::io::write_obj(&path, &counterexample.mesh.mesh).unwrap();
    let loaded = tvf_core::io::load_mesh(&path).unwrap().mesh;
    assert!(!loaded.is_triangle_mesh());
    assert_eq!(loaded.face_count(), counterexample.mesh.mesh.face_count());
}

#[test]
fn polygon_dec_has_2g_harmonic_fields_on_closed_duals_and_quad_surfaces_of_genus_0_to_5() {
    let entry = catalog_entry("polygon-dec").unwrap();
    for genus in 0..=5 {
        let triangles = genus_surface(genus, 2);
        let duals = SurfaceMesh::from(dual(&triangles).expect("a closed dual"));
        let quads = jittered(&quad_split(&triangles).unwrap(), 0.1, genus as u64).unwrap();
        let largest = (0..duals.face_count()).map(|f| duals.face_size(f)).max();
        assert!(largest >= Some(5), "the dual has pentagons or larger");
        for (what, mesh) in [("dual", duals), ("jittered quad surface", quads)] {
            assert!(mesh.is_closed() && !mesh.is_triangle_mesh());
            let complex = entry.build(&mesh).unwrap();
            let harmonic = HodgeDecomposer::new(complex.as_ref())
                .unwrap()
                .harmonic_basis(7)
                .unwrap();
            assert_eq!(harmonic.len(), 2 * genus, "genus-{genus} {what}");
            assert_eq!(complex.topology().harmonic_dimension, 2 * genus);
        }
    }
}

#[test]
fn the_polygon_sampling_checks_catch_a_sampling_built_on_other_geometry() {
    let mesh = polygon_corpus().swap_remove(1).mesh; // the cube-sphere
    let moved = jittered(&mesh, 0.1, 4).unwrap();
    let entry = catalog_entry("polygon-dec").unwrap();
    let correct = check_polygon_mesh(&|m| entry.build(m).map_err(|e| e.to_string()), &mesh);
    assert!(correct.passed(), "{:?}", correct.failures());
    let mutant = check_polygon_mesh(&|_| entry.build(&moved).map_err(|e| e.to_string()), &mesh);
    let failed: Vec<&str> = mutant.failures().iter().map(|o| o.name.as_str()).collect();
    for name in ["polygon_sampling:frames", "polygon_sampling:sharp_of_flat"] {
        assert!(failed.contains(&name), "{name} not failed: {failed:?}");
    }
    assert_eq!(mesh.vertex_count(), moved.vertex_count());
}
