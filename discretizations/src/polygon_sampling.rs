//! Sampling and point evaluation of polygonal DEC ([`crate::PolygonDec`]): a 1-form seen as one
//! tangent vector per polygon (its sharp), per-face vectors turned into a 1-form (the flat), and
//! 0- and 2-forms at points.

use crate::edge_averages::edge_integrals;
use crate::polygon_operators::PolygonOperators;
use tvf_core::discretization::{
    FaceFrames, FieldSampling, PointEvaluation, SamplingReproduction, TangentProjection,
};
use tvf_core::geometry::{cross, dot, normalize, scale, sub};
use tvf_core::mesh::Mesh;
use tvf_core::SurfacePoint;

/// The sharp of polygonal DEC as a [`FieldSampling`]: the vector of polygon `f` is
/// `U_f x_f = Σ_c U_f[:, c] x_{e_c}` over its sides' edges (constant on the polygon, in the plane
/// normal to its vector area; pointwise units). Edges the boundary condition fixes (relative
/// forms) get no weight.
#[derive(Debug, Clone)]
pub struct PolygonSampling {
    /// The edge of every side, face by face.
    side_edges: Vec<Vec<usize>>,
    /// `U_f`'s columns, face by face.
    sharp: Vec<Vec<[f64; 3]>>,
    /// `[e1, e2]` per face (the first side projected onto the plane, then `n × e1`) and the unit
    /// normal along its vector area.
    frames: FaceFrames,
    /// The mesh's edges `(a, b)`, `a < b`.
    edges: Vec<[usize; 2]>,
    positions: Vec<[f64; 3]>,
    fixed_edges: Vec<bool>,
}

impl PolygonSampling {
    /// The sampling of `mesh` with the polygons' `operators`; `fixed_edges[e]` marks the edges
    /// the boundary condition fixes to zero.
    pub(crate) fn new<M: Mesh + ?Sized>(
        mesh: &M,
        operators: &[PolygonOperators],
        fixed_edges: Vec<bool>,
    ) -> Self {
        let faces = mesh.face_corners();
        let mut frames = Vec::with_capacity(operators.len());
        let mut normals = Vec::with_capacity(operators.len());
        for (f, ops) in operators.iter().enumerate() {
            let n = scale(ops.vector_area, 1.0 / ops.area);
            let corners = faces.corners(f);
            let side = sub(mesh.positions()[corners[1]], mesh.positions()[corners[0]]);
            let e1 = normalize(sub(side, scale(n, dot(n, side))));
            frames.push([e1, cross(n, e1)]);
            normals.push(n);
        }
        let side_edges: Vec<Vec<usize>> = (0..faces.face_count())
            .map(|f| {
                (0..faces.corners(f).len())
                    .map(|c| mesh.face_edge(f, c))
                    .collect()
            })
            .collect();
        let corner_counts = side_edges.iter().map(Vec::len).collect();
        Self {
            side_edges,
            sharp: operators.iter().map(|o| o.sharp.clone()).collect(),
            frames: FaceFrames::of_polygons(frames, normals, corner_counts),
            edges: mesh.topology().edges().to_vec(),
            positions: mesh.positions().to_vec(),
            fixed_edges,
        }
    }
}

impl FieldSampling for PolygonSampling {
    fn face_frames(&self) -> &FaceFrames {
        &self.frames
    }

    fn field_dimension(&self) -> usize {
        self.edges.len()
    }

    fn reproduction(&self) -> SamplingReproduction {
        SamplingReproduction::LinearGradients
    }

    /// `U_f`'s columns at the polygon's edges (the same at every point of the polygon).
    fn sample_weights(&self, point: &SurfacePoint) -> Vec<(usize, [f64; 3])> {
        let face = point.face;
        self.side_edges[face]
            .iter()
            .zip(&self.sharp[face])
            .filter(|(&e, _)| !self.fixed_edges[e])
            .map(|(&e, &u)| (e, u))
            .collect()
    }

    /// The flat of the per-face vectors: each vector projected onto its polygon's plane (the
    /// dropped normal parts are returned), then `x_e` the average, over the faces of edge
    /// `e = (a, b)`, of `⟨v_f, p_b − p_a⟩`; 0 on fixed edges. On planar polygons the sharp gives
    /// the projected vectors back where they agree across edges.
    fn project_face_vectors(&self, vectors: &[[f64; 3]]) -> TangentProjection {
        let normal_parts = self.frames.normal_parts(vectors);
        let tangents = vectors
            .iter()
            .zip(self.frames.normals())
            .zip(&normal_parts)
            .map(|((&v, &n), &normal_part)| sub(v, scale(n, normal_part)));
        let faces = self.side_edges.iter().map(Vec::as_slice);
        TangentProjection {
            field: edge_integrals(
                &self.edges,
                &self.positions,
                &self.fixed_edges,
                faces.zip(tangents),
            ),
            normal_parts,
        }
    }
}

/// Point evaluation of polygonal DEC: a 0-form at a point of a polygon is its corner weights
/// applied to the corners' values (exact for linear functions, since the point is the same
/// average of the corners' positions); a 2-form's pointwise value is constant on its face.
#[derive(Debug, Clone)]
pub struct PolygonEvaluation {
    /// The corners of every face.
    faces: Vec<Vec<usize>>,
}

impl PolygonEvaluation {
    /// The evaluation on the faces of `mesh`.
    pub(crate) fn new<M: Mesh + ?Sized>(mesh: &M) -> Self {
        let faces = mesh.face_corners();
        Self {
            faces: (0..faces.face_count())
                .map(|f| faces.corners(f).to_vec())
                .collect(),
        }
    }
}

impl PointEvaluation for PolygonEvaluation {
    fn potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)> {
        self.faces[point.face]
            .iter()
            .copied()
            .zip(point.weights.iter().copied())
            .collect()
    }

    fn co_potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)> {
        vec![(point.face, 1.0)]
    }
}
