//! Splitting an intrinsic edge at a point: a new intrinsic vertex, with its place on the input
//! surface and the integer coordinates of the new edges.

use super::curve_ends::{CurveEnd, NO_END};
use super::error::IntrinsicError;
use super::length_geometry::place_left;
use super::normal_coordinates::{QuadTriangle, TriangleArcs, ALONG_INPUT_EDGE};
use super::surface_location::{location_barycentric, InputLocation, TrianglePoint};
use super::triangulation::{IntrinsicTriangulation, NO_HALFEDGE};
use crate::{TriangleMesh, NO_FACE};

/// Where a split puts its new vertex: the fraction along the reference halfedge, the number of
/// input edges crossing the edge between its tail and the vertex, and the vertex's place on the
/// input.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Placement {
    t: f64,
    crossings_before: i64,
    location: InputLocation,
}

/// One face beside the split edge, before the split: the side `P → Q` being split (`P`, `Q` in
/// the face's order), the opposite corner `O`, and what the new edge `O–m` gets.
#[derive(Debug, Clone, Copy)]
struct Side {
    face: usize,
    new_face: usize,
    corners: [usize; 3],
    /// Old halfedges `O → P` and `Q → O`.
    outer: [usize; 2],
    /// Roundabout of `P → Q` (it becomes `P → m`, the same direction).
    roundabout_pq: usize,
    /// Normal coordinate, roundabout of `O → m`, and length of `O–m`.
    normal_om: i64,
    roundabout_om: usize,
    length_om: f64,
}

/// The smallest distance a split point keeps from the crossings on either side of it, as a
/// fraction of the gap between them: the new vertex must not sit on an input edge it is not
/// known to be on.
const GAP_MARGIN: f64 = 0.01;

impl IntrinsicTriangulation {
    /// Splits edge `e` at the fraction `t` (in `(0, 1)`) along its reference halfedge, moved
    /// into the stretch between two crossings if it falls within [`GAP_MARGIN`] of one.
    /// Returns the new vertex. The faces beside `e` keep their numbers as `(O, P, m)` and new
    /// faces `(O, m, Q)` are appended; `e` becomes the part from its tail to the new vertex.
    pub(crate) fn split_edge(
        &mut self,
        e: usize,
        t: f64,
        mesh: &TriangleMesh,
    ) -> Result<usize, IntrinsicError> {
        let h = self.edge_halfedge[e];
        let h2 = self.twin[h];
        if h2 != NO_HALFEDGE && h2 / 3 == h / 3 {
            // Both sides in one face (an edge to a vertex of degree one): always Delaunay, never
            // split by refinement.
            return Err(IntrinsicError::Inconsistent(format!(
                "edge {e} has the same face on both sides and cannot be split"
            )));
        }
        let placement = self.placement(h, t, mesh)?;
        let n = self.normal[e];
        let s = placement.crossings_before;
        let first = self.side_before_split(h, s, placement.t, self.face_count());
        let second = (h2 != NO_HALFEDGE).then(|| {
            self.side_before_split(h2, n.max(0) - s, 1.0 - placement.t, self.face_count() + 1)
        });
        let m = self.vertex_count();
        self.vertex_locations.push(placement.location);
        // m's ends: the two pieces of the input edge it lies on, towards Q = j and P = i.
        let (to_j, to_i) = if n == ALONG_INPUT_EDGE {
            let end = self.curve_ends.ends[self.roundabout[h]];
            let other = CurveEnd {
                toward_b: !end.toward_b,
                ..end
            };
            let fan = self.curve_ends.push_fan(&[end, other], second.is_some());
            (fan, fan + 1)
        } else {
            (NO_END, NO_END)
        };
        let length = self.lengths[e];
        let (normal_im, normal_mj) = if n == ALONG_INPUT_EDGE {
            (n, n)
        } else {
            (s, n - s)
        };
        let e_mj = self.push_edge(normal_mj, (1.0 - placement.t) * length);
        self.lengths[e] = placement.t * length;
        self.set_normal(e, normal_im);
        for _ in std::iter::once(first).chain(second) {
            self.faces.push([0; 3]);
            self.twin.extend([NO_HALFEDGE; 3]);
            self.halfedge_edge.extend([0; 3]);
            self.roundabout.extend([NO_END; 3]);
        }
        let mut outer_old = vec![first.outer[0], first.outer[1]];
        let mut outer_new = vec![3 * first.face + 2, 3 * first.new_face + 1];
        if let Some(second) = second {
            outer_old.extend(second.outer);
            outer_new.extend([3 * second.face + 2, 3 * second.new_face + 1]);
        }
        self.relocate_outer_halfedges(&outer_old, &outer_new);
        // Edges P–m and m–Q: (e, e_mj) beside the first face, (e_mj, e) beside the second.
        self.rebuild_side(&first, m, [e, e_mj], [to_i, to_j]);
        if let Some(second) = second {
            self.rebuild_side(&second, m, [e_mj, e], [to_j, to_i]);
            self.twin[3 * first.face] = 3 * second.new_face;
            self.twin[3 * second.new_face] = 3 * first.face;
            self.twin[3 * first.new_face] = 3 * second.face;
            self.twin[3 * second.face] = 3 * first.new_face;
        }
        self.edge_halfedge[e] = 3 * first.face;
        self.edge_halfedge[e_mj] = 3 * first.new_face;
        Ok(m)
    }

