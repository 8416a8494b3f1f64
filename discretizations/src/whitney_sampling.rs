//! [`WhitneySampling`]: DEC 1-forms seen as tangent vectors through Whitney interpolation, and
//! per-face vectors turned into 1-forms by the de Rham map.

use crate::edge_averages::edge_integrals;
use crate::face_geometry::FaceGeometry;
use tvf_core::discretization::{FaceFrames, FieldSampling, TangentProjection};
use tvf_core::geometry::{cross, scale, sub};
use tvf_core::{SurfacePoint, TriangleMesh};

/// Whitney interpolation of 1-forms on edges.
///
/// In face `t` with corners `i, j, k`, the Whitney form of the oriented edge `j → k` is
/// `W_jk = λ_j ∇λ_k − λ_k ∇λ_j` (`λ` the barycentric coordinates, `∇λ_c = n × (p_{c+2} −
/// p_{c+1}) / 2A`); the vector of a 1-form `x` at a point is `Σ_e ±x_e W_e` over the face's three
/// edges, with `+` where the edge's orientation `a < b` runs `j → k`. Whitney forms integrate to
/// 1 along their own edge and 0 along the others, and reproduce constant vector fields exactly.
///
/// The de Rham map from one 3D vector per face: `x_e = ⟨v_t, p_b − p_a⟩` averaged over the (one
/// or two) faces `t` next to edge `e`. The edge lies in each face's plane, so this is the
/// integral of the face-projected vector; a constant 3D vector projected face by face gives the
/// same value from both sides, so sampling after the de Rham map reproduces it exactly.
///
/// For relative forms (the boundary edges fixed to zero) the fixed edges have no Whitney form in
/// the sampling and get 0 from the de Rham map. The sampled field is then normal to the boundary:
/// along a boundary edge the Whitney forms of the other two edges of its face have no tangential
/// component. A constant vector is still reproduced in every face without a fixed edge.
#[derive(Debug, Clone)]
pub struct WhitneySampling {
    faces: Vec<[usize; 3]>,
    face_edges: Vec<[usize; 3]>,
    edges: Vec<[usize; 2]>,
    positions: Vec<[f64; 3]>,
    frames: FaceFrames,
    /// Edges whose value the boundary condition fixes to zero (`E` entries; all `false` for
    /// absolute forms).
    fixed_edges: Vec<bool>,
    /// `∇λ_c` of the three corners of every face (3D, in the face plane, 1/length).
    barycentric_gradients: Vec<[[f64; 3]; 3]>,
}

impl WhitneySampling {
    /// Precomputes the barycentric gradients of every face of `mesh`; the edges flagged in
    /// `fixed_edges` (`E` entries) are zero in every field.
    pub fn new(mesh: &TriangleMesh, geometry: &FaceGeometry, fixed_edges: Vec<bool>) -> Self {
        assert_eq!(fixed_edges.len(), mesh.edge_count(), "one flag per edge");
        let barycentric_gradients = mesh
            .faces()
            .iter()
            .enumerate()
            .map(|(t, face)| {
                let p = face.map(|i| mesh.positions()[i]);
                let n = geometry.normals[t];
                let two_area = 2.0 * geometry.areas[t];
                std::array::from_fn(|c| {
                    let opposite = sub(p[(c + 2) % 3], p[(c + 1) % 3]);
                    scale(cross(n, opposite), 1.0 / two_area)
                })
            })
            .collect();
        Self {
            faces: mesh.faces().to_vec(),
            face_edges: mesh.face_edges().to_vec(),
            edges: mesh.edges().to_vec(),
            positions: mesh.positions().to_vec(),
            frames: geometry.face_frames(),
            fixed_edges,
            barycentric_gradients,
        }
    }
}

impl FieldSampling for WhitneySampling {
    fn face_frames(&self) -> &FaceFrames {
        &self.frames
    }

    fn field_dimension(&self) -> usize {
        self.edges.len()
    }

    fn sample_weights(&self, point: &SurfacePoint) -> Vec<(usize, [f64; 3])> {
        let (face, barycentric) = (point.face, point.triangle_coordinates());
        let corners = self.faces[face];
        let gradients = &self.barycentric_gradients[face];
        (0..3)
            .filter(|&c| !self.fixed_edges[self.face_edges[face][c]])
            .map(|c| {
                let (j, k) = ((c + 1) % 3, (c + 2) % 3);
                let sign = if corners[j] < corners[k] { 1.0 } else { -1.0 };
                let w: [f64; 3] = std::array::from_fn(|d| {
                    sign * (barycentric[j] * gradients[k][d] - barycentric[k] * gradients[j][d])
                });
                (self.face_edges[face][c], w)
            })
            .collect()
    }

    fn project_face_vectors(&self, vectors: &[[f64; 3]]) -> TangentProjection {
        let faces = self.face_edges.iter().map(|e| e.as_slice());
        TangentProjection {
            field: edge_integrals(
                &self.edges,
                &self.positions,
                &self.fixed_edges,
                faces.zip(vectors.iter().copied()),
            ),
            normal_parts: self.frames.normal_parts(vectors),
        }
    }
}
