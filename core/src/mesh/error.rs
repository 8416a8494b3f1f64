//! Errors found while building a mesh from positions and faces.

use thiserror::Error;

/// A defect that makes a list of positions and faces unusable as a tvf surface mesh.
///
/// Indices are 0-based positions in the arrays handed to [`crate::TriangleMesh::new`].
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
    /// A face has zero area (collinear or coincident corners).
    #[error("face {face} has zero area")]
    ZeroAreaFace {
        /// Face index.
        face: usize,
    },
}