    /// Appends an edge with normal coordinate `normal` and length `length` (its halfedges are
    /// set by the caller); returns its index.
    fn push_edge(&mut self, normal: i64, length: f64) -> usize {
        self.lengths.push(length);
        self.normal.push(normal);
        self.crossing_total += normal.max(0) as usize;
        self.edge_halfedge.push(NO_HALFEDGE);
        self.lengths.len() - 1
    }

    /// What the face of halfedge `g` (from `P` to `Q`) contributes to a split at fraction
    /// `t_from_p` from `P`, with `s` input edges crossing between `P` and the new vertex.
    fn side_before_split(&self, g: usize, s: i64, t_from_p: f64, new_face: usize) -> Side {
        let (face, side) = (g / 3, g % 3);
        let corners = [0, 1, 2].map(|d| self.faces[face][(side + d) % 3]);
        let op = 3 * face + (side + 2) % 3;
        let qo = 3 * face + (side + 1) % 3;
        let arcs = TriangleArcs::new(self.face_normals(face));
        let named = QuadTriangle::new(&arcs, side, (side + 1) % 3);
        let n = self.crossings(g);
        // The arcs separating O from the new vertex: O's corner arcs, the arcs from P and Q,
        // and the corner arcs of P beyond it and of Q before it.
        let normal_om = named.corner_opposite
            + named.emanating_i
            + named.emanating_j
            + (named.corner_i - s).max(0)
            + (s + named.corner_j - n).max(0);
        let advance = i64::from(self.is_along_input(op))
            + (s - named.corner_i).clamp(0, named.emanating_opposite);
        let length = self.lengths[self.halfedge_edge[g]];
        let o = place_left(
            [0.0, 0.0],
            [length, 0.0],
            length,
            self.lengths[self.halfedge_edge[op]],
            self.lengths[self.halfedge_edge[qo]],
        );
        Side {
            face,
            new_face,
            corners,
            outer: [op, qo],
            roundabout_pq: self.roundabout[g],
            normal_om,
            roundabout_om: self.advance_roundabout(op, advance),
            length_om: (o[0] - t_from_p * length).hypot(o[1]),
        }
    }

    /// Rewrites one side's face as `(O, P, m)` and fills its new face `(O, m, Q)`, with the new
    /// edge `O–m`; `edges` are `P–m` and `m–Q`, `ends` the roundabouts of `m → O` and `m → Q`.
    /// `P → m` and `m → Q` are left without twins (the caller pairs them across an interior
    /// edge).
    fn rebuild_side(&mut self, side: &Side, m: usize, edges: [usize; 2], ends: [usize; 2]) {
        let [o, p, q] = side.corners;
        let (t, u) = (side.face, side.new_face);
        let e_om = self.push_edge(side.normal_om, side.length_om);
        self.faces[t] = [o, p, m];
        self.faces[u] = [o, m, q];
        // (O, P, m): side 0 is P → m, side 1 is m → O, side 2 (O → P) was relocated.
        self.halfedge_edge[3 * t] = edges[0];
        self.roundabout[3 * t] = side.roundabout_pq;
        self.twin[3 * t] = NO_HALFEDGE;
        self.halfedge_edge[3 * t + 1] = e_om;
        self.roundabout[3 * t + 1] = ends[0];
        self.twin[3 * t + 1] = 3 * u + 2;
        // (O, m, Q): side 0 is m → Q, side 1 (Q → O) was relocated, side 2 is O → m.
        self.halfedge_edge[3 * u] = edges[1];
        self.roundabout[3 * u] = ends[1];
        self.twin[3 * u] = NO_HALFEDGE;
        self.halfedge_edge[3 * u + 2] = e_om;
        self.roundabout[3 * u + 2] = side.roundabout_om;
        self.twin[3 * u + 2] = 3 * t + 1;
        self.edge_halfedge[e_om] = 3 * t + 1;
    }

