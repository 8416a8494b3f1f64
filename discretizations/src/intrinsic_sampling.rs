//! Fields and potentials of a complex on an intrinsic triangulation, seen on the input mesh:
//! [`IntrinsicWhitneySampling`] (1-forms on intrinsic edges as tangent vectors at input points,
//! and per-input-face vectors as 1-forms) and [`IntrinsicEvaluation`] (potentials and
//! co-potentials at input points), both through the common subdivision.

use crate::edge_averages::EdgeAverages;
use crate::intrinsic_delaunay::IntrinsicInput;
use crate::intrinsic_input_faces::InputFaces;
use tvf_core::discretization::{
    check_face_vectors, check_length, DiscretizationError, FaceFrames, FieldSampling, NodeKind,
    PointEvaluation, SamplingReproduction, TangentProjection,
};
use tvf_core::intrinsic::corner_cotangents;
use tvf_core::{SurfacePoint, TriangleMesh};

/// Whitney interpolation of 1-forms on the edges of an intrinsic triangulation, sampled at points
/// of the **input** faces: `face_count()` is the input's, so a field file holds one 3D vector per
/// input face, the field's value at the input face's centroid ([`FieldSampling::to_face_vectors`]).
///
/// **Sampling** at an input point: the point is mapped to the intrinsic face it lies in (through
/// the cell of the common subdivision that contains it), the Whitney form of each side of that
/// face, `W_jk = λ_j ∇λ_k − λ_k ∇λ_j`, is evaluated there from the edge lengths (the Gram
/// matrix of the `∇λ` is `⟨∇λ_i, ∇λ_j⟩ = −cot θ_k / 2A`, `|∇λ_i|² = (cot θ_j + cot θ_k) / 2A`),
/// and the vector is carried to the input face by the cell's isometry (lengths and angles kept).
///
/// **Per-face vectors → 1-form** (the de Rham map): each input face's vector is projected onto its
/// plane, carried into every intrinsic face that overlaps the face and averaged there weighted by
/// the overlap areas (one tangent vector per intrinsic face); `x_e = ⟨u_t, p_k − p_j⟩` along each
/// side, averaged over the edge's faces. On a flat part of the input a constant vector comes back
/// exactly; across creases it is the area average (see [`SamplingReproduction::Approximate`]).
///
/// Edges fixed by the boundary condition (relative forms) have no Whitney form and get 0, as in
/// [`crate::WhitneySampling`].
#[derive(Debug, Clone)]
pub struct IntrinsicWhitneySampling {
    faces: InputFaces,
    /// `±1` per side of every intrinsic face: `+1` where it runs along its edge's reference
    /// direction.
    signs: Vec<[f64; 3]>,
    fixed_edges: Vec<bool>,
    /// [`FieldSampling::sample_weights`] at every input face's centroid, computed once: what
    /// [`FieldSampling::to_face_vectors`] applies to every field (a basis converts hundreds).
    centroid_weights: Vec<Vec<(usize, [f64; 3])>>,
}

impl IntrinsicWhitneySampling {
    /// The sampling of 1-forms on the triangulation of `input` on the faces of `mesh`; the edges
    /// flagged in `fixed_edges` (intrinsic `E` entries) are zero in every field. Fails on a
    /// degenerate input face.
    pub fn new(
        mesh: &TriangleMesh,
        input: &IntrinsicInput,
        fixed_edges: Vec<bool>,
    ) -> Result<Self, DiscretizationError> {
        let tri = &input.triangulation;
        let signs = (0..tri.face_count())
            .map(|t| {
                tri.face_edge_orientations(t)
                    .map(|f| if f { 1.0 } else { -1.0 })
            })
            .collect();
        let mut sampling = Self {
            faces: InputFaces::new(mesh, input)?,
            signs,
            fixed_edges,
            centroid_weights: Vec::new(),
        };
        sampling.centroid_weights = centroid_weights(&sampling);
        Ok(sampling)
    }
}

/// [`FieldSampling::sample_weights`] of `sampling` at the centroid of every input face.
pub(crate) fn centroid_weights(sampling: &dyn FieldSampling) -> Vec<Vec<(usize, [f64; 3])>> {
    (0..sampling.face_count())
        .map(|f| sampling.sample_weights(&sampling.centroid(f)))
        .collect()
}

/// The field `field` sampled at every input face's centroid by the precomputed `weights`
/// ([`centroid_weights`]).
pub(crate) fn apply_centroid_weights(
    weights: &[Vec<(usize, [f64; 3])>],
    field: &[f64],
) -> Vec<[f64; 3]> {
    weights
        .iter()
        .map(|weights| {
            let mut v = [0.0; 3];
            for &(i, w) in weights {
                for k in 0..3 {
                    v[k] += w[k] * field[i];
                }
            }
            v
        })
        .collect()
}

/// `⟨∇λ_i, ∇λ_j⟩` of a triangle with side lengths `lengths` (`l_c` opposite corner `c`), from its
/// cotangents and area (1/length²).
fn barycentric_gram(lengths: [f64; 3]) -> [[f64; 3]; 3] {
    let cot = corner_cotangents(lengths);
    let two_area = 2.0 * tvf_core::intrinsic::triangle_area(lengths);
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            if i == j {
                (cot[(i + 1) % 3] + cot[(i + 2) % 3]) / two_area
            } else {
                -cot[3 - i - j] / two_area
            }
        })
    })
}

