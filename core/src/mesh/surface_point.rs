//! [`SurfacePoint`]: a point on a mesh's surface as the mesh defines it — a face and weights over
//! its corners (for a triangle, its barycentric coordinates).

use thiserror::Error;

/// A point of face `face`: one weight per corner of the face, in the face's corner order,
/// non-negative and summing to 1. Its position is `Σ_c w_c p_c`; for a triangle the weights are
/// the point's barycentric coordinates, for a planar polygon they are one of its generalised
/// barycentric coordinates (any choice gives the same point), and for a non-planar polygon the
/// point is that average of its corners.
///
/// Points come from files (constraint files: `"face"` with `"barycentric"`), from clicks and
/// pixels on the display triangulation ([`crate::SurfaceMesh::display_point`]) and from face
/// centroids ([`SurfacePoint::centroid`]); [`crate::SurfaceMesh::check_point`] checks one against
/// a mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfacePoint {
    /// The face, `0..F`.
    pub face: usize,
    /// One weight per corner of the face.
    pub weights: Vec<f64>,
}

impl SurfacePoint {
    /// The point of triangle `face` with barycentric coordinates `barycentric` (w.r.t. its
    /// corners `i0, i1, i2`).
    pub fn barycentric(face: usize, barycentric: [f64; 3]) -> Self {
        Self {
            face,
            weights: barycentric.to_vec(),
        }
    }

    /// The corner average of a face with `corner_count` corners: every weight `1/n` (for a
    /// triangle `[1/3; 3]`, its centroid).
    pub fn centroid(face: usize, corner_count: usize) -> Self {
        Self {
            face,
            weights: vec![1.0 / corner_count as f64; corner_count],
        }
    }

    /// The weights as barycentric coordinates, if there are three (a point of a triangle).
    pub fn as_barycentric(&self) -> Option<[f64; 3]> {
        <[f64; 3]>::try_from(self.weights.as_slice()).ok()
    }

    /// The barycentric coordinates of a point that a triangle discretization was handed: its
    /// weights, which are three on every face of the triangle mesh it was built on. Panics
    /// otherwise (a point of another mesh; callers check points against the mesh first).
    pub fn triangle_coordinates(&self) -> [f64; 3] {
        self.as_barycentric().unwrap_or_else(|| {
            panic!(
                "a point of face {} with {} corner weights given to a triangle discretization",
                self.face,
                self.weights.len()
            )
        })
    }
}

/// Why a [`SurfacePoint`] does not belong to a mesh.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SurfacePointError {
    /// The face does not exist.
    #[error("face {face} does not exist (the mesh has {face_count} faces)")]
    FaceOutOfRange {
        /// The face asked for.
        face: usize,
        /// Number of faces.
        face_count: usize,
    },
    /// The number of weights is not the face's number of corners.
    #[error("face {face} has {corners} corners, but {weights} weights were given")]
    WrongWeightCount {
        /// The face.
        face: usize,
        /// Its corners.
        corners: usize,
        /// Weights given.
        weights: usize,
    },
    /// A weight is negative or not finite, or the weights do not sum to 1 (to 1e-9).
    #[error(
        "the weights of a point in face {face} must be non-negative and sum to 1 (got {weights:?})"
    )]
    NotConvex {
        /// The face.
        face: usize,
        /// The weights given.
        weights: Vec<f64>,
    },
}
