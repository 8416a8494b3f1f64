//! [`Crossings`]: every crossing of an input edge with an intrinsic edge, with its position on
//! both, and the input face each stretch of an intrinsic edge between crossings runs through.

use super::curve_ends::{CurveEnd, NO_END};
use super::error::IntrinsicError;
use super::surface_location::InputLocation;
use super::trace::{CornerArc, PiecePath};
use super::triangulation::IntrinsicTriangulation;
use crate::{TriangleMesh, NO_FACE};

/// Every crossing of an input edge with an intrinsic edge. The crossings of intrinsic edge `e`
/// are the **slots** `offsets[e] .. offsets[e + 1]` (as many as its normal coordinate), ordered
/// from the tail of its reference halfedge. Its **segments** (the stretches before, between and
/// after the crossings, `n + 1` of them, each inside one input face) are
/// `offsets[e] + e .. offsets[e + 1] + e + 1` of `segment_face`.
#[derive(Debug, Clone)]
pub(crate) struct Crossings {
    pub offsets: Vec<usize>,
    /// Input edge of each slot.
    pub input_edge: Vec<usize>,
    /// Fraction along the intrinsic edge, from the tail of its reference halfedge.
    pub sigma: Vec<f64>,
    /// Fraction along the input edge `(a, b)`, from `a`.
    pub t: Vec<f64>,
    /// Input face of each segment ([`NO_FACE`] for edges along an input edge: there it
    /// depends on the side).
    pub segment_face: Vec<usize>,
}

impl Crossings {
    /// The global slot index of the crossing at `position` (from the tail of halfedge `h`).
    pub fn slot(&self, tri: &IntrinsicTriangulation, h: usize, position: i64) -> usize {
        let e = tri.halfedge_edge[h];
        let n = self.offsets[e + 1] - self.offsets[e];
        let p = position as usize;
        self.offsets[e]
            + if tri.edge_halfedge[e] == h {
                p
            } else {
                n - 1 - p
            }
    }

    /// The input face of segment `q` (0-based from the tail of halfedge `h`) of `h`'s edge, on
    /// the side of `h`'s face.
    pub fn segment_face_of(
        &self,
        tri: &IntrinsicTriangulation,
        mesh: &TriangleMesh,
        h: usize,
        q: i64,
    ) -> usize {
        let e = tri.halfedge_edge[h];
        if tri.is_along_input(h) {
            // The input face on the left of `h`, which runs along its input edge.
            let end = tri.curve_ends.ends[tri.roundabout[h]];
            return mesh.edge_faces()[end.edge][usize::from(!end.toward_b)];
        }
        let n = self.offsets[e + 1] - self.offsets[e];
        let q = q as usize;
        let q = if tri.edge_halfedge[e] == h { q } else { n - q };
        self.segment_face[self.offsets[e] + e + q]
    }
}

/// One crossing of a traced piece: the halfedge it enters and the position along it (from its
/// tail), the fraction `sigma` along it, the input edge and the fraction `t` along that, and the
/// input faces on the halfedge's tail and head sides of the crossing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CrossingRecord {
    pub halfedge: usize,
    pub position: i64,
    pub sigma: f64,
    pub input_edge: usize,
    pub t: f64,
    pub tail_face: usize,
    pub head_face: usize,
}

impl IntrinsicTriangulation {
    /// Traces every piece of every input edge and records its crossings.
    pub(crate) fn trace_all_crossings(
        &self,
        mesh: &TriangleMesh,
    ) -> Result<Crossings, IntrinsicError> {
        let mut offsets = Vec::with_capacity(self.edge_count() + 1);
        offsets.push(0);
        for &n in &self.normal {
            offsets.push(offsets.last().copied().unwrap_or(0) + n.max(0) as usize);
        }
        let slots = offsets[self.edge_count()];
        let mut out = Crossings {
            offsets,
            input_edge: vec![usize::MAX; slots],
            sigma: vec![f64::NAN; slots],
            t: vec![f64::NAN; slots],
            segment_face: vec![NO_FACE; slots + self.edge_count()],
        };
        let mut before = vec![NO_FACE; slots];
        let mut after = vec![NO_FACE; slots];
        for face in 0..self.face_count() {
            let arcs = super::normal_coordinates::TriangleArcs::new(self.face_normals(face));
            for corner in 0..3 {
                for index in 0..arcs.emanating[corner] {
                    let arc = CornerArc {
                        face,
                        corner,
                        index,
                    };
                    let (_, end) = self.end_of_arc(arc)?;
                    if end.toward_b {
                        let path = self.trace_from(arc)?;
                        self.record_piece(&path, end, mesh, &mut out, [&mut before, &mut after])?;
                    }
                }
            }
        }
        if out.input_edge.contains(&usize::MAX) {
            return Err(IntrinsicError::Inconsistent(
                "some crossings of intrinsic edges belong to no traced input edge".into(),
            ));
        }
        self.fill_segment_faces(&mut out, &before, &after, mesh.edge_faces())?;
        Ok(out)
    }

