//! Consistency checks of an intrinsic triangulation's connectivity and integer coordinates,
//! used by the tests after every kind of change.

use super::curve_ends::NO_END;
use super::length_geometry::is_triangle;
use super::normal_coordinates::TriangleArcs;
use super::triangulation::{IntrinsicTriangulation, NO_HALFEDGE};

impl IntrinsicTriangulation {
    /// Checks twins, edge records, triangle inequalities, the arcs implied by the normal
    /// coordinates and the roundabouts around every vertex; describes the first violation.
    pub(crate) fn check_invariants(&self) -> Result<(), String> {
        for h in 0..self.twin.len() {
            let t = self.twin[h];
            if t != NO_HALFEDGE
                && (self.twin[t] != h
                    || self.tail(t) != self.head(h)
                    || self.head(t) != self.tail(h)
                    || self.halfedge_edge[t] != self.halfedge_edge[h])
            {
                return Err(format!("halfedge {h} and its twin {t} disagree"));
            }
        }
        for (e, &h) in self.edge_halfedge.iter().enumerate() {
            if self.halfedge_edge[h] != e {
                return Err(format!("edge {e}'s halfedge {h} belongs to another edge"));
            }
        }
        for t in 0..self.face_count() {
            if !is_triangle(self.face_lengths(t)) {
                return Err(format!("face {t} has lengths {:?}", self.face_lengths(t)));
            }
            let arcs = TriangleArcs::new(self.face_normals(t));
            if !arcs.is_valid() {
                return Err(format!("face {t}: invalid normal coordinates {arcs:?}"));
            }
        }
        for h in 0..self.twin.len() {
            self.check_roundabout_step(h)?;
        }
        let total: usize = self.normal.iter().map(|&n| n.max(0) as usize).sum();
        if total != self.crossing_total {
            return Err(format!(
                "crossing total {} but the edges have {total}",
                self.crossing_total
            ));
        }
        Ok(())
    }

    /// The roundabout of the halfedge counter-clockwise after `h` at its tail is that of `h`
    /// advanced by the input edge ends in between (at the end of an open fan, the last end).
    fn check_roundabout_step(&self, h: usize) -> Result<(), String> {
        let corner = (h % 3 + 1) % 3;
        let arcs = TriangleArcs::new(self.face_normals(h / 3));
        let between = i64::from(self.is_along_input(h)) + arcs.emanating[corner];
        let after = self.twin[self.prev(h)];
        let r = self.roundabout[h];
        if r == NO_END {
            let other = if after == NO_HALFEDGE {
                NO_END
            } else {
                self.roundabout[after]
            };
            return if between == 0 && other == NO_END {
                Ok(())
            } else {
                Err(format!(
                    "halfedge {h} has no roundabout but {between} ends follow"
                ))
            };
        }
        let expected = self.curve_ends.advance(r, between);
        let fan = self.curve_ends.fans[self.curve_ends.fan_of[r] as usize];
        let found = if after == NO_HALFEDGE {
            (!fan.closed).then(|| fan.start + fan.len - 1)
        } else {
            Some(self.roundabout[after])
        };
        if expected.is_some() && expected == found {
            Ok(())
        } else {
            Err(format!(
                "roundabout after halfedge {h}: expected {expected:?}, found {found:?}"
            ))
        }
    }
}
