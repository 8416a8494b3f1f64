//! [`NodalEvaluation`]: point evaluation of potentials and co-potentials from nothing but the
//! kinds of their nodes — what a complex given as matrices ([`crate::MatrixComplex`], a
//! `--complex` folder) knows — so that face colours (curl, divergence, energy) and point
//! constraints work on it.

use tvf_core::discretization::{NodeKind, PointEvaluation};
use tvf_core::{SurfaceMesh, SurfacePoint};

/// How the values of one space are evaluated at a point of a face.
#[derive(Debug, Clone)]
enum Interpolation {
    /// Vertex nodes: the point's corner weights (barycentric on a triangle, the generalized
    /// barycentric weights of a polygon point), the P1 / Whitney 0-form interpolant.
    Corners,
    /// Edge nodes of a triangle mesh: the Crouzeix–Raviart interpolant, `Σ_c (1 − 2 λ_c) x_c`
    /// over the edges opposite corners `c` (edge `face_edges[t][c]`).
    EdgeMidpoints(Vec<[usize; 3]>),
    /// Face nodes: the face's own value, constant on the face.
    Faces,
}

impl Interpolation {
    /// The interpolation of nodes of kind `kind` on `mesh`; `None` where no interpolant is
    /// defined by the kind alone (face frames; edge nodes of a polygon mesh).
    fn of(kind: NodeKind, mesh: &SurfaceMesh) -> Option<Self> {
        match kind {
            NodeKind::Vertices => Some(Self::Corners),
            NodeKind::Edges => Some(Self::EdgeMidpoints(
                mesh.as_triangles()?.face_edges().to_vec(),
            )),
            NodeKind::Faces => Some(Self::Faces),
            NodeKind::FaceFrames => None,
        }
    }

    fn weights(&self, faces: &[Vec<usize>], point: &SurfacePoint) -> Vec<(usize, f64)> {
        match self {
            Self::Corners => faces[point.face]
                .iter()
                .copied()
                .zip(point.weights.iter().copied())
                .collect(),
            Self::EdgeMidpoints(face_edges) => {
                let lambda = point.triangle_coordinates();
                (0..3)
                    .map(|c| (face_edges[point.face][c], 1.0 - 2.0 * lambda[c]))
                    .collect()
            }
            Self::Faces => vec![(point.face, 1.0)],
        }
    }
}

/// Point evaluation by node kinds: vertex values interpolated linearly, edge values by
/// Crouzeix–Raviart (triangles), face values constant per face. The weights of vertex and
/// face nodes sum to 1; Crouzeix–Raviart weights sum to 1 as well (`Σ (1 − 2λ_c) = 1`).
#[derive(Debug, Clone)]
pub struct NodalEvaluation {
    faces: Vec<Vec<usize>>,
    potentials: Interpolation,
    co_potentials: Interpolation,
}

impl NodalEvaluation {
    /// The evaluation of potentials on nodes of kind `potential_kind` and co-potentials on
    /// nodes of kind `co_potential_kind` on `mesh`; `None` when a kind has no interpolant of its
    /// own (face frames, or edge nodes on a polygon mesh).
    pub fn new(
        mesh: &SurfaceMesh,
        potential_kind: NodeKind,
        co_potential_kind: NodeKind,
    ) -> Option<Self> {
        Some(Self {
            faces: (0..mesh.face_count())
                .map(|f| mesh.face(f).to_vec())
                .collect(),
            potentials: Interpolation::of(potential_kind, mesh)?,
            co_potentials: Interpolation::of(co_potential_kind, mesh)?,
        })
    }
}

impl PointEvaluation for NodalEvaluation {
    fn potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)> {
        self.potentials.weights(&self.faces, point)
    }

    fn co_potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)> {
        self.co_potentials.weights(&self.faces, point)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::generate::icosphere;

    /// Linear functions are reproduced by vertex and edge interpolation at any point; face
    /// values are the face's.
    #[test]
    fn vertex_and_edge_interpolation_reproduce_linear_functions() {
        let triangles = icosphere(1);
        let mesh = SurfaceMesh::from(triangles.clone());
        let evaluation = NodalEvaluation::new(&mesh, NodeKind::Vertices, NodeKind::Edges).unwrap();
        let linear = |p: [f64; 3]| 0.3 * p[0] - 1.2 * p[1] + 0.7 * p[2] + 0.1;
        let vertex_values: Vec<f64> = triangles.positions().iter().map(|&p| linear(p)).collect();
        let p = triangles.positions();
        let edge_values: Vec<f64> = triangles
            .edges()
            .iter()
            .map(|&[a, b]| linear(std::array::from_fn(|k| (p[a][k] + p[b][k]) / 2.0)))
            .collect();
        for face in [0, 17, 79] {
            let lambda = [0.2, 0.5, 0.3];
            let point = SurfacePoint::barycentric(face, lambda);
            let corners = triangles.faces()[face];
            let position: [f64; 3] =
                std::array::from_fn(|k| (0..3).map(|c| lambda[c] * p[corners[c]][k]).sum::<f64>());
            let at = |weights: Vec<(usize, f64)>, values: &[f64]| -> f64 {
                weights.iter().map(|&(i, w)| w * values[i]).sum()
            };
            let expected = linear(position);
            assert!(
                (at(evaluation.potential_weights(&point), &vertex_values) - expected).abs() < 1e-14
            );
            assert!(
                (at(evaluation.co_potential_weights(&point), &edge_values) - expected).abs()
                    < 1e-14
            );
        }
        let faces = NodalEvaluation::new(&mesh, NodeKind::Vertices, NodeKind::Faces).unwrap();
        assert_eq!(
            faces.co_potential_weights(&SurfacePoint::barycentric(5, [0.1, 0.1, 0.8])),
            vec![(5, 1.0)]
        );
        assert!(NodalEvaluation::new(&mesh, NodeKind::FaceFrames, NodeKind::Faces).is_none());
    }
}
