//! Intrinsic Delaunay flipping, refinement and the common subdivision on the real meshes of
//! `../shared/meshes`. Every test here has `shared_meshes` in its name; a missing file fails the
//! test under `CI=true` and is skipped (with a message) elsewhere.

use super::{IntrinsicTriangulation, RefineOptions, TrianglePoint};
use super::{DELAUNAY_FLIP_TOLERANCE, STRICT_DELAUNAY_MARGIN};
use crate::TriangleMesh;
use std::path::PathBuf;

/// The mesh `name` of `../shared/meshes`, `None` (skipped) when absent outside CI.
fn shared_mesh(name: &str) -> Option<TriangleMesh> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/meshes")
        .join(name);
    if !path.exists() {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "{} is missing (required under CI=true)",
            path.display()
        );
        eprintln!("skipping {}: not present", path.display());
        return None;
    }
    match crate::io::load_mesh(&path) {
        Ok(loaded) => match loaded.mesh.into_triangles() {
            Ok(mesh) => Some(mesh),
            Err(_) => panic!(
                "{} has polygons; these tests need triangles",
                path.display()
            ),
        },
        Err(error) => panic!("{} does not load: {error}", path.display()),
    }
}

const MESHES: [&str; 9] = [
    "hand.obj",
    "rocker-arm.obj",
    "bunny.obj",
    "bunny-closed.obj",
    "bumpy-torus.obj",
    "armadillo.obj",
    "kitten.obj",
    "eight.obj",
    "3holes.obj",
];

#[test]
fn shared_meshes_flip_to_delaunay_with_a_tiling_overlay() {
    for name in MESHES {
        let Some(mesh) = shared_mesh(name) else {
            continue;
        };
        let mut tri = IntrinsicTriangulation::new(&mesh).unwrap();
        let flips = tri.flip_to_delaunay().unwrap();
        let mut ties = 0;
        for e in 0..tri.edge_count() {
            let (sum, scale) = tri.cotan_sum_and_scale(e);
            if !tri.is_boundary_edge(e) {
                assert!(
                    sum >= -DELAUNAY_FLIP_TOLERANCE * scale,
                    "{name}: edge {e}: {sum}"
                );
                ties += usize::from(sum <= STRICT_DELAUNAY_MARGIN * scale);
            }
        }
        let area = mesh.total_area();
        assert!((tri.total_area() - area).abs() < 1e-12 * area, "{name}");
        let overlay = tri.common_subdivision(&mesh).unwrap();
        for f in 0..mesh.face_count() {
            let covered: f64 = overlay.input_face_overlaps(f).iter().map(|o| o.area).sum();
            assert!(
                (covered - mesh.face_area(f)).abs() < 1e-12 * area,
                "{name}: face {f}"
            );
        }
        // Centroids of input faces go there and back.
        for f in (0..mesh.face_count()).step_by(7) {
            let point = TrianglePoint {
                face: f,
                barycentric: [1.0 / 3.0; 3],
            };
            let back = overlay
                .to_input(overlay.to_intrinsic(point).unwrap())
                .unwrap();
            assert_eq!(back.face, f, "{name}");
            for k in 0..3 {
                assert!(
                    (back.barycentric[k] - 1.0 / 3.0).abs() < 1e-12,
                    "{name}: {back:?}"
                );
            }
        }
        eprintln!(
            "{name}: {flips} flips, {ties} interior edges with ⋆1 = 0 after flipping, {} cells",
            overlay.cell_count()
        );
    }
}

#[test]
fn shared_meshes_refine_to_strictly_delaunay() {
    for name in MESHES {
        let Some(mesh) = shared_mesh(name) else {
            continue;
        };
        let mut tri = IntrinsicTriangulation::new(&mesh).unwrap();
        let report = tri.refine(&mesh, RefineOptions::default()).unwrap();
        for e in 0..tri.edge_count() {
            let (sum, scale) = tri.cotan_sum_and_scale(e);
            assert!(
                sum > STRICT_DELAUNAY_MARGIN * scale,
                "{name}: edge {e}: {sum}"
            );
        }
        let area = mesh.total_area();
        let overlay = tri.common_subdivision(&mesh).unwrap();
        for f in 0..mesh.face_count() {
            let covered: f64 = overlay.input_face_overlaps(f).iter().map(|o| o.area).sum();
            assert!(
                (covered - mesh.face_area(f)).abs() < 1e-12 * area,
                "{name}: face {f}"
            );
        }
        eprintln!("{name}: refined with {report:?}");
    }
}
