//! Errors of intrinsic triangulations: input they cannot be built on, limits reached, and
//! correspondence queries that do not fit.

use thiserror::Error;

/// Why an intrinsic triangulation, its Delaunay flipping or refinement, or its correspondence
/// with the input could not be computed. Indices are those of the input mesh unless said
/// otherwise.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum IntrinsicError {
    /// A face's edge lengths do not form a triangle of positive area.
    #[error("face {face} is degenerate: its edge lengths {lengths:?} do not form a triangle of positive area (collinear or coincident corners)")]
    DegenerateFace {
        /// Input face.
        face: usize,
        /// Its edge lengths, opposite corners 0, 1, 2.
        lengths: [f64; 3],
    },
    /// An edge length is not finite (coordinates too large).
    #[error("edge {edge} has a non-finite length (coordinates too large)")]
    NonFiniteLength {
        /// Input edge.
        edge: usize,
    },
    /// Round-off in flips or splits of nearly flat faces left an intrinsic face whose lengths
    /// are not those of a triangle (never seen on valid meshes; reported rather than returning
    /// non-finite geometry).
    #[error("intrinsic face {face} has lengths {lengths:?}, not those of a triangle (round-off on nearly flat input faces)")]
    DegenerateIntrinsicFace {
        /// Intrinsic face.
        face: usize,
        /// Its edge lengths.
        lengths: [f64; 3],
    },
    /// Delaunay flipping made its maximum number of flips without reaching a Delaunay
    /// triangulation (a guard against round-off cycles; exact arithmetic always terminates).
    #[error("intrinsic Delaunay flipping stopped after {flips} flips (its limit) with edges still to flip")]
    FlipLimit {
        /// Flips made.
        flips: usize,
    },
    /// Refinement needed more inserted vertices than allowed.
    #[error("intrinsic Delaunay refinement stopped at {inserted} inserted vertices (its limit) with {remaining} edges still not strictly Delaunay")]
    InsertionLimit {
        /// Vertices inserted.
        inserted: usize,
        /// Edges still to split.
        remaining: usize,
    },
    /// The mesh given is not the input the triangulation was built from.
    #[error("the mesh given has {given:?} vertices, edges and faces, but the intrinsic triangulation was built on one with {expected:?}")]
    InputMismatch {
        /// Vertex, edge and face counts of the input.
        expected: [usize; 3],
        /// Those of the mesh given.
        given: [usize; 3],
    },
    /// A face index out of range in a point query.
    #[error("face {face} does not exist (the mesh has {face_count} faces)")]
    NoSuchFace {
        /// The face asked for.
        face: usize,
        /// Number of faces.
        face_count: usize,
    },
    /// A point with non-finite barycentric coordinates.
    #[error("the point in face {face} has non-finite barycentric coordinates {barycentric:?}")]
    InvalidPoint {
        /// Its face.
        face: usize,
        /// Its coordinates.
        barycentric: [f64; 3],
    },
    /// The correspondence could not be followed: an internal consistency check failed (a bug,
    /// or round-off in tracing beyond what it tolerates). Names what was being done.
    #[error("the correspondence with the input is inconsistent: {0}")]
    Inconsistent(String),
}
