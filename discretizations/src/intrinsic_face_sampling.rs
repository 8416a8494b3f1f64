//! [`IntrinsicFaceSampling`]: piecewise constant tangent fields on the faces of an intrinsic
//! triangulation (the `X_h` of the finite element complexes built from edge lengths), sampled at
//! points of the input faces through the common subdivision.

use crate::intrinsic_delaunay::IntrinsicInput;
use crate::intrinsic_input_faces::InputFaces;
use crate::intrinsic_sampling::{apply_centroid_weights, centroid_weights};
use crate::planar_triangle::PlanarTriangle;
use tvf_core::discretization::{
    check_face_vectors, check_length, DiscretizationError, FaceFrames, FieldSampling,
    SamplingReproduction, TangentProjection,
};
use tvf_core::{SurfacePoint, TriangleMesh};

/// One tangent vector per **intrinsic** face, stored as `(x[2t], x[2t+1])` in the frame of the
/// face laid out from its lengths ([`PlanarTriangle::from_lengths`]: `e1` along corner 0 →
/// corner 1, `e2` its +π/2 rotation; pointwise coefficients), sampled at points of the **input**
/// faces: `face_count()` is the input's, so a field file holds one 3D vector per input face, the
/// field's value at the input face's centroid.
///
/// **Sampling** at an input point: the point is mapped to the intrinsic face it lies in (through
/// the cell of the common subdivision that contains it), and that face's vector is carried to
/// the input face by the cell's isometry (lengths and angles kept). The field is constant on each
/// intrinsic face, so an input face that several intrinsic faces cross shows the one at its
/// centroid.
///
/// **Per-face vectors → field**: each input face's vector is projected onto its plane, carried
/// into every intrinsic face that overlaps the face and averaged there weighted by the overlap
/// areas. On a flat part of the input a constant vector comes back exactly; across creases it
/// is the area average (see [`SamplingReproduction::Approximate`]).
#[derive(Debug, Clone)]
pub struct IntrinsicFaceSampling {
    faces: InputFaces,
    /// Every intrinsic face laid out from its lengths.
    triangles: Vec<PlanarTriangle>,
    /// [`FieldSampling::sample_weights`] at every input face's centroid, computed once.
    centroid_weights: Vec<Vec<(usize, [f64; 3])>>,
}

impl IntrinsicFaceSampling {
    /// The sampling of face fields on the triangulation of `input`, whose faces are laid out as
    /// `triangles` ([`PlanarTriangle::of_intrinsic_faces`]), on the faces of `mesh`. Fails on a
    /// degenerate input face.
    pub fn new(
        mesh: &TriangleMesh,
        input: &IntrinsicInput,
        triangles: Vec<PlanarTriangle>,
    ) -> Result<Self, DiscretizationError> {
        let mut sampling = Self {
            faces: InputFaces::new(mesh, input)?,
            triangles,
            centroid_weights: Vec::new(),
        };
        sampling.centroid_weights = centroid_weights(&sampling);
        Ok(sampling)
    }
}

impl FieldSampling for IntrinsicFaceSampling {
    fn face_frames(&self) -> &FaceFrames {
        &self.faces.frames
    }

    fn field_dimension(&self) -> usize {
        2 * self.triangles.len()
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
        let t = q.face;
        [[1.0, 0.0], [0.0, 1.0]]
            .into_iter()
            .enumerate()
            .map(|(k, axis)| {
                // The frame axis e_k of the intrinsic face as a displacement of its barycentric
                // coordinates, carried to the input face.
                let d = self.triangles[t].displacement_of_vector(axis);
                let on_input = input
                    .overlay
                    .to_input_displacement(cell, d)
                    .unwrap_or([0.0; 3]);
                (2 * t + k, self.faces.input_vector(point.face, on_input))
            })
            .collect()
    }

    fn to_face_vectors(&self, field: &[f64]) -> Result<Vec<[f64; 3]>, DiscretizationError> {
        check_length(
            "tangent field coefficients",
            self.field_dimension(),
            field.len(),
        )?;
        Ok(apply_centroid_weights(&self.centroid_weights, field))
    }

    fn from_face_vectors(
        &self,
        vectors: &[[f64; 3]],
    ) -> Result<TangentProjection, DiscretizationError> {
        check_face_vectors(self.face_count(), vectors)?;
        let field = self
            .faces
            .intrinsic_face_displacements(vectors)
            .iter()
            .zip(&self.triangles)
            .flat_map(|(&d, triangle)| triangle.vector_of_displacement(d))
            .collect();
        Ok(TangentProjection {
            field,
            normal_parts: self.faces.normal_parts(vectors),
        })
    }
}
