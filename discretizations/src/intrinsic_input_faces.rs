//! [`InputFaces`]: the input mesh's faces as the samplings of complexes on an intrinsic
//! triangulation see them — frames, normals and barycentric gradients of the input faces, and
//! tangent vectors carried between input and intrinsic faces through the common subdivision.

use crate::face_geometry::FaceGeometry;
use crate::intrinsic_delaunay::IntrinsicInput;
use tvf_core::discretization::{DiscretizationError, FaceFrames};
use tvf_core::geometry::{cross, dot, scale, sub};
use tvf_core::TriangleMesh;

/// The faces of the input mesh of an intrinsic triangulation, with the correspondence.
#[derive(Debug, Clone)]
pub(crate) struct InputFaces {
    /// The intrinsic triangulation and its common subdivision with the input.
    pub(crate) input: IntrinsicInput,
    faces: Vec<[usize; 3]>,
    positions: Vec<[f64; 3]>,
    /// `[e1, e2]` and the unit normal of every input face (the convention of [`FaceGeometry`]).
    pub(crate) frames: FaceFrames,
    /// `∇λ_c` of the corners of every input face (3D, in the face plane, 1/length).
    gradients: Vec<[[f64; 3]; 3]>,
}

impl InputFaces {
    /// The faces of `mesh`, the input of `input`. Fails on a degenerate input face.
    pub(crate) fn new(
        mesh: &TriangleMesh,
        input: &IntrinsicInput,
    ) -> Result<Self, DiscretizationError> {
        let geometry = FaceGeometry::new(mesh)?;
        let gradients = mesh
            .faces()
            .iter()
            .enumerate()
            .map(|(t, face)| {
                let p = face.map(|i| mesh.positions()[i]);
                let two_area = 2.0 * geometry.areas[t];
                std::array::from_fn(|c| {
                    let opposite = sub(p[(c + 2) % 3], p[(c + 1) % 3]);
                    scale(cross(geometry.normals[t], opposite), 1.0 / two_area)
                })
            })
            .collect();
        Ok(Self {
            input: input.clone(),
            faces: mesh.faces().to_vec(),
            positions: mesh.positions().to_vec(),
            frames: geometry.face_frames(),
            gradients,
        })
    }

    /// A displacement of barycentric coordinates of input face `f` as a 3D vector.
    pub(crate) fn input_vector(&self, f: usize, d: [f64; 3]) -> [f64; 3] {
        let p = self.faces[f].map(|i| self.positions[i]);
        std::array::from_fn(|k| d[0] * p[0][k] + d[1] * p[1][k] + d[2] * p[2][k])
    }

    /// The tangent vector of every intrinsic face (as a displacement of its barycentric
    /// coordinates): the area average of the input faces' vectors `vectors` (one per input face,
    /// projected onto its plane) over the cells of the face. On a flat part of the input a
    /// constant vector comes back exactly; across creases it is the area average.
    pub(crate) fn intrinsic_face_displacements(&self, vectors: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let overlay = &self.input.overlay;
        (0..overlay.intrinsic_face_count())
            .map(|t| {
                let mut sum = [0.0; 3];
                let mut area = 0.0;
                for &i in overlay.intrinsic_face_cells(t) {
                    let cell = overlay.cell(i);
                    let gradients = &self.gradients[cell.input_face];
                    let v = vectors[cell.input_face];
                    let d: [f64; 3] = std::array::from_fn(|c| dot(gradients[c], v));
                    if let Some(there) = overlay.to_intrinsic_displacement(i, d) {
                        for k in 0..3 {
                            sum[k] += cell.area * there[k];
                        }
                        area += cell.area;
                    }
                }
                if area > 0.0 {
                    sum.map(|x| x / area)
                } else {
                    [0.0; 3]
                }
            })
            .collect()
    }
}
