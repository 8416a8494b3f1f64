//! [`IntrinsicFaceSampling`]: piecewise constant tangent fields on the faces of an intrinsic
//! triangulation (the `X_h` of the finite element complexes built from edge lengths,
//! [`IntrinsicFaceVectors`]), sampled at points of the input faces through the common
//! subdivision.

use crate::intrinsic_delaunay::IntrinsicInput;
use crate::intrinsic_sampling::{IntrinsicReconstruction, IntrinsicSampling};
use crate::planar_triangle::PlanarTriangle;
use tvf_core::discretization::DiscretizationError;
use tvf_core::intrinsic::IntrinsicTriangulation;
use tvf_core::TriangleMesh;

/// One tangent vector per **intrinsic** face, sampled at points of the **input** faces
/// ([`IntrinsicSampling`]). The field is constant on each intrinsic face, so an input face that
/// several intrinsic faces cross shows the one at its centroid; per-face vectors become a field
/// as the area average of the input faces' vectors over each intrinsic face.
pub type IntrinsicFaceSampling = IntrinsicSampling<IntrinsicFaceVectors>;

/// Piecewise constant tangent fields on an intrinsic triangulation as an
/// [`IntrinsicReconstruction`]: one vector per intrinsic face, stored as `(x[2t], x[2t+1])` in
/// the frame of the face laid out from its lengths ([`PlanarTriangle::from_lengths`]: `e1` along
/// corner 0 → corner 1, `e2` its +π/2 rotation; pointwise coefficients).
#[derive(Debug, Clone)]
pub struct IntrinsicFaceVectors {
    /// Every intrinsic face laid out from its lengths.
    triangles: Vec<PlanarTriangle>,
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
        Self::with_reconstruction(mesh, input, IntrinsicFaceVectors { triangles })
    }
}

impl IntrinsicReconstruction for IntrinsicFaceVectors {
    fn field_dimension(&self, _: &IntrinsicTriangulation) -> usize {
        2 * self.triangles.len()
    }

    /// The frame axes `e1`, `e2` of face `t` (the same at every point of it).
    fn face_weights(
        &self,
        _: &IntrinsicTriangulation,
        t: usize,
        _: [f64; 3],
    ) -> Vec<(usize, [f64; 3])> {
        [[1.0, 0.0], [0.0, 1.0]]
            .into_iter()
            .enumerate()
            .map(|(k, axis)| (2 * t + k, self.triangles[t].displacement_of_vector(axis)))
            .collect()
    }

    /// Each face's vector in its frame.
    fn field_of_displacements(
        &self,
        _: &IntrinsicTriangulation,
        displacements: &[[f64; 3]],
    ) -> Vec<f64> {
        displacements
            .iter()
            .zip(&self.triangles)
            .flat_map(|(&d, triangle)| triangle.vector_of_displacement(d))
            .collect()
    }
}
