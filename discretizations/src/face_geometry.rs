//! Per-face geometry shared by every space: frames, normals, areas and the corners in 2D frame
//! coordinates, computed once per mesh; each face as a [`PlanarTriangle`].

use crate::planar_triangle::PlanarTriangle;
use tvf_core::discretization::{DiscretizationError, FaceFrames};
use tvf_core::geometry::{cross, dot, normalize, sub};
use tvf_core::TriangleMesh;

/// Frames and 2D corner coordinates of every face (the frame convention of `docs/conventions.md`:
/// `e1 = normalize(p_{i1} − p_{i0})`, `e2 = n × e1`).
#[derive(Debug, Clone)]
pub struct FaceGeometry {
    /// `[e1, e2]` per face.
    pub frames: Vec<[[f64; 3]; 2]>,
    /// Unit normal per face.
    pub normals: Vec<[f64; 3]>,
    /// Area per face.
    pub areas: Vec<f64>,
    /// Corners of each face in its frame, relative to corner 0 (so `corners[t][0] = (0, 0)`).
    pub corners: Vec<[[f64; 2]; 3]>,
}

impl FaceGeometry {
    /// The frames and normals of every face, as a sampling holds them.
    pub fn face_frames(&self) -> FaceFrames {
        FaceFrames::new(self.frames.clone(), self.normals.clone())
    }

    /// Computes the geometry of every face; fails on a face of zero or non-finite area.
    pub fn new(mesh: &TriangleMesh) -> Result<Self, DiscretizationError> {
        let face_count = mesh.face_count();
        let mut frames = Vec::with_capacity(face_count);
        let mut normals = Vec::with_capacity(face_count);
        let mut areas = Vec::with_capacity(face_count);
        let mut corners = Vec::with_capacity(face_count);
        for (t, face) in mesh.faces().iter().enumerate() {
            let [p0, p1, p2] = face.map(|i| mesh.positions()[i]);
            let scaled = cross(sub(p1, p0), sub(p2, p0));
            let area = 0.5 * dot(scaled, scaled).sqrt();
            if !(area > 0.0 && area.is_finite()) {
                return Err(DiscretizationError::DegenerateFace { face: t, area });
            }
            let n = normalize(scaled);
            let e1 = normalize(sub(p1, p0));
            let e2 = cross(n, e1);
            let local = |p: [f64; 3]| {
                let d = sub(p, p0);
                [dot(d, e1), dot(d, e2)]
            };
            frames.push([e1, e2]);
            normals.push(n);
            areas.push(area);
            corners.push([[0.0, 0.0], local(p1), local(p2)]);
        }
        Ok(Self {
            frames,
            normals,
            areas,
            corners,
        })
    }

    /// Face `t` laid out in its frame: its corners there and its area.
    pub fn triangle(&self, t: usize) -> PlanarTriangle {
        PlanarTriangle {
            corners: self.corners[t],
            area: self.areas[t],
        }
    }
}
