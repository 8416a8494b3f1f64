//! The frame, unit normal and corner count of every face: the geometry a
//! [`crate::discretization::FieldSampling`] reads its per-face vectors in, and where it samples
//! them (each face's corner average).

use crate::geometry::dot;
use crate::SurfacePoint;

/// An orthonormal, positively oriented frame `[e1, e2]` (`e2 = n × e1`) and the unit normal `n`
/// of each of the mesh's `F` faces (counter-clockwise orientation; for a triangle
/// `e1 = normalize(p_{i1} − p_{i0})`, for a polygon the first side projected onto the plane normal
/// to its vector area, and `n` along that vector area). Unitless. With each face's number of
/// corners, which places its corner average ([`FaceFrames::centroid`]).
#[derive(Debug, Clone, PartialEq)]
pub struct FaceFrames {
    frames: Vec<[[f64; 3]; 2]>,
    normals: Vec<[f64; 3]>,
    corner_counts: Vec<usize>,
}

impl FaceFrames {
    /// Frames and normals of `F` triangles, `F` entries each. Panics if the two lengths differ
    /// (a programming error: both come from one pass over the faces).
    pub fn new(frames: Vec<[[f64; 3]; 2]>, normals: Vec<[f64; 3]>) -> Self {
        let triangles = vec![3; frames.len()];
        Self::of_polygons(frames, normals, triangles)
    }

    /// Frames, normals and corner counts of `F` polygons, `F` entries each. Panics if the
    /// lengths differ (a programming error: all come from one pass over the faces).
    pub fn of_polygons(
        frames: Vec<[[f64; 3]; 2]>,
        normals: Vec<[f64; 3]>,
        corner_counts: Vec<usize>,
    ) -> Self {
        assert!(
            frames.len() == normals.len() && frames.len() == corner_counts.len(),
            "FaceFrames: one frame, one normal and one corner count per face"
        );
        Self {
            frames,
            normals,
            corner_counts,
        }
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

    /// The corner average of face `face`, every corner weighted `1/n` (for a triangle its
    /// centroid, barycentric `[1/3; 3]`). Panics if out of range.
    pub fn centroid(&self, face: usize) -> SurfacePoint {
        SurfacePoint::centroid(face, self.corner_counts[face])
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
