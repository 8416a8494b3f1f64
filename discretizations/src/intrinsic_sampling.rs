//! Fields and potentials of a complex on an intrinsic triangulation, seen on the input mesh:
//! [`IntrinsicSampling`] (fields as tangent vectors at input points, and per-input-face vectors
//! as fields, for any [`IntrinsicReconstruction`] of a field in an intrinsic face) and
//! [`IntrinsicEvaluation`] (potentials and co-potentials at input points), both through the
//! common subdivision.

use crate::intrinsic_delaunay::IntrinsicInput;
use crate::intrinsic_input_faces::InputFaces;
use tvf_core::discretization::{
    check_length, DiscretizationError, FaceFrames, FieldSampling, NodeKind, PointEvaluation,
    SamplingReproduction, TangentProjection,
};
use tvf_core::intrinsic::IntrinsicTriangulation;
use tvf_core::{SurfacePoint, TriangleMesh};

/// What a field is inside the faces of an intrinsic triangulation, for [`IntrinsicSampling`]:
/// the vectors of its coefficients at a point of an intrinsic face, and coefficients from one
/// tangent vector per intrinsic face. A vector in intrinsic face `t` is given as a displacement
/// of `t`'s barycentric coordinates (three numbers summing to 0), the form in which the common
/// subdivision carries it to the input.
pub trait IntrinsicReconstruction: Send + Sync {
    /// Number of field coefficients `n1` on `triangulation`.
    fn field_dimension(&self, triangulation: &IntrinsicTriangulation) -> usize;

    /// The coefficients non-zero in intrinsic face `t` of `triangulation` with their vectors at
    /// its point of barycentric coordinates `barycentric` (pointwise units): the field's vector
    /// there is `Σ w_i x_i` over the returned `(i, w_i)`.
    fn face_weights(
        &self,
        triangulation: &IntrinsicTriangulation,
        t: usize,
        barycentric: [f64; 3],
    ) -> Vec<(usize, [f64; 3])>;

    /// The coefficients (`n1` entries) of the field closest to the vector `displacements[t]` in
    /// every intrinsic face `t` of `triangulation` (`F` intrinsic entries).
    fn field_of_displacements(
        &self,
        triangulation: &IntrinsicTriangulation,
        displacements: &[[f64; 3]],
    ) -> Vec<f64>;
}

/// A field on an intrinsic triangulation, reconstructed in its faces by `R`, sampled at points
/// of the **input** faces: `face_count()` is the input's, so a field file holds one 3D vector per
/// input face, the field's value at the input face's centroid
/// ([`FieldSampling::to_face_vectors`]).
///
/// **Sampling** at an input point: the point is mapped to the intrinsic face it lies in (through
/// the cell of the common subdivision that contains it), the reconstruction's vectors are taken
/// there ([`IntrinsicReconstruction::face_weights`]) and carried to the input face by the cell's
/// isometry (lengths and angles kept).
///
/// **Per-face vectors → field**: each input face's vector is projected onto its plane (the
/// dropped normal parts are returned), carried into every intrinsic face that overlaps the face
/// and averaged there weighted by the overlap areas (one tangent vector per intrinsic face), and
/// turned into coefficients by [`IntrinsicReconstruction::field_of_displacements`]. On a flat
/// part of the input a constant vector comes back exactly; across creases it is the area average
/// (see [`SamplingReproduction::Approximate`]).
#[derive(Debug, Clone)]
pub struct IntrinsicSampling<R> {
    faces: InputFaces,
    reconstruction: R,
    /// [`FieldSampling::sample_weights`] at every input face's centroid, computed once: what
    /// [`FieldSampling::to_face_vectors`] applies to every field (a basis converts hundreds).
    centroid_weights: Vec<Vec<(usize, [f64; 3])>>,
}

impl<R: IntrinsicReconstruction> IntrinsicSampling<R> {
    /// The sampling of the fields `reconstruction` describes on the triangulation of `input`, on
    /// the faces of `mesh`. Fails on a degenerate input face.
    pub fn with_reconstruction(
        mesh: &TriangleMesh,
        input: &IntrinsicInput,
        reconstruction: R,
    ) -> Result<Self, DiscretizationError> {
        let mut sampling = Self {
            faces: InputFaces::new(mesh, input)?,
            reconstruction,
            centroid_weights: Vec::new(),
        };
        sampling.centroid_weights = (0..sampling.face_count())
            .map(|f| sampling.sample_weights(&sampling.centroid(f)))
            .collect();
        Ok(sampling)
    }
}

impl<R: IntrinsicReconstruction> FieldSampling for IntrinsicSampling<R> {
    fn face_frames(&self) -> &FaceFrames {
        &self.faces.frames
    }

    fn field_dimension(&self) -> usize {
        self.reconstruction
            .field_dimension(&self.faces.input.triangulation)
    }

    fn reproduction(&self) -> SamplingReproduction {
        SamplingReproduction::Approximate
    }

    fn sample_weights(&self, point: &SurfacePoint) -> Vec<(usize, [f64; 3])> {
        let input = &self.faces.input;
        let (cell, q) = input.locate(point.face, point.triangle_coordinates());
        self.reconstruction
            .face_weights(&input.triangulation, q.face, q.barycentric)
            .into_iter()
            .map(|(i, d)| {
                let on_input = input
                    .overlay
                    .to_input_displacement(cell, d)
                    .unwrap_or([0.0; 3]);
                (i, self.faces.input_vector(point.face, on_input))
            })
            .collect()
    }

    fn to_face_vectors(&self, field: &[f64]) -> Result<Vec<[f64; 3]>, DiscretizationError> {
        check_length("field coefficients", self.field_dimension(), field.len())?;
        Ok(self
            .centroid_weights
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
            .collect())
    }

    fn project_face_vectors(&self, vectors: &[[f64; 3]]) -> TangentProjection {
        let displacements = self.faces.intrinsic_face_displacements(vectors);
        TangentProjection {
            field: self
                .reconstruction
                .field_of_displacements(&self.faces.input.triangulation, &displacements),
            normal_parts: self.faces.frames.normal_parts(vectors),
        }
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
