//! Errors found while building a mesh from positions and faces.

use thiserror::Error;

/// A defect that makes a list of positions and faces unusable as a tvf surface mesh.
///
/// Indices are 0-based positions in the arrays handed to [`crate::TriangleMesh::new`] or
/// [`crate::PolygonMesh::new`].
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MeshError {
    /// The mesh has no faces.
    #[error("the mesh has no faces")]
    NoFaces,
    /// A face refers to a vertex that does not exist.
    #[error("face {face} refers to vertex {index}, but there are only {vertex_count} vertices")]
    IndexOutOfRange {
        /// Face index.
        face: usize,
        /// The offending vertex index.
        index: usize,
        /// Number of vertices.
        vertex_count: usize,
    },
    /// A face uses the same vertex twice.
    #[error("face {face} uses vertex {vertex} more than once")]
    RepeatedVertexInFace {
        /// Face index.
        face: usize,
        /// The repeated vertex.
        vertex: usize,
    },
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate")]
    NonFiniteCoordinate {
        /// Vertex index.
        vertex: usize,
    },
    /// More than two faces share an edge.
    #[error("edge ({a}, {b}) is shared by {face_count} faces (non-manifold edge)")]
    NonManifoldEdge {
        /// Smaller vertex index of the edge.
        a: usize,
        /// Larger vertex index of the edge.
        b: usize,
        /// Number of faces containing the edge.
        face_count: usize,
    },
    /// Two faces traverse their common edge in the same direction.
    #[error("faces {face_a} and {face_b} are inconsistently oriented across edge ({a}, {b})")]
    InconsistentOrientation {
        /// First face.
        face_a: usize,
        /// Second face.
        face_b: usize,
        /// Smaller vertex index of the shared edge.
        a: usize,
        /// Larger vertex index of the shared edge.
        b: usize,
    },
    /// The faces around a vertex form more than one edge-connected fan (e.g. two cones
    /// touching at their tips, a "bowtie").
    #[error("vertex {vertex} is non-manifold: its faces form {fans} separate fans")]
    NonManifoldVertex {
        /// Vertex index.
        vertex: usize,
        /// Number of edge-connected fans of faces around the vertex (at least 2).
        fans: usize,
    },
    /// No choice of face orientations makes all neighbours consistent (e.g. a Möbius strip).
    ///
    /// Distinguished from [`MeshError::InconsistentOrientation`], which is reported when a
    /// consistent orientation exists but the file does not use it.
    #[error(
        "the surface is non-orientable: reorienting from face {face_a} conflicts at face {face_b}"
    )]
    NonOrientable {
        /// Face where the reorientation started (first face of its component).
        face_a: usize,
        /// Face whose required orientation contradicts itself.
        face_b: usize,
    },
    /// A face has zero area (collinear or coincident corners; for a polygon, a zero vector
    /// area `½ Σ p_i × p_{i+1}`).
    #[error("face {face} has zero area")]
    ZeroAreaFace {
        /// Face index.
        face: usize,
    },
    /// A face lists fewer than three corners.
    #[error("face {face} has {corners} corners (a face needs at least three)")]
    TooFewCorners {
        /// Face index.
        face: usize,
        /// Number of corners it lists.
        corners: usize,
    },
    /// A polygon that ear clipping of its own corners, seen along its vector area, cannot split
    /// into triangles facing the way of the vector area (it is flat up to rounding, or folds).
    #[error(
        "face {face} cannot be split into triangles by its own corners: seen along its vector \
         area it is flat or folds over itself"
    )]
    PolygonNotTriangulable {
        /// Face index.
        face: usize,
    },
    /// A polygon folds over itself: seen along its vector area (projected to the plane
    /// orthogonal to it), two of its sides that are not neighbours meet, as for a polygon whose
    /// corners wind around more than once or a bow tie. A simple non-convex polygon does not
    /// fold.
    #[error(
        "face {face} folds over itself: seen along its vector area, its side from corner {side} \
         and its side from corner {other_side} cross"
    )]
    PolygonFolds {
        /// Face index.
        face: usize,
        /// The first side that meets another (side `c` joins corner `c` to corner `c + 1`,
        /// 0-based within the face).
        side: usize,
        /// The side it meets.
        other_side: usize,
    },
}
