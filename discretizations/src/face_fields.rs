//! [`FaceFields`]: the space `X_h` of piecewise constant tangent fields, one vector per face.

use crate::face_geometry::FaceGeometry;
use sprs::CsMat;
use tvf_core::discretization::{
    check_length, DiscretizationError, FaceFrames, FieldRotation, FieldSampling, TangentProjection,
};
use tvf_core::geometry::dot;
use tvf_core::{SurfacePoint, TriangleMesh};

/// Piecewise constant tangent fields, one vector per face stored as `(x[2t], x[2t+1])` in the
/// frame `e1 = normalize(p_{i1} − p_{i0})`, `e2 = n × e1` (pointwise coefficients);
/// `M_X = diag(A_t, A_t)`, `J` the +π/2 rotation. Sampling is exact (the field is constant on
/// each face); per-face vectors become fields by projection onto the face plane.
#[derive(Debug, Clone)]
pub struct FaceFields {
    frames: FaceFrames,
    mass: Vec<f64>,
    rotation: CsMat<f64>,
}

impl FaceFields {
    /// Builds the field space of `mesh`; fails on a degenerate face.
    pub fn new(mesh: &TriangleMesh) -> Result<Self, DiscretizationError> {
        Ok(Self::from_geometry(&FaceGeometry::new(mesh)?))
    }

    /// Builds the field space from precomputed face geometry.
    pub fn from_geometry(geometry: &FaceGeometry) -> Self {
        let face_count = geometry.areas.len();
        let mass = geometry.areas.iter().flat_map(|&a| [a, a]).collect();
        // Row 2t: (−1 at column 2t+1); row 2t+1: (+1 at column 2t).
        let indptr = (0..=2 * face_count).collect();
        let indices = (0..face_count).flat_map(|t| [2 * t + 1, 2 * t]).collect();
        let data = (0..face_count).flat_map(|_| [-1.0, 1.0]).collect();
        let rotation = CsMat::new((2 * face_count, 2 * face_count), indptr, indices, data);
        Self {
            frames: geometry.face_frames(),
            mass,
            rotation,
        }
    }

    /// Diagonal of `M_X` (`2F` entries: the face area `A_t` twice per face, units of area).
    pub fn mass(&self) -> &[f64] {
        &self.mass
    }
}

impl FieldSampling for FaceFields {
    fn face_frames(&self) -> &FaceFrames {
        &self.frames
    }

    fn field_dimension(&self) -> usize {
        2 * self.frames.len()
    }

    /// `v = x[2t] e1 + x[2t+1] e2` anywhere in face `t`.
    fn sample_weights(&self, point: &SurfacePoint) -> Vec<(usize, [f64; 3])> {
        let face = point.face;
        let [e1, e2] = self.frames.frame(face);
        vec![(2 * face, e1), (2 * face + 1, e2)]
    }

    /// Exactly `(1, 0)` at `2t` and `(0, 1)` at `2t + 1`.
    fn sample_frame_weights(&self, point: &SurfacePoint) -> Vec<(usize, [f64; 2])> {
        let face = point.face;
        vec![(2 * face, [1.0, 0.0]), (2 * face + 1, [0.0, 1.0])]
    }

    /// `(x[2t], x[2t+1]) = (v·e1, v·e2)`: the orthogonal projection onto the face plane.
    fn project_face_vectors(&self, vectors: &[[f64; 3]]) -> TangentProjection {
        let mut field = Vec::with_capacity(self.field_dimension());
        let mut normal_parts = Vec::with_capacity(self.face_count());
        for (t, &v) in vectors.iter().enumerate() {
            let [e1, e2] = self.frames.frame(t);
            field.push(dot(v, e1));
            field.push(dot(v, e2));
            normal_parts.push(dot(v, self.frames.normal(t)));
        }
        TangentProjection {
            field,
            normal_parts,
        }
    }

    fn to_face_vectors(&self, field: &[f64]) -> Result<Vec<[f64; 3]>, DiscretizationError> {
        check_length(
            "tangent field coefficients",
            self.field_dimension(),
            field.len(),
        )?;
        Ok(self
            .frames
            .frames()
            .iter()
            .zip(field.chunks_exact(2))
            .map(|([e1, e2], ab)| std::array::from_fn(|k| ab[0] * e1[k] + ab[1] * e2[k]))
            .collect())
    }
}

impl FieldRotation for FaceFields {
    /// Block diagonal with blocks `[[0, −1], [1, 0]]`, i.e. `(a, b) ↦ (−b, a)`.
    fn rotation(&self) -> &CsMat<f64> {
        &self.rotation
    }
}