impl FieldSampling for IntrinsicWhitneySampling {
    fn face_frames(&self) -> &FaceFrames {
        &self.faces.frames
    }

    fn field_dimension(&self) -> usize {
        self.faces.input.triangulation.edge_count()
    }

    fn centroid(&self, face: usize) -> SurfacePoint {
        SurfacePoint::barycentric(face, [1.0 / 3.0; 3])
    }

    fn reproduction(&self) -> SamplingReproduction {
        SamplingReproduction::Approximate
    }

    fn sample_weights(&self, point: &SurfacePoint) -> Vec<(usize, [f64; 3])> {
        let input = &self.faces.input;
        let (cell, q) = input.locate(point.face, point.triangle_coordinates());
        let tri = &input.triangulation;
        let t = q.face;
        let b = q.barycentric;
        let gram = barycentric_gram(tri.face_lengths(t));
        let edges = tri.face_edges(t);
        (0..3)
            .filter(|&c| !self.fixed_edges[edges[c]])
            .map(|c| {
                let (j, k) = ((c + 1) % 3, (c + 2) % 3);
                let sign = self.signs[t][c];
                let d: [f64; 3] =
                    std::array::from_fn(|m| sign * (b[j] * gram[m][k] - b[k] * gram[m][j]));
                let on_input = input
                    .overlay
                    .to_input_displacement(cell, d)
                    .unwrap_or([0.0; 3]);
                (edges[c], self.faces.input_vector(point.face, on_input))
            })
            .collect()
    }

    fn to_face_vectors(&self, field: &[f64]) -> Result<Vec<[f64; 3]>, DiscretizationError> {
        check_length("field coefficients", self.field_dimension(), field.len())?;
        Ok(apply_centroid_weights(&self.centroid_weights, field))
    }

    fn from_face_vectors(
        &self,
        vectors: &[[f64; 3]],
    ) -> Result<TangentProjection, DiscretizationError> {
        check_face_vectors(self.face_count(), vectors)?;
        let tri = &self.faces.input.triangulation;
        let face_vectors = self.faces.intrinsic_face_displacements(vectors);
        let mut averages = EdgeAverages::new(tri.edge_count());
        for (t, u) in face_vectors.iter().enumerate() {
            let l2 = tri.face_lengths(t).map(|l| l * l);
            for (c, e) in tri.face_edges(t).into_iter().enumerate() {
                let (j, k) = ((c + 1) % 3, (c + 2) % 3);
                // ⟨u, p_k − p_j⟩ with u = Σ u_m (p_m − p_j): |p_k − p_j|² = l_c², and
                // ⟨p_c − p_j, p_k − p_j⟩ = (l_k² + l_c² − l_j²) / 2.
                let along = u[k] * l2[c] + u[c] * (l2[k] + l2[c] - l2[j]) / 2.0;
                averages.add(e, self.signs[t][c] * along);
            }
        }
        Ok(TangentProjection {
            field: averages.means(&self.fixed_edges),
            normal_parts: self.faces.normal_parts(vectors),
        })
    }
}

/// Point evaluation of the potentials and co-potentials of a complex on an intrinsic
/// triangulation at points of the input faces, in the intrinsic face the point lies in: nodes on
/// vertices (0-forms, P1) are interpolated linearly (its corners, which may include inserted
/// vertices), nodes on edges (Crouzeix–Raviart) by `1 − 2λ_c` for the side opposite corner `c`,
/// nodes on faces (2-forms) are constant on it.
#[derive(Debug, Clone)]
pub struct IntrinsicEvaluation {
    input: IntrinsicInput,
    /// The node kinds of the potentials and of the co-potentials.
    kinds: [NodeKind; 2],
}

impl IntrinsicEvaluation {
    /// The evaluation of primal forms (0-forms on vertices, 2-forms on faces) at the input points
    /// of `input`.
    pub fn new(input: &IntrinsicInput) -> Self {
        Self::with_node_kinds(input, [NodeKind::Vertices, NodeKind::Faces])
    }

    /// The evaluation of potentials and co-potentials on the node kinds `kinds` (each
    /// [`NodeKind::Vertices`], [`NodeKind::Edges`] or [`NodeKind::Faces`]) at the input points of
    /// `input`.
    pub fn with_node_kinds(input: &IntrinsicInput, kinds: [NodeKind; 2]) -> Self {
        Self {
            input: input.clone(),
            kinds,
        }
    }

    /// The nodes of kind `kind` non-zero at `point` with their values there.
    fn weights(&self, kind: NodeKind, point: &SurfacePoint) -> Vec<(usize, f64)> {
        let (_, q) = self.input.locate(point.face, point.triangle_coordinates());
        let tri = &self.input.triangulation;
        let b = q.barycentric;
        match kind {
            NodeKind::Vertices => {
                let corners = tri.faces()[q.face];
                (0..3).map(|c| (corners[c], b[c])).collect()
            }
            NodeKind::Edges => {
                let edges = tri.face_edges(q.face);
                (0..3).map(|c| (edges[c], 1.0 - 2.0 * b[c])).collect()
            }
            NodeKind::Faces | NodeKind::FaceFrames => vec![(q.face, 1.0)],
        }
    }
}

impl PointEvaluation for IntrinsicEvaluation {
    fn potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)> {
        self.weights(self.kinds[0], point)
    }

    fn co_potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)> {
        self.weights(self.kinds[1], point)
    }
}
