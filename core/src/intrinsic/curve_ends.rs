//! The ends of input edges at the vertices of an intrinsic triangulation, in counter-clockwise
//! order around each vertex: what the roundabouts of the integer coordinates point into.
//!
//! An input vertex is the end of every input edge at it; an intrinsic vertex inserted on an
//! input edge is the end of the two pieces of that edge on either side; a vertex inserted inside
//! an input face is the end of none. The ends around one vertex form a **fan** (one per
//! edge-connected sheet of faces around the vertex; a vertex where several sheets touch has
//! several): cyclic around an interior vertex, a list from the boundary edge with the surface on
//! its left to the other boundary edge at a boundary vertex.

/// One end of an input edge at a vertex: the input edge and the direction it leaves in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct CurveEnd {
    /// The input edge `(a, b)`, `a < b`.
    pub edge: usize,
    /// Whether the edge leaves towards `b` (else towards `a`).
    pub toward_b: bool,
}

impl CurveEnd {
    /// The input face just clockwise of this end (between it and the previous end of its fan):
    /// walking along the input edge in its direction, the face on the right. [`NO_FACE`] outside
    /// a boundary edge.
    pub fn face_before(self, edge_faces: &[[usize; 2]]) -> usize {
        // Leaving towards b, the face on the right of a → b is `right` = edge_faces[e][1].
        edge_faces[self.edge][usize::from(self.toward_b)]
    }
}

/// One fan of ends: a range of [`CurveEnds::ends`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Fan {
    pub start: usize,
    pub len: usize,
    /// Cyclic (interior vertex) or a list from one boundary edge to the other.
    pub closed: bool,
}

/// Every end of every input edge, fan by fan.
#[derive(Debug, Clone, Default)]
pub(crate) struct CurveEnds {
    pub ends: Vec<CurveEnd>,
    /// Fan of each entry of `ends`.
    pub fan_of: Vec<u32>,
    pub fans: Vec<Fan>,
}

impl CurveEnds {
    /// Appends a fan and returns the index of its first end.
    pub fn push_fan(&mut self, ends: &[CurveEnd], closed: bool) -> usize {
        let start = self.ends.len();
        let fan = self.fans.len() as u32;
        self.fans.push(Fan {
            start,
            len: ends.len(),
            closed,
        });
        self.ends.extend_from_slice(ends);
        self.fan_of.extend(std::iter::repeat_n(fan, ends.len()));
        start
    }

    /// The end `steps` places counter-clockwise after end `index` in its fan. `None` when an
    /// open fan ends before that, which consistent integer coordinates never ask for.
    pub fn advance(&self, index: usize, steps: i64) -> Option<usize> {
        let fan = self.fans[self.fan_of[index] as usize];
        let offset = (index - fan.start) as i64 + steps;
        if fan.closed {
            Some(fan.start + offset.rem_euclid(fan.len as i64) as usize)
        } else if (0..fan.len as i64).contains(&offset) {
            Some(fan.start + offset as usize)
        } else {
            None
        }
    }

    /// The input face between end `index` and the one before it.
    pub fn face_before(&self, index: usize, edge_faces: &[[usize; 2]]) -> usize {
        self.ends[index].face_before(edge_faces)
    }
}

/// Marker for "no roundabout": a halfedge leaving a vertex that is no input edge's end.
pub(crate) const NO_END: usize = usize::MAX;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::NO_FACE;

    #[test]
    fn advance_wraps_only_closed_fans() {
        let mut ends = CurveEnds::default();
        let end = |edge| CurveEnd {
            edge,
            toward_b: true,
        };
        let closed = ends.push_fan(&[end(0), end(1), end(2)], true);
        let open = ends.push_fan(&[end(3), end(4)], false);
        assert_eq!(ends.advance(closed + 2, 2), Some(closed + 1));
        assert_eq!(ends.advance(closed, -1), Some(closed + 2));
        assert_eq!(ends.advance(open, 1), Some(open + 1));
        assert_eq!(ends.advance(open + 1, 1), None);
        let edge_faces = [[7, NO_FACE]];
        let forward = CurveEnd {
            edge: 0,
            toward_b: true,
        };
        assert_eq!(forward.face_before(&edge_faces), NO_FACE);
        let backward = CurveEnd {
            edge: 0,
            toward_b: false,
        };
        assert_eq!(backward.face_before(&edge_faces), 7);
    }
}
