//! The frame and unit normal of every face: the geometry a [`crate::discretization::FieldSampling`]
//! reads its per-face vectors in.

use crate::geometry::dot;

/// An orthonormal, positively oriented frame `[e1, e2]` (`e2 = n × e1`) and the unit normal `n`
/// of each of the mesh's `F` faces (counter-clockwise orientation; for a triangle
/// `e1 = normalize(p_{i1} − p_{i0})`, for a polygon the first side projected onto the plane normal
/// to its vector area, and `n` along that vector area). Unitless.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceFrames {
    frames: Vec<[[f64; 3]; 2]>,
    normals: Vec<[f64; 3]>,
}

impl FaceFrames {
    /// Frames and normals, `F` entries each. Panics if the two lengths differ (a programming
    /// error: both come from one pass over the faces).
    pub fn new(frames: Vec<[[f64; 3]; 2]>, normals: Vec<[f64; 3]>) -> Self {
        assert_eq!(
            frames.len(),
            normals.len(),
            "FaceFrames: one frame and one normal per face"
        );
        Self { frames, normals }
    }

    /// Number of faces `F`.
    pub fn len(&self) -> usize {
        self.frames.len()
    }

    /// Whether there are no faces.
    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }

    /// `[e1, e2]` of face `face` (panics if out of range).
    pub fn frame(&self, face: usize) -> [[f64; 3]; 2] {
        self.frames[face]
    }

    /// The unit normal of face `face` (panics if out of range).
    pub fn normal(&self, face: usize) -> [f64; 3] {
        self.normals[face]
    }

    /// All frames, `F` entries.
    pub fn frames(&self) -> &[[[f64; 3]; 2]] {
        &self.frames
    }

    /// All normals, `F` entries.
    pub fn normals(&self) -> &[[f64; 3]] {
        &self.normals
    }

    /// The normal component `v_f · n_f` of every face's vector in `vectors` (one per face, as
    /// the caller has checked): what projecting them onto the face planes drops.
    pub fn normal_parts(&self, vectors: &[[f64; 3]]) -> Vec<f64> {
        vectors
            .iter()
            .zip(&self.normals)
            .map(|(&v, &n)| dot(v, n))
            .collect()
    }
}
