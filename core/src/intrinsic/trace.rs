//! Tracing the pieces of input edges through the intrinsic triangulation: which intrinsic edges
//! a piece crosses, in order (exact, from the integer coordinates), and where (from the edge
//! lengths, by laying the strip of crossed faces out flat).
//!
//! A **piece** is an input edge between two consecutive intrinsic vertices on it: the whole
//! input edge unless refinement inserted vertices on it. A piece that lies along an intrinsic
//! edge crosses nothing; every other piece leaves its first vertex as an arc emanating from a
//! corner and enters the next face through the opposite side.

use super::curve_ends::{CurveEnd, NO_END};
use super::error::IntrinsicError;
use super::length_geometry::{layout, place_left};
use super::normal_coordinates::{ArcAt, TriangleArcs};
use super::surface_location::InputLocation;
use super::triangulation::{IntrinsicTriangulation, NO_HALFEDGE};

/// A corner of a face and one of the arcs emanating from it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct CornerArc {
    pub face: usize,
    pub corner: usize,
    /// Counter-clockwise index among the arcs emanating from the corner.
    pub index: i64,
}

/// The crossings of one piece, in order from its start: the halfedge entered (the piece passes
/// from its twin's face into its face) and the position along it, 0-based from its tail.
#[derive(Debug, Clone, Default)]
pub(crate) struct PiecePath {
    pub start: Option<CornerArc>,
    pub crossings: Vec<(usize, i64)>,
    pub end: Option<CornerArc>,
}

impl IntrinsicTriangulation {
    /// The input edge end that arc `arc` is (looked up through the roundabout of the halfedge
    /// leaving the corner).
    pub(crate) fn end_of_arc(&self, arc: CornerArc) -> Result<(usize, CurveEnd), IntrinsicError> {
        let out = 3 * arc.face + (arc.corner + 2) % 3;
        let r = self.roundabout[out];
        let steps = i64::from(self.is_along_input(out)) + arc.index;
        let index = (r != NO_END)
            .then(|| self.curve_ends.advance(r, steps))
            .flatten()
            .ok_or_else(|| {
                IntrinsicError::Inconsistent(format!(
                    "an input edge leaves corner {} of intrinsic face {}, whose vertex has no such end",
                    arc.corner, arc.face
                ))
            })?;
        Ok((index, self.curve_ends.ends[index]))
    }

    /// Follows a piece that enters the face of halfedge `h` at position `p` until it ends at a
    /// vertex, appending every crossing (the first included) to `crossings`.
    pub(crate) fn walk_piece(
        &self,
        mut h: usize,
        mut p: i64,
        crossings: &mut Vec<(usize, i64)>,
    ) -> Result<CornerArc, IntrinsicError> {
        // A piece crosses every intrinsic edge at most as often as the edge is crossed at all.
        let limit = crossings.len() + self.crossing_total;
        loop {
            crossings.push((h, p));
            if crossings.len() > limit {
                return Err(IntrinsicError::Inconsistent(
                    "an input edge crosses more intrinsic edges than there are crossings".into(),
                ));
            }
            let (t, s) = (h / 3, h % 3);
            let arcs = TriangleArcs::new(self.face_normals(t));
            let (exit_side, exit_position) = match arcs.arc_at(s, p) {
                ArcAt::Emanating { corner, index } => {
                    return Ok(CornerArc {
                        face: t,
                        corner,
                        index,
                    })
                }
                ArcAt::Corner { corner, index } if corner == (s + 1) % 3 => {
                    let side = (s + 2) % 3;
                    (side, arcs.crossings[side] - 1 - index)
                }
                ArcAt::Corner { index, .. } => ((s + 1) % 3, index),
            };
            let exit = 3 * t + exit_side;
            let twin = self.twin[exit];
            if twin == NO_HALFEDGE || exit_position < 0 {
                return Err(IntrinsicError::Inconsistent(format!(
                    "an input edge leaves intrinsic face {t} through a boundary side"
                )));
            }
            h = twin;
            p = self.crossings(exit) - 1 - exit_position;
        }
    }

