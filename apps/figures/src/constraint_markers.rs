//! Markers of constraints on pictures: where a constraint applies and how it is drawn (vector
//! orange with its direction, source red, sink blue, vortex green); the markers of a constraint
//! file, checked first (`tvf render --constraints`).

use crate::error::FigureError;
use std::path::Path;
use tvf_core::discretization::HodgeComplex;
use tvf_core::geometry::{add, scale};
use tvf_core::{SurfaceMesh, SurfacePoint};
use tvf_design::{Constraint, ConstraintSet, Location, Target};
use tvf_render::Marker;

/// Marker radius in pixels on a picture 768 pixels high; it scales with the picture's height.
const MARKER_RADIUS_AT_768: f64 = 6.0;

/// The point of `mesh` where `constraint` applies: a face's barycentric point (centroid if
/// none), a vertex, or an edge midpoint. `None` if an index is out of range.
pub fn constraint_position(mesh: &SurfaceMesh, constraint: &Constraint) -> Option<[f64; 3]> {
    let p = mesh.positions();
    match constraint.location {
        Location::Face {
            face,
            ref barycentric,
        } => {
            if face >= mesh.face_count() {
                return None;
            }
            let point = match barycentric {
                Some(weights) => SurfacePoint {
                    face,
                    weights: weights.clone(),
                },
                None => mesh.centroid_point(face),
            };
            mesh.check_point(&point).ok()?;
            Some(mesh.point_position(&point))
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

/// The markers of every constraint of the constraint file `path` on a picture `image_height`
/// pixels high, after the file was checked against `mesh` and `complex` as a spline would check
/// it ([`ConstraintSet::load_for`]). A constraint without a place on the mesh is an error.
pub fn constraint_file_markers<H: HodgeComplex + ?Sized>(
    path: &Path,
    mesh: &SurfaceMesh,
    complex: &H,
    image_height: u32,
) -> Result<Vec<Marker>, FigureError> {
    let set = ConstraintSet::load_for(path, mesh, complex)?;
    let radius_px = MARKER_RADIUS_AT_768 * image_height as f64 / 768.0;
    let markers = constraint_markers(mesh, &set.constraints, radius_px);
    if markers.len() < set.constraints.len() {
        return Err(FigureError::Invalid(format!(
            "{}: {} constraint(s) refer to vertices, edges or faces this mesh does not have",
            path.display(),
            set.constraints.len() - markers.len()
        )));
    }
    Ok(markers)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::generate::icosphere;
    use tvf_discretizations::{catalog_entry, DEFAULT_DISCRETIZATION};

    #[test]
    fn a_checked_file_gives_one_marker_per_constraint_scaled_with_the_picture() {
        let mesh = SurfaceMesh::from(icosphere(1));
        let complex = catalog_entry(DEFAULT_DISCRETIZATION)
            .unwrap()
            .build(&mesh)
            .unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("c.json");
        std::fs::write(
            &path,
            r#"{"constraints": [{"id": "a", "kind": "vector", "face": 3, "value": [1, 0, 0]},
                {"id": "b", "kind": "divergence", "vertex": 2, "value": -1}]}"#,
        )
        .unwrap();
        let markers = constraint_file_markers(&path, &mesh, complex.as_ref(), 384).unwrap();
        assert_eq!(markers.len(), 2);
        assert_eq!(markers[0].radius_px, 3.0);
        assert!(markers[0].direction.is_some() && markers[1].direction.is_none());
        assert_eq!(markers[1].color, Marker::constraint_color("sink"));
    }
}
