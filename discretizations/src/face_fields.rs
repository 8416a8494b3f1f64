//! [`FaceFields`]: the space `X_h` of piecewise constant tangent fields.

use crate::face_geometry::FaceGeometry;
use sprs::CsMat;
use tvf_core::discretization::{DiscretizationError, FieldSpace};
use tvf_core::SurfaceMesh;

/// Piecewise constant tangent fields, one vector per face in the frame
/// `e1 = normalize(p_{i1} − p_{i0})`, `e2 = n × e1`; `M_X = diag(A_t, A_t)`, `J` the +π/2 rotation.
#[derive(Debug, Clone)]
pub struct FaceFields {
    frames: Vec<[[f64; 3]; 2]>,
    normals: Vec<[f64; 3]>,
    mass: Vec<f64>,
    rotation: CsMat<f64>,
    face_components: Vec<usize>,
}

impl FaceFields {
    /// Builds the field space of `mesh`; fails on a degenerate face.
    pub fn new(mesh: &SurfaceMesh) -> Result<Self, DiscretizationError> {
        Ok(Self::from_geometry(mesh, &FaceGeometry::new(mesh)?))
    }

    /// Builds the field space from precomputed face geometry.
    pub fn from_geometry(mesh: &SurfaceMesh, geometry: &FaceGeometry) -> Self {
        let face_count = mesh.face_count();
        let mass = geometry.areas.iter().flat_map(|&a| [a, a]).collect();
        // Row 2t: (−1 at column 2t+1); row 2t+1: (+1 at column 2t).
        let indptr = (0..=2 * face_count).collect();
        let indices = (0..face_count).flat_map(|t| [2 * t + 1, 2 * t]).collect();
        let data = (0..face_count).flat_map(|_| [-1.0, 1.0]).collect();
        let rotation = CsMat::new((2 * face_count, 2 * face_count), indptr, indices, data);
        Self {
            frames: geometry.frames.clone(),
            normals: geometry.normals.clone(),
            mass,
            rotation,
            face_components: mesh.face_components().to_vec(),
        }
    }
}

impl FieldSpace for FaceFields {
    fn face_count(&self) -> usize {
        self.frames.len()
    }

    fn mass(&self) -> &[f64] {
        &self.mass
    }

    fn rotation(&self) -> &CsMat<f64> {
        &self.rotation
    }

    fn frame(&self, face: usize) -> [[f64; 3]; 2] {
        self.frames[face]
    }

    fn normal(&self, face: usize) -> [f64; 3] {
        self.normals[face]
    }

    fn face_components(&self) -> &[usize] {
        &self.face_components
    }
}