    /// The whole path of the piece emanating as arc `start`.
    pub(crate) fn trace_from(&self, start: CornerArc) -> Result<PiecePath, IntrinsicError> {
        let side = 3 * start.face + start.corner;
        let arcs = TriangleArcs::new(self.face_normals(start.face));
        let position = arcs.corner[(start.corner + 1) % 3] + start.index;
        let twin = self.twin[side];
        if twin == NO_HALFEDGE {
            return Err(IntrinsicError::Inconsistent(format!(
                "an input edge leaves intrinsic face {} through a boundary side",
                start.face
            )));
        }
        let mut crossings = Vec::new();
        let end = self.walk_piece(twin, self.crossings(side) - 1 - position, &mut crossings)?;
        Ok(PiecePath {
            start: Some(start),
            crossings,
            end: Some(end),
        })
    }

    /// The whole path of the piece through position `p` of halfedge `h` (entering its face),
    /// from its start in the direction it crosses `h`.
    pub(crate) fn trace_through(&self, h: usize, p: i64) -> Result<PiecePath, IntrinsicError> {
        let mut forward = Vec::new();
        let end = self.walk_piece(h, p, &mut forward)?;
        let mut backward = Vec::new();
        let twin = self.twin[h];
        if twin == NO_HALFEDGE {
            return Err(IntrinsicError::Inconsistent(
                "a crossing on a boundary edge".into(),
            ));
        }
        let start = self.walk_piece(twin, self.crossings(h) - 1 - p, &mut backward)?;
        // Walking backwards the piece entered the twins; forwards it enters the halfedges.
        let mut crossings: Vec<(usize, i64)> = backward[1..]
            .iter()
            .rev()
            .map(|&(g, q)| (self.twin[g], self.crossings(g) - 1 - q))
            .collect();
        crossings.extend(forward);
        Ok(PiecePath {
            start: Some(start),
            crossings,
            end: Some(end),
        })
    }

    /// Where the piece `path` crosses each halfedge it enters: `(σ, λ)` with `σ` the fraction
    /// along the halfedge from its tail and `λ` the fraction along the piece from its start,
    /// both in `[0, 1]`. The faces along the path are unfolded into the plane from the edge
    /// lengths; the piece is the straight segment between its two end vertices there.
    pub(crate) fn piece_positions(&self, path: &PiecePath) -> Vec<(f64, f64)> {
        let (Some(start), Some(end)) = (path.start, path.end) else {
            return Vec::new();
        };
        let mut corners = layout(self.face_lengths(start.face));
        let from = corners[start.corner];
        let mut sides = Vec::with_capacity(path.crossings.len());
        for &(h, _) in &path.crossings {
            // The side just left is the twin of `h`: it runs from the head of `h` to its tail.
            let exit = self.twin[h] % 3;
            let (tail, head) = (corners[(exit + 2) % 3], corners[(exit + 1) % 3]);
            let (t, s) = (h / 3, h % 3);
            let l = self.face_lengths(t);
            let mut next = [[0.0; 2]; 3];
            next[(s + 1) % 3] = tail;
            next[(s + 2) % 3] = head;
            next[s] = place_left(tail, head, l[s], l[(s + 2) % 3], l[(s + 1) % 3]);
            corners = next;
            sides.push((tail, head));
        }
        let to = corners[end.corner];
        let d = [to[0] - from[0], to[1] - from[1]];
        sides
            .iter()
            .map(|&(a, b)| {
                let u = [b[0] - a[0], b[1] - a[1]];
                let w = [a[0] - from[0], a[1] - from[1]];
                let denominator = d[0] * u[1] - d[1] * u[0];
                let sigma = (w[0] * d[1] - w[1] * d[0]) / denominator;
                let lambda = (w[0] * u[1] - w[1] * u[0]) / denominator;
                (clamp_unit(sigma), clamp_unit(lambda))
            })
            .collect()
    }

    /// The fraction along input edge `edge` at which intrinsic vertex `v` sits (0 or 1 for its
    /// endpoints), `None` if `v` is not on it.
    pub(crate) fn vertex_fraction_on(
        &self,
        v: usize,
        edge: usize,
        edge_vertices: [usize; 2],
    ) -> Option<f64> {
        match self.vertex_locations[v] {
            InputLocation::Vertex(w) if w == edge_vertices[0] => Some(0.0),
            InputLocation::Vertex(w) if w == edge_vertices[1] => Some(1.0),
            InputLocation::Edge { edge: e, t } if e == edge => Some(t),
            _ => None,
        }
    }
}

/// `x` clamped to `[0, 1]` (NaN, from a degenerate layout, becomes 0.5).
fn clamp_unit(x: f64) -> f64 {
    if x.is_nan() {
        0.5
    } else {
        x.clamp(0.0, 1.0)
    }
}
