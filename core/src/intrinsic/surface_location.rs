//! Points of a triangle mesh given by a face and barycentric coordinates, and where an
//! intrinsic vertex sits on the input surface.

/// A point of a triangle mesh: a face and barycentric coordinates in it
/// (`barycentric[c]` weighs corner `c`; the three sum to 1 and are in `[0, 1]` inside the face).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrianglePoint {
    /// Face index.
    pub face: usize,
    /// Barycentric coordinates, one per corner of the face.
    pub barycentric: [f64; 3],
}

/// Where a vertex of an intrinsic triangulation sits on the input surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum InputLocation {
    /// An input vertex (every input vertex is an intrinsic vertex with the same index).
    Vertex(usize),
    /// A point inside input edge `(a, b)` (numbered as [`crate::TriangleMesh::edges`]):
    /// `(1 − t) a + t b` with `0 < t < 1`.
    Edge {
        /// Input edge.
        edge: usize,
        /// Fraction of the way from `a` to `b`.
        t: f64,
    },
    /// A point inside an input face.
    Face(TrianglePoint),
}

/// Barycentric coordinates of the point `(1 − t) a + t b` of the segment between vertices `a`
/// and `b` in the face with corners `face`; `None` if `a` or `b` is not a corner of it.
pub(crate) fn segment_point_barycentric(
    face: [usize; 3],
    a: usize,
    b: usize,
    t: f64,
) -> Option<[f64; 3]> {
    let ca = face.iter().position(|&v| v == a)?;
    let cb = face.iter().position(|&v| v == b)?;
    let mut bary = [0.0; 3];
    bary[ca] = 1.0 - t;
    bary[cb] = t;
    Some(bary)
}

/// Barycentric coordinates of vertex `v` in the face with corners `face`.
pub(crate) fn vertex_barycentric(face: [usize; 3], v: usize) -> Option<[f64; 3]> {
    let c = face.iter().position(|&w| w == v)?;
    let mut bary = [0.0; 3];
    bary[c] = 1.0;
    Some(bary)
}

/// Barycentric coordinates of `location` in input face `f` (corners `input_faces[f]`), `None`
/// if it is not on that face.
pub(crate) fn location_barycentric(
    location: InputLocation,
    f: usize,
    input_faces: &[[usize; 3]],
    input_edges: &[[usize; 2]],
) -> Option<[f64; 3]> {
    let face = input_faces[f];
    match location {
        InputLocation::Vertex(v) => vertex_barycentric(face, v),
        InputLocation::Edge { edge, t } => {
            let [a, b] = input_edges[edge];
            segment_point_barycentric(face, a, b, t)
        }
        InputLocation::Face(point) => (point.face == f).then_some(point.barycentric),
    }
}
