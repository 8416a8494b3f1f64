//! The mesh strategies and the property runner: generated meshes are valid with the genus and
//! boundary their description states (Delaunay where asked), and a correct catalog entry passes
//! the property runner.

use tvf_conformance::corpus::is_delaunay;
use tvf_conformance::property_runner::{run_property, PropertyRequest};
use tvf_conformance::proptest::prelude::*;
use tvf_conformance::reference_report::catalog_reference_checks;
use tvf_conformance::strategies::{mesh_specs, MeshNeeds};
use tvf_discretizations::component_boundary_loops;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn generated_meshes_have_the_stated_topology(spec in mesh_specs(MeshNeeds::default())) {
        let mesh = spec.build().unwrap();
        let genus: usize = mesh.mesh.component_genera().iter().sum();
        prop_assert_eq!(genus, mesh.genus);
        prop_assert_eq!(
            mesh.component_harmonic_dimensions().iter().sum::<usize>(),
            mesh.harmonic_dimension
        );
        prop_assert_eq!(mesh.mesh.component_count(), spec.components.len());
    }

    #[test]
    fn delaunay_variants_are_delaunay(spec in mesh_specs(MeshNeeds { delaunay: true, closed_only: false })) {
        let mesh = spec.build().unwrap();
        prop_assert!(is_delaunay(&mesh.mesh), "{}", mesh.name);
    }

    #[test]
    fn closed_only_meshes_are_closed(spec in mesh_specs(MeshNeeds { delaunay: false, closed_only: true })) {
        let mesh = spec.build().unwrap();
        prop_assert!(component_boundary_loops(&mesh.mesh).iter().all(|&b| b == 0));
    }
}

#[test]
fn a_correct_entry_passes_the_property_runner_with_its_reference_checks() {
    let id = "nonconforming-consistent";
    let entry = tvf_conformance::builtin_entry(id);
    let builder = |mesh: &tvf_core::TriangleMesh| entry.build(mesh).map_err(|e| e.to_string());
    let mut request = PropertyRequest::new(12, 3, MeshNeeds::default());
    request.reference = catalog_reference_checks(id).to_vec();
    let report = run_property(&builder, &request, &|_| {});
    assert!(
        report.passed(),
        "{:?}",
        report.counterexample.map(|c| c
            .report
            .failures()
            .iter()
            .map(|o| format!("{}: {}", o.name, o.detail))
            .collect::<Vec<_>>())
    );
    assert_eq!(report.cases_passed, 12);
    assert!(report.worst.iter().any(|o| o.name == "rotation:J_squared"));
}
