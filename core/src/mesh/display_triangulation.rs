//! [`DisplayTriangulation`]: how a polygon mesh is drawn — each face of more than three corners
//! as the fan of triangles around its corner average, each triangle as itself — and the map
//! from its triangles back to the faces.

use super::error::MeshError;
use super::face_list::{FaceCorners, FaceList};
use super::validate::polygon_centroid;
use super::TriangleMesh;

/// The triangles a polygon mesh is drawn with. It belongs to the mesh, not to a discretization:
/// rendering, exports of per-triangle data and the editor's picking use it.
///
/// Face `f` with corners `p_0 … p_{n−1}`, `n > 3`, becomes the `n` triangles
/// `(m_f, p_c, p_{c+1})`, `m_f` the average of its corners, a vertex appended after the mesh's
/// vertices (in face order); a triangle face stays one triangle. Triangles are listed face by
/// face. On a valid polygon mesh (no folded polygon) every triangle faces the way of its
/// polygon's vector area.
#[derive(Debug, Clone)]
pub struct DisplayTriangulation {
    mesh: TriangleMesh,
    /// The face of every display triangle.
    face: Vec<usize>,
    /// The corner `c` of the face where each display triangle's second vertex sits (its third is
    /// `c + 1`), or `usize::MAX` for a triangle face shown as itself.
    corner: Vec<usize>,
}

impl DisplayTriangulation {
    /// The display triangulation of `faces` over `positions`.
    pub(crate) fn of(positions: &[[f64; 3]], faces: &FaceList) -> Result<Self, MeshError> {
        let mut display_positions = positions.to_vec();
        let mut triangles = Vec::with_capacity(faces.total_corners());
        let mut face = Vec::with_capacity(faces.total_corners());
        let mut corner = Vec::with_capacity(faces.total_corners());
        for (f, corners) in faces.iter().enumerate() {
            if let &[a, b, c] = corners {
                triangles.push([a, b, c]);
                face.push(f);
                corner.push(usize::MAX);
                continue;
            }
            let points: Vec<[f64; 3]> = corners.iter().map(|&v| positions[v]).collect();
            let middle = display_positions.len();
            display_positions.push(polygon_centroid(&points));
            for c in 0..corners.len() {
                triangles.push([middle, corners[c], corners[(c + 1) % corners.len()]]);
                face.push(f);
                corner.push(c);
            }
        }
        Ok(Self {
            mesh: TriangleMesh::new(display_positions, triangles)?,
            face,
            corner,
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
    /// triangle `t` with barycentric coordinates `b` (w.r.t. the triangle's corners): for a
    /// triangle face `b` itself; for a fan triangle `(m_f, p_c, p_{c+1})`, `b_0/n` on every
    /// corner plus `b_1` on `c` and `b_2` on `c + 1`.
    pub fn corner_weights(&self, t: usize, b: [f64; 3], corner_count: usize) -> Vec<f64> {
        let c = self.corner[t];
        if c == usize::MAX {
            return b.to_vec();
        }
        let mut weights = vec![b[0] / corner_count as f64; corner_count];
        weights[c] += b[1];
        weights[(c + 1) % corner_count] += b[2];
        weights
    }
}
