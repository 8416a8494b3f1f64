//! Markers of constraints on pictures: where a constraint applies and how it is drawn (vector
//! orange with its direction, source red, sink blue, vortex green).

use tvf_core::geometry::{add, scale};
use tvf_core::SurfaceMesh;
use tvf_design::{Constraint, Location, Target};
use tvf_render::Marker;

/// The point of `mesh` where `constraint` applies: a face's barycentric point (centroid if
/// none), a vertex, or an edge midpoint. `None` if an index is out of range.
pub fn constraint_position(mesh: &SurfaceMesh, constraint: &Constraint) -> Option<[f64; 3]> {
    let p = mesh.positions();
    match constraint.location {
        Location::Face { face, barycentric } => {
            let f = mesh.faces().get(face)?;
            let l = barycentric.unwrap_or([1.0 / 3.0; 3]);
            Some((0..3).fold([0.0; 3], |acc, c| add(acc, scale(p[f[c]], l[c]))))
        }
        Location::Vertex(v) => p.get(v).copied(),
        Location::Edge(e) => {
            let [a, b] = *mesh.edges().get(e)?;
            Some(scale(add(p[a], p[b]), 0.5))
        }
    }
}

/// Markers for constraints, coloured by kind (vector orange with its direction, source red,
/// sink blue, vortex green), `radius_px` in output pixels.
pub fn constraint_markers(
    mesh: &SurfaceMesh,
    constraints: &[Constraint],
    radius_px: f64,
) -> Vec<Marker> {
    constraints
        .iter()
        .filter_map(|c| {
            let position = constraint_position(mesh, c)?;
            let (kind, direction) = match c.target {
                Target::Vector(v) => ("vector", Some(v)),
                Target::Divergence(d) if d >= 0.0 => ("source", None),
                Target::Divergence(_) => ("sink", None),
                Target::Curl(_) => ("vortex", None),
            };
            Some(Marker {
                position,
                color: Marker::constraint_color(kind),
                radius_px,
                direction,
            })
        })
        .collect()
}
