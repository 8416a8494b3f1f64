//! The edges of a polygon mesh drawn over its surface: a polygon mesh is shaded through its
//! display triangulation, whose extra triangles say nothing about the mesh; these lines show the
//! polygons themselves.

use crate::Polyline;
use tvf_core::SurfaceMesh;

/// Colour of polygon edges (dark grey, visible on every colour map).
const EDGE_COLOR: [u8; 3] = [45, 45, 45];

/// One two-point polyline per edge of `mesh` (`E` of them, in edge order), `width_px` wide in
/// the output image; none for a triangle mesh, whose faces are drawn as they are.
pub fn polygon_edges(mesh: &SurfaceMesh, width_px: f64) -> Vec<Polyline> {
    if mesh.is_triangle_mesh() {
        return Vec::new();
    }
    let positions = mesh.positions();
    mesh.edges()
        .iter()
        .map(|&[a, b]| Polyline {
            points: vec![positions[a], positions[b]],
            color: EDGE_COLOR,
            tip_color: EDGE_COLOR,
            width_px,
        })
        .collect()
}