    /// Where to put the new vertex of a split of the edge of halfedge `h` near fraction `t`.
    fn placement(
        &self,
        h: usize,
        t: f64,
        mesh: &TriangleMesh,
    ) -> Result<Placement, IntrinsicError> {
        let t = t.clamp(GAP_MARGIN, 1.0 - GAP_MARGIN);
        let (tail, head) = (self.tail(h), self.head(h));
        if self.is_along_input(h) {
            let end = self.curve_ends.ends[self.roundabout[h]];
            let ab = mesh.edges()[end.edge];
            let (Some(t0), Some(t1)) = (
                self.vertex_fraction_on(tail, end.edge, ab),
                self.vertex_fraction_on(head, end.edge, ab),
            ) else {
                return Err(IntrinsicError::Inconsistent(format!(
                    "an intrinsic edge along input edge {} has an end off it",
                    end.edge
                )));
            };
            let location = InputLocation::Edge {
                edge: end.edge,
                t: t0 + t * (t1 - t0),
            };
            return Ok(Placement {
                t,
                crossings_before: 0,
                location,
            });
        }
        self.placement_between_crossings(h, t, mesh)
    }

    /// [`IntrinsicTriangulation::placement`] on an edge crossed by input edges: the crossings
    /// are traced, the point is kept off them, and its input face and coordinates interpolated
    /// between the two points (crossings or ends) around it.
    fn placement_between_crossings(
        &self,
        h: usize,
        t: f64,
        mesh: &TriangleMesh,
    ) -> Result<Placement, IntrinsicError> {
        let n = self.crossings(h);
        let mut records = Vec::with_capacity(n as usize);
        for p in 0..n {
            let path = self.trace_through(h, p)?;
            let start = path.start.ok_or_else(|| {
                IntrinsicError::Inconsistent("a traced input edge has no start".into())
            })?;
            let (_, start_end) = self.end_of_arc(start)?;
            let found = self
                .piece_records(&path, start_end, mesh)?
                .into_iter()
                .find(|r| r.halfedge == h && r.position == p);
            records.push(found.ok_or_else(|| {
                IntrinsicError::Inconsistent(
                    "a crossing is missing from its input edge's trace".into(),
                )
            })?);
        }
        // The stretch between crossings holding t (σ of the ends: 0 and 1).
        let s = records.iter().take_while(|r| r.sigma < t).count();
        let low = if s == 0 { 0.0 } else { records[s - 1].sigma };
        let high = records.get(s).map_or(1.0, |r| r.sigma);
        let margin = GAP_MARGIN * (high - low);
        let t = t.clamp(low + margin, high - margin);
        let face = match (s.checked_sub(1).map(|k| records[k]), records.get(s)) {
            (Some(before), _) => before.head_face,
            (None, Some(after)) => after.tail_face,
            (None, None) => self.first_segment_face(h, mesh.edge_faces()),
        };
        let point_of = |record: Option<&super::crossings::CrossingRecord>, vertex: usize| {
            let location = match record {
                Some(r) => InputLocation::Edge {
                    edge: r.input_edge,
                    t: r.t,
                },
                None => self.vertex_locations[vertex],
            };
            (face != NO_FACE)
                .then(|| location_barycentric(location, face, mesh.faces(), mesh.edges()))
                .flatten()
        };
        let from = point_of(s.checked_sub(1).map(|k| &records[k]), self.tail(h));
        let to = point_of(records.get(s), self.head(h));
        let (Some(from), Some(to)) = (from, to) else {
            return Err(IntrinsicError::Inconsistent(format!(
                "the stretch of intrinsic edge {} to split is not in one input face",
                self.halfedge_edge[h]
            )));
        };
        let w = if high > low {
            (t - low) / (high - low)
        } else {
            0.5
        };
        Ok(Placement {
            t,
            crossings_before: s as i64,
            location: InputLocation::Face(TrianglePoint {
                face,
                barycentric: std::array::from_fn(|k| from[k] + w * (to[k] - from[k])),
            }),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{disk, icosphere};
    use crate::intrinsic::test_meshes::non_delaunay_meshes;
    use std::f64::consts::PI;

    /// Checks what every split must keep: invariants, area, angle sums, a tiling common
    /// subdivision, and the new vertex mapping to itself.
    fn check_after_split(tri: &IntrinsicTriangulation, mesh: &TriangleMesh, m: usize, angle: f64) {
        tri.check_invariants().unwrap();
        let area = mesh.total_area();
        assert!((tri.total_area() - area).abs() < 1e-13 * area);
        let sums = tri.vertex_angle_sums();
        assert!((sums[m] - angle).abs() < 1e-12, "{} vs {angle}", sums[m]);
        let sub = tri.common_subdivision(mesh).unwrap();
        for f in 0..mesh.face_count() {
            let covered: f64 = sub.input_face_overlaps(f).iter().map(|o| o.area).sum();
            assert!((covered - mesh.face_area(f)).abs() < 1e-13 * area);
        }
        // The new vertex's input location maps onto the vertex.
        let point = match tri.vertex_location(m) {
            InputLocation::Face(p) => p,
            InputLocation::Edge { edge, t } => {
                let f = mesh.edge_faces()[edge]
                    .into_iter()
                    .find(|&f| f != NO_FACE)
                    .unwrap();
                let [a, b] = mesh.edges()[edge];
                TrianglePoint {
                    face: f,
                    barycentric: super::super::surface_location::segment_point_barycentric(
                        mesh.faces()[f],
                        a,
                        b,
                        t,
                    )
                    .unwrap(),
                }
            }
            InputLocation::Vertex(_) => panic!("an inserted vertex is no input vertex"),
        };
        let q = sub.to_intrinsic(point).unwrap();
        let corner = tri.faces()[q.face]
            .iter()
            .position(|&v| v == m)
            .expect("lands in a face at the new vertex");
        assert!((q.barycentric[corner] - 1.0).abs() < 1e-9, "{q:?}");
    }

    #[test]
    fn splitting_an_input_edge() {
        let mesh = icosphere(1);
        let mut tri = IntrinsicTriangulation::new(&mesh).unwrap();
        let m = tri.split_edge(7, 0.3, &mesh).unwrap();
        assert_eq!(m, mesh.vertex_count());
        assert_eq!(
            tri.vertex_location(m),
            InputLocation::Edge { edge: 7, t: 0.3 }
        );
        assert_eq!(tri.face_count(), mesh.face_count() + 2);
        check_after_split(&tri, &mesh, m, 2.0 * PI);
    }

    #[test]
    fn splitting_a_boundary_edge() {
        let mesh = disk(2);
        let e = mesh.boundary_edges()[3];
        let mut tri = IntrinsicTriangulation::new(&mesh).unwrap();
        let m = tri.split_edge(e, 0.5, &mesh).unwrap();
        assert_eq!(tri.face_count(), mesh.face_count() + 1);
        assert!(tri.is_boundary_edge(e));
        check_after_split(&tri, &mesh, m, PI);
    }

    #[test]
    fn splitting_flipped_edges_crossed_by_input_edges() {
        for (name, mesh) in non_delaunay_meshes() {
            let mut tri = IntrinsicTriangulation::new(&mesh).unwrap();
            tri.flip_to_delaunay().unwrap();
            let crossed: Vec<usize> = (0..tri.edge_count())
                .filter(|&e| tri.normal_coordinate(e) > 0)
                .take(5)
                .collect();
            assert!(!crossed.is_empty(), "{name}");
            for e in crossed {
                let m = tri.split_edge(e, 0.5, &mesh).unwrap();
                assert!(
                    matches!(tri.vertex_location(m), InputLocation::Face(_)),
                    "{name}"
                );
                check_after_split(&tri, &mesh, m, 2.0 * PI);
                tri.flip_to_delaunay().unwrap();
                check_after_split(&tri, &mesh, m, 2.0 * PI);
            }
        }
    }
}