    /// Records the crossings of one traced piece that starts with input edge end `start_end`.
    /// `sides[0]`/`sides[1]` receive the input face before/after each slot.
    fn record_piece(
        &self,
        path: &PiecePath,
        start_end: CurveEnd,
        mesh: &TriangleMesh,
        out: &mut Crossings,
        sides: [&mut Vec<usize>; 2],
    ) -> Result<(), IntrinsicError> {
        let [before, after] = sides;
        for record in self.piece_records(path, start_end, mesh)? {
            let e = self.halfedge_edge[record.halfedge];
            let reference = self.edge_halfedge[e] == record.halfedge;
            let slot = out.slot(self, record.halfedge, record.position);
            if out.input_edge[slot] != usize::MAX {
                return Err(IntrinsicError::Inconsistent(format!(
                    "two input edges traced through the same crossing of intrinsic edge {e}"
                )));
            }
            out.input_edge[slot] = record.input_edge;
            out.t[slot] = record.t;
            (out.sigma[slot], before[slot], after[slot]) = if reference {
                (record.sigma, record.tail_face, record.head_face)
            } else {
                (1.0 - record.sigma, record.head_face, record.tail_face)
            };
        }
        Ok(())
    }

    /// The crossings of one traced piece that starts with input edge end `start_end`, with
    /// their positions and the input faces on either side.
    pub(crate) fn piece_records(
        &self,
        path: &PiecePath,
        start_end: CurveEnd,
        mesh: &TriangleMesh,
    ) -> Result<Vec<CrossingRecord>, IntrinsicError> {
        let (Some(start), Some(end)) = (path.start, path.end) else {
            return Ok(Vec::new());
        };
        let edge = start_end.edge;
        let (_, end_end) = self.end_of_arc(end)?;
        let ab = mesh.edges()[edge];
        let v0 = self.faces[start.face][start.corner];
        let v1 = self.faces[end.face][end.corner];
        let (Some(t0), Some(t1)) = (
            self.vertex_fraction_on(v0, edge, ab),
            self.vertex_fraction_on(v1, edge, ab),
        ) else {
            return Err(IntrinsicError::Inconsistent(format!(
                "a piece of input edge {edge} runs between intrinsic vertices {v0} and {v1}, not both on it"
            )));
        };
        if end_end.edge != edge || end_end.toward_b == start_end.toward_b {
            return Err(IntrinsicError::Inconsistent(format!(
                "input edge {edge} traced from vertex {v0} ends at vertex {v1} as input edge {}",
                end_end.edge
            )));
        }
        let [left, right] = mesh.edge_faces()[edge];
        // The piece enters each crossed halfedge's face: the halfedge's tail side is on the
        // piece's left, which is the left of a → b when the piece runs towards b.
        let (tail_face, head_face) = if start_end.toward_b {
            (left, right)
        } else {
            (right, left)
        };
        let positions = self.piece_positions(path);
        Ok(path
            .crossings
            .iter()
            .zip(&positions)
            .map(|(&(halfedge, position), &(sigma, lambda))| CrossingRecord {
                halfedge,
                position,
                sigma,
                input_edge: edge,
                t: t0 + lambda * (t1 - t0),
                tail_face,
                head_face,
            })
            .collect())
    }

    /// Input faces of the segments of every intrinsic edge that does not lie along an input
    /// edge: from the crossings, and from the sector at the tail for the first segment (checked
    /// against each other).
    fn fill_segment_faces(
        &self,
        out: &mut Crossings,
        before: &[usize],
        after: &[usize],
        edge_faces: &[[usize; 2]],
    ) -> Result<(), IntrinsicError> {
        for e in 0..self.edge_count() {
            let h = self.edge_halfedge[e];
            if self.is_along_input(h) {
                continue;
            }
            let (first, last) = (out.offsets[e], out.offsets[e + 1]);
            let tail_face = self.first_segment_face(h, edge_faces);
            out.segment_face[first + e] = tail_face;
            for slot in first..last {
                if before[slot] != out.segment_face[slot + e] {
                    return Err(IntrinsicError::Inconsistent(format!(
                        "intrinsic edge {e}: the input faces on either side of its crossings do not chain"
                    )));
                }
                out.segment_face[slot + e + 1] = after[slot];
            }
        }
        Ok(())
    }

    /// The input face in which halfedge `h` (not along an input edge) leaves its tail: the
    /// sector between the input edges around the tail, or the face an inserted tail lies in
    /// ([`NO_FACE`] for a vertex inserted on an input edge without ends, which cannot happen).
    pub(crate) fn first_segment_face(&self, h: usize, edge_faces: &[[usize; 2]]) -> usize {
        let r = self.roundabout[h];
        if r != NO_END {
            return self.curve_ends.face_before(r, edge_faces);
        }
        match self.vertex_locations[self.tail(h)] {
            InputLocation::Face(point) => point.face,
            _ => NO_FACE,
        }
    }
}
