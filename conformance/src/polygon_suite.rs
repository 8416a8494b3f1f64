//! The core suite on polygon meshes, for one catalog entry (of any catalog): on the closed
//! polygon corpus ([`polygon_mesh_suite`] with no boundary condition), on the polygon meshes with
//! holes for each boundary condition, and on generated polygon meshes
//! ([`generated_polygon_meshes`]). An entry that needs triangles is checked to refuse every
//! polygon mesh with [`DiscretizationError::NeedsTriangles`] naming it.

use crate::corpus::DENSE_LIMIT;
use crate::open_suite::{check_decomposition_and_spectrum, check_operator_algebra};
use crate::polygon_capability_checks::check_polygon_capabilities;
use crate::polygon_corpus::{open_polygon_corpus, polygon_corpus, PolygonCorpusMesh};
use crate::polygon_operations::moved;
use crate::property_runner::{run_polygon_property, PropertyRequest};
use crate::spectral_checks::check_rigid_motion_invariance;
use crate::strategies::MeshNeeds;
use crate::suite::{panic_with_counterexample, GENERATED_MESHES_SEED};
use tvf_core::discretization::{
    BoundaryCondition, DiscretizationError, HodgeComplex, HodgeOperators,
};
use tvf_core::SurfaceMesh;
use tvf_discretizations::CatalogEntry;

/// Every core check on every closed polygon mesh ([`polygon_corpus`], `boundary = None`) or on
/// every polygon mesh with holes under `boundary` ([`open_polygon_corpus`]): shapes and masses,
/// `d1 d0 = 0`, symmetry, semi-definiteness, sampling and point evaluation on polygons, the
/// Hodge decomposition, `dim ker L = 2g` (`2g + b − 1` per component with boundary; dense and by
/// harmonic projection), the spectrum union, Lemma 1, the complete orthonormal basis and, for
/// relative forms, fields that vanish on the fixed boundary edges; on the closed meshes, the same
/// stiffness matrices, masses and spectrum on a rigidly moved copy. An entry that does not offer
/// `boundary` must refuse the open meshes with
/// [`DiscretizationError::UnsupportedBoundaryCondition`]; an entry that needs triangles must
/// refuse every polygon mesh with [`DiscretizationError::NeedsTriangles`].
pub fn polygon_mesh_suite(entry: &CatalogEntry, boundary: Option<BoundaryCondition>) {
    let id = entry.id();
    let meshes = match boundary {
        None => polygon_corpus(),
        Some(_) => open_polygon_corpus(),
    };
    let condition = boundary.unwrap_or(entry.default_boundary());
    for mesh in meshes {
        eprintln!(
            "checking {id} ({}) on {} ({} faces)",
            condition.name(),
            mesh.name,
            mesh.mesh.face_count()
        );
        let built = entry.build_with(&mesh.mesh, condition);
        if entry.needs_triangles() {
            match built {
                Err(DiscretizationError::NeedsTriangles { discretization, .. }) => {
                    assert_eq!(
                        discretization, id,
                        "{}: the error names the entry",
                        mesh.name
                    );
                    continue;
                }
                Err(e) => panic!("{}: {id} refused a polygon mesh with {e}", mesh.name),
                Ok(_) => panic!("{}: {id} needs triangles but built on polygons", mesh.name),
            }
        }
        if boundary.is_some() && !entry.boundary_conditions().contains(&condition) {
            match built {
                Err(DiscretizationError::UnsupportedBoundaryCondition { .. }) => continue,
                Err(e) => panic!("{}: unexpected error {e}", mesh.name),
                Ok(_) => panic!("{}: {id} built with unsupported {condition:?}", mesh.name),
            }
        }
        let complex = built.unwrap_or_else(|e| panic!("{}: {e}", mesh.name));
        polygon_core_checks(complex.as_ref(), &mesh);
        if boundary.is_none() {
            let moved = moved(&mesh.mesh, MOTION_AXIS, MOTION_ANGLE, MOTION_TRANSLATION)
                .unwrap_or_else(|e| panic!("{}: {e}", mesh.name));
            let moved = entry.build_with(&moved, condition).expect("built unmoved");
            let dense = complex.field_dimension() <= DENSE_LIMIT;
            check_rigid_motion_invariance(complex.as_ref(), moved.as_ref(), dense);
        }
    }
}

/// The rigid motion the closed polygon meshes are checked to be invariant under (the generated
/// polygon meshes draw others).
const MOTION_AXIS: [f64; 3] = [1.0, -2.0, 0.5];
/// Its angle, radians.
const MOTION_ANGLE: f64 = 0.83;
/// Its translation.
const MOTION_TRANSLATION: [f64; 3] = [3.0, -1.0, 2.0];

/// The core checks on one polygon mesh.
fn polygon_core_checks(complex: &dyn HodgeComplex, mesh: &PolygonCorpusMesh) {
    check_operator_algebra(complex, mesh);
    check_polygon_capabilities(complex, mesh);
    check_decomposition_and_spectrum(complex, mesh);
}

/// The core checks and the polygon capability checks on `cases` polygon meshes drawn from
/// [`crate::strategies::polygon_mesh_specs`] (closed and with holes); panics with the shrunk
/// minimal failing mesh and its failed checks. For an entry that needs triangles, checks that it
/// refuses each drawn mesh (the run's failure is `construction` on the first one).
pub fn generated_polygon_meshes(entry: &CatalogEntry, cases: u32) {
    let request = PropertyRequest::new(cases, GENERATED_MESHES_SEED, MeshNeeds::default());
    let builder = |mesh: &SurfaceMesh| -> Result<Box<dyn HodgeComplex>, String> {
        entry.build(mesh).map_err(|e| e.to_string())
    };
    let report = run_polygon_property(&builder, &request, &|_| {});
    if let Some(aborted) = report.aborted {
        panic!("the polygon property run stopped: {aborted}");
    }
    if entry.needs_triangles() {
        let counterexample = report
            .counterexample
            .expect("an entry that needs triangles refuses polygon meshes");
        let failed = counterexample.report.failures();
        assert!(
            failed.len() == 1 && failed[0].name == crate::property_runner::CONSTRUCTION,
            "{}: expected a refusal, got {failed:?}",
            entry.id()
        );
        return;
    }
    panic_with_counterexample(report.counterexample, "polygon mesh");
}

/// The accuracy checks on polygon meshes ([`crate::accuracy::accuracy_report`] with polygons
/// only: the flat box of quads, the regular and jittered quad spheres) for an entry that accepts
/// polygons; an entry that needs triangles must refuse the quad box
/// ([`crate::accuracy::AccuracyRequest`] then has nothing to check on polygons).
pub fn polygon_accuracy(entry: &CatalogEntry) {
    let builder = |mesh: &SurfaceMesh| -> Result<Box<dyn HodgeComplex>, String> {
        entry.build(mesh).map_err(|e| e.to_string())
    };
    if entry.needs_triangles() {
        let refused = entry.build(&crate::accuracy_meshes::flat_box(true, 0));
        assert!(
            matches!(refused, Err(DiscretizationError::NeedsTriangles { .. })),
            "{} needs triangles: it must refuse the quad box",
            entry.id()
        );
        return;
    }
    let request = crate::accuracy::AccuracyRequest {
        triangles: false,
        polygons: true,
        open_meshes: true,
    };
    let report = crate::accuracy::accuracy_report(&builder, &request);
    crate::check_outcome::assert_outcomes(&report.outcomes);
}
