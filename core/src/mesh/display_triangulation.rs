//! [`DisplayTriangulation`]: how a polygon mesh is drawn — each face of more than three corners
//! as the fan of triangles around its corner average (or, for a polygon that is not star-shaped
//! around it, by ear clipping of its own corners), each triangle as itself — and the map from its
//! triangles back to the faces.

use super::error::MeshError;
use super::face_list::{FaceCorners, FaceList};
use super::polygon_outline::PolygonOutline;
use super::validate::{polygon_centroid, polygon_vector_area};
use super::TriangleMesh;
use crate::geometry::{cross, dot, sub};

/// Marks the corner average of a face among a display triangle's [`DisplayTriangulation`]
/// sources.
const CORNER_AVERAGE: usize = usize::MAX;

/// The triangles a polygon mesh is drawn with. It belongs to the mesh, not to a discretization:
/// rendering, exports of per-triangle data and the editor's picking use it.
///
/// Face `f` with corners `p_0 … p_{n−1}`, `n > 3`, becomes the `n` triangles
/// `(m_f, p_c, p_{c+1})`, `m_f` the average of its corners, a vertex appended after the mesh's
/// vertices (in face order), when every such triangle faces the way of the polygon's vector area
/// (the polygon is star-shaped around `m_f`, e.g. convex); otherwise the `n − 2` triangles of an
/// ear clipping of its corners seen along the vector area, with no new vertex. A triangle face
/// stays one triangle. Triangles are listed face by face. On a valid polygon mesh (no folded
/// polygon) every triangle faces the way of its polygon's vector area.
#[derive(Debug, Clone)]
pub struct DisplayTriangulation {
    mesh: TriangleMesh,
    /// The face of every display triangle.
    face: Vec<usize>,
    /// For every display triangle, the corner (0-based within its face) at each of its three
    /// vertices, or [`CORNER_AVERAGE`] for the face's corner average.
    sources: Vec<[usize; 3]>,
}

impl DisplayTriangulation {
    /// The display triangulation of `faces` over `positions`.
    pub(crate) fn of(positions: &[[f64; 3]], faces: &FaceList) -> Result<Self, MeshError> {
        let mut display_positions = positions.to_vec();
        let mut triangles = Vec::with_capacity(faces.total_corners());
        let mut face = Vec::with_capacity(faces.total_corners());
        let mut sources = Vec::with_capacity(faces.total_corners());
        for (f, corners) in faces.iter().enumerate() {
            let n = corners.len();
            if n == 3 {
                triangles.push([corners[0], corners[1], corners[2]]);
                face.push(f);
                sources.push([0, 1, 2]);
                continue;
            }
            let points: Vec<[f64; 3]> = corners.iter().map(|&v| positions[v]).collect();
            let area = polygon_vector_area(&points);
            let middle = polygon_centroid(&points);
            let star_shaped = (0..n).all(|c| {
                let spoke = cross(sub(points[c], middle), sub(points[(c + 1) % n], middle));
                dot(spoke, area) > 0.0
            });
            if star_shaped {
                let m = display_positions.len();
                display_positions.push(middle);
                for c in 0..n {
                    triangles.push([m, corners[c], corners[(c + 1) % n]]);
                    face.push(f);
                    sources.push([CORNER_AVERAGE, c, (c + 1) % n]);
                }
                continue;
            }
            let ears = PolygonOutline::new(&points, area)
                .ear_triangles()
                .ok_or(MeshError::PolygonNotTriangulable { face: f })?;
            for ear in ears {
                triangles.push(ear.map(|c| corners[c]));
                face.push(f);
                sources.push(ear);
            }
        }
        Ok(Self {
            mesh: TriangleMesh::new(display_positions, triangles)?,
            face,
            sources,
        })
    }

    /// The triangles as a triangle mesh.
    pub fn mesh(&self) -> &TriangleMesh {
        &self.mesh
    }

    /// The face of the mesh that display triangle `t` belongs to.
    pub fn face_of(&self, t: usize) -> usize {
        self.face[t]
    }

    /// The face of every display triangle.
    pub fn faces_of_triangles(&self) -> &[usize] {
        &self.face
    }

    /// The weights over the corners of its face (`corner_count` of them) of the point of display
    /// triangle `t` with barycentric coordinates `b` (w.r.t. the triangle's vertices): `b_i` on
    /// the corner at vertex `i`, and for the corner average `b_i / n` on every corner. For a
    /// triangle face that is `b` itself.
    pub fn corner_weights(&self, t: usize, b: [f64; 3], corner_count: usize) -> Vec<f64> {
        let mut weights = vec![0.0; corner_count];
        for (&source, &w) in self.sources[t].iter().zip(&b) {
            if source == CORNER_AVERAGE {
                for x in &mut weights {
                    *x += w / corner_count as f64;
                }
            } else {
                weights[source] += w;
            }
        }
        weights
    }
}
