//! Intrinsic edge flips and [`IntrinsicTriangulation::flip_to_delaunay`].

use super::error::IntrinsicError;
use super::length_geometry::flipped_length;
use super::normal_coordinates::{flip_update, QuadTriangle, TriangleArcs};
use super::triangulation::{IntrinsicTriangulation, NO_HALFEDGE};

/// Relative round-off allowance of the Delaunay test (dimensionless): an interior edge is
/// flipped only when `cot α + cot β < −DELAUNAY_FLIP_TOLERANCE · max(1, |cot α| + |cot β|)`.
///
/// Cotangents computed from lengths carry a relative error of a few ulps, so the sum of a
/// cocircular pair (exactly 0) comes out as ±1e-17 on a regular quadrilateral and larger on
/// slivers; flipping on its sign would flip such an edge back and forth. Edges inside the
/// allowance are *ties*: both diagonals of a cocircular quadrilateral give the same cotan
/// matrix (the weight of either diagonal is 0, and the angles the other four edges see are
/// inscribed in the same circle), so the result does not depend on how ties are broken, up to
/// this tolerance.
pub const DELAUNAY_FLIP_TOLERANCE: f64 = 1e-12;

/// A stack of edges, each at most once.
#[derive(Debug, Clone, Default)]
pub(crate) struct EdgeQueue {
    stack: Vec<usize>,
    queued: Vec<bool>,
}

impl EdgeQueue {
    /// Pushes `e` unless it is already queued.
    pub fn push(&mut self, e: usize) {
        if e >= self.queued.len() {
            self.queued.resize(e + 1, false);
        }
        if !self.queued[e] {
            self.queued[e] = true;
            self.stack.push(e);
        }
    }

    /// Takes the last edge pushed.
    pub fn pop(&mut self) -> Option<usize> {
        let e = self.stack.pop()?;
        self.queued[e] = false;
        Some(e)
    }
}

impl IntrinsicTriangulation {
    /// Flips interior edges until every one is Delaunay (`cot α + cot β ≥ 0` up to
    /// [`DELAUNAY_FLIP_TOLERANCE`]); returns the number of flips made. Boundary edges are never
    /// flipped and no vertex is inserted, so the result is the intrinsic Delaunay triangulation
    /// of the input (Bobenko and Springborn 2007), unique up to cocircular ties, which do not
    /// change its cotan matrix. On a Delaunay input nothing flips and the triangulation stays
    /// the input's, numbers and lengths bit for bit.
    ///
    /// Lawson's algorithm on a queue of edges (Fisher, Springborn, Schröder and Bobenko 2007):
    /// every edge starts in it, each flip queues the four edges around the flipped one. Each
    /// flip updates the lengths and the integer coordinates of two faces in constant time.
    /// Fails with [`IntrinsicError::FlipLimit`] after `100 E + 100 000` flips, which exact
    /// arithmetic never needs on real meshes (it guards against round-off cycles), and with
    /// [`IntrinsicError::DegenerateIntrinsicFace`] rather than leave a face whose lengths
    /// round-off made non-triangular.
    pub fn flip_to_delaunay(&mut self) -> Result<usize, IntrinsicError> {
        let mut queue = EdgeQueue::default();
        for e in 0..self.edge_count() {
            queue.push(e);
        }
        let flips = self.flip_until_delaunay(&mut queue, None)?;
        self.check_faces()?;
        Ok(flips)
    }

    /// Fails with [`IntrinsicError::DegenerateIntrinsicFace`] on the first face whose lengths
    /// are not a triangle's (or not finite).
    pub(crate) fn check_faces(&self) -> Result<(), IntrinsicError> {
        match (0..self.face_count())
            .find(|&t| !super::length_geometry::is_triangle(self.face_lengths(t)))
        {
            Some(face) => Err(IntrinsicError::DegenerateIntrinsicFace {
                face,
                lengths: self.face_lengths(face),
            }),
            None => Ok(()),
        }
    }

    /// Flips the non-Delaunay edges in `queue` and those that become non-Delaunay, until the
    /// queue is empty; pushes every edge of a changed face to `touched`.
    pub(crate) fn flip_until_delaunay(
        &mut self,
        queue: &mut EdgeQueue,
        mut touched: Option<&mut EdgeQueue>,
    ) -> Result<usize, IntrinsicError> {
        let limit = 100 * self.edge_count() + 100_000;
        let mut flips = 0;
        while let Some(e) = queue.pop() {
            if !self.needs_flip(e) || !self.flip(e) {
                continue;
            }
            flips += 1;
            if flips > limit {
                return Err(IntrinsicError::FlipLimit { flips });
            }
            let h = self.edge_halfedge[e];
            let twin = self.twin[h];
            for g in [self.next(h), self.prev(h), self.next(twin), self.prev(twin)] {
                queue.push(self.halfedge_edge[g]);
            }
            if let Some(touched) = touched.as_deref_mut() {
                for g in [
                    h,
                    self.next(h),
                    self.prev(h),
                    self.next(twin),
                    self.prev(twin),
                ] {
                    touched.push(self.halfedge_edge[g]);
                }
            }
        }
        Ok(flips)
    }

    /// The interior edges that are not Delaunay (`cot α + cot β` below
    /// `−DELAUNAY_FLIP_TOLERANCE · max(1, |cot α| + |cot β|)`), ascending: those
    /// [`IntrinsicTriangulation::flip_to_delaunay`] would start by flipping. On a fresh
    /// triangulation, the input's non-Delaunay edges.
    pub fn non_delaunay_edges(&self) -> Vec<usize> {
        (0..self.edge_count())
            .filter(|&e| self.needs_flip(e))
            .collect()
    }

    /// Whether interior edge `e` is not Delaunay beyond the round-off allowance.
    pub(crate) fn needs_flip(&self, e: usize) -> bool {
        if self.is_boundary_edge(e) {
            return false;
        }
        let (sum, scale) = self.cotan_sum_and_scale(e);
        sum < -DELAUNAY_FLIP_TOLERANCE * scale
    }

    /// Flips interior edge `e`: the diagonal `i–j` of the quadrilateral made of its two faces
    /// `(i, j, k)` and `(j, i, l)` becomes `k–l`, with the length of that diagonal in the
    /// quadrilateral laid out flat. Returns `false` (and changes nothing) on a boundary edge or
    /// an edge with the same face on both sides. The caller makes sure the quadrilateral is
    /// convex (true of every non-Delaunay edge).
    ///
    /// Afterwards face `t1` (the face on the left of `e` before) is `(k, l, j)` and face `t2` is
    /// `(l, k, i)`; `e` is the side opposite corner 2 of both, reference direction `k → l`.
    pub(crate) fn flip(&mut self, e: usize) -> bool {
        let h = self.edge_halfedge[e];
        let h2 = self.twin[h];
        if h2 == NO_HALFEDGE || h / 3 == h2 / 3 {
            return false;
        }
        let (t1, s1) = (h / 3, h % 3);
        let (t2, s2) = (h2 / 3, h2 % 3);
        let [k, i, j] = [0, 1, 2].map(|d| self.faces[t1][(s1 + d) % 3]);
        let l = self.faces[t2][s2];
        // Outer halfedges: a = j→k, b = k→i (in t1), c = i→l, d = l→j (in t2).
        let a = 3 * t1 + (s1 + 1) % 3;
        let b = 3 * t1 + (s1 + 2) % 3;
        let c = 3 * t2 + (s2 + 1) % 3;
        let d = 3 * t2 + (s2 + 2) % 3;

        let arcs1 = TriangleArcs::new(self.face_normals(t1));
        let arcs2 = TriangleArcs::new(self.face_normals(t2));
        let quad1 = QuadTriangle::new(&arcs1, s1, (s1 + 1) % 3);
        let quad2 = QuadTriangle::new(&arcs2, s2, (s2 + 2) % 3);
        let update = flip_update(
            &quad1,
            &quad2,
            self.normal[e],
            self.is_along_input(b),
            self.is_along_input(d),
        );
        let length = flipped_length(
            self.lengths[e],
            self.lengths[self.halfedge_edge[a]],
            self.lengths[self.halfedge_edge[b]],
            self.lengths[self.halfedge_edge[c]],
            self.lengths[self.halfedge_edge[d]],
        );
        let roundabout_k = self.advance_roundabout(b, update.advance_at_k);
        let roundabout_l = self.advance_roundabout(d, update.advance_at_l);

        self.relocate_outer_halfedges(&[a, b, c, d], &[3 * t1 + 1, 3 * t2, 3 * t2 + 1, 3 * t1]);
        self.faces[t1] = [k, l, j];
        self.faces[t2] = [l, k, i];
        let (new1, new2) = (3 * t1 + 2, 3 * t2 + 2);
        self.twin[new1] = new2;
        self.twin[new2] = new1;
        self.halfedge_edge[new1] = e;
        self.halfedge_edge[new2] = e;
        self.edge_halfedge[e] = new1;
        self.lengths[e] = length;
        self.set_normal(e, update.new_edge);
        self.roundabout[new1] = roundabout_k;
        self.roundabout[new2] = roundabout_l;
        self.flip_count += 1;
        true
    }

    /// The roundabout of halfedge `h` advanced by `steps` ends around its tail (no roundabout
    /// stays none).
    pub(crate) fn advance_roundabout(&self, h: usize, steps: i64) -> usize {
        let r = self.roundabout[h];
        if r == super::curve_ends::NO_END {
            return r;
        }
        self.curve_ends
            .advance(r, steps)
            .unwrap_or(super::curve_ends::NO_END)
    }

    /// Moves the data of halfedges `old[m]` (twin, edge, roundabout) to positions `new[m]`,
    /// fixing the twins' back pointers and the edges' reference halfedges.
    pub(crate) fn relocate_outer_halfedges(&mut self, old: &[usize], new: &[usize]) {
        let saved: Vec<_> = old
            .iter()
            .map(|&h| {
                let edge = self.halfedge_edge[h];
                let reference = self.edge_halfedge[edge] == h;
                (self.twin[h], edge, self.roundabout[h], reference)
            })
            .collect();
        let moved = |h: usize| old.iter().position(|&x| x == h).map_or(h, |m| new[m]);
        for (m, &(twin, edge, roundabout, reference)) in saved.iter().enumerate() {
            let twin = if twin == NO_HALFEDGE {
                twin
            } else {
                moved(twin)
            };
            self.twin[new[m]] = twin;
            self.halfedge_edge[new[m]] = edge;
            self.roundabout[new[m]] = roundabout;
            if reference {
                self.edge_halfedge[edge] = new[m];
            }
        }
        for &position in new {
            let twin = self.twin[position];
            if twin != NO_HALFEDGE {
                self.twin[twin] = position;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{icosphere, torus};
    use crate::geometry::{cross, dot, norm, sub};
    use crate::intrinsic::test_meshes::square_grid;
    use crate::TriangleMesh;

    /// Two triangles forming a convex quadrilateral whose diagonal 0–1 is far from Delaunay.
    fn thin_kite() -> TriangleMesh {
        TriangleMesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [4.0, 0.0, 0.0],
                [2.0, 0.3, 0.0],
                [2.0, -0.3, 0.0],
            ],
            vec![[0, 1, 2], [1, 0, 3]],
        )
        .unwrap()
    }

    #[test]
    fn flipping_a_kite() {
        let mesh = thin_kite();
        let mut tri = IntrinsicTriangulation::new(&mesh).unwrap();
        assert_eq!(tri.non_delaunay_edges().len(), 1);
        let flips = tri.flip_to_delaunay().unwrap();
        assert_eq!(flips, 1);
        assert!(tri.non_delaunay_edges().is_empty());
        tri.check_invariants().unwrap();
        let e = (0..tri.edge_count())
            .find(|&e| !tri.is_boundary_edge(e))
            .unwrap();
        let mut ends = tri.edge_vertices(e);
        ends.sort();
        assert_eq!(ends, [2, 3]);
        assert!((tri.lengths()[e] - 0.6).abs() < 1e-15);
        // The new diagonal crosses the old one, an input edge, once.
        assert_eq!(tri.normal_coordinate(e), 1);
        assert!((tri.total_area() - mesh.total_area()).abs() < 1e-14 * mesh.total_area());
        // Flipping back restores an edge along the input edge.
        assert!(tri.flip(e));
        tri.check_invariants().unwrap();
        assert_eq!(tri.normal_coordinate(e), -1);
        assert!((tri.lengths()[e] - 4.0).abs() < 1e-14);
    }

    #[test]
    fn cocircular_ties_do_not_change_the_cotan_matrix() {
        // Every diagonal of a square grid is a tie: flipping all of them changes the
        // triangulation but not its cotan Laplacian.
        let mesh = square_grid(4);
        let tri = IntrinsicTriangulation::new(&mesh).unwrap();
        assert!(tri.non_delaunay_edges().is_empty());
        let mut other = tri.clone();
        let ties: Vec<usize> = (0..tri.edge_count())
            .filter(|&e| !tri.is_boundary_edge(e) && tri.cotan_sum_and_scale(e).0.abs() < 1e-12)
            .collect();
        assert_eq!(ties.len(), 16);
        for &e in &ties {
            assert!(other.flip(e));
        }
        other.check_invariants().unwrap();
        let (a, b) = (tri.cotan_laplacian(), other.cotan_laplacian());
        for (value, (i, j)) in a.iter() {
            let w = b.get(i, j).copied().unwrap_or(0.0);
            assert!((value - w).abs() < 1e-14, "({i}, {j}): {value} vs {w}");
        }
        for (value, (i, j)) in b.iter() {
            let w = a.get(i, j).copied().unwrap_or(0.0);
            assert!((value - w).abs() < 1e-14, "({i}, {j}): {value} vs {w}");
        }
    }

    /// `(cot α + cot β) / 2` per edge from the 3D positions: the input's own cotan weights.
    fn input_hodge_star(mesh: &TriangleMesh) -> Vec<f64> {
        let mut star = vec![0.0; mesh.edge_count()];
        for (t, face) in mesh.faces().iter().enumerate() {
            let p = face.map(|v| mesh.positions()[v]);
            for c in 0..3 {
                let (u, v) = (sub(p[(c + 1) % 3], p[c]), sub(p[(c + 2) % 3], p[c]));
                star[mesh.face_edges()[t][c]] += dot(u, v) / norm(cross(u, v)) / 2.0;
            }
        }
        star
    }

    #[test]
    fn a_delaunay_input_does_not_flip() {
        let meshes = [
            icosphere(1),
            icosphere(3),
            // Every cell a cocircular trapezoid: ties, left as they are.
            torus(3.0, 1.0, 24, 12).unwrap(),
        ];
        for mesh in meshes {
            let star = input_hodge_star(&mesh);
            assert!(
                star.iter().all(|&s| s > -1e-12),
                "the test mesh is Delaunay"
            );
            let mut tri = IntrinsicTriangulation::new(&mesh).unwrap();
            assert_eq!(tri.flip_to_delaunay().unwrap(), 0);
            // The triangulation is still the input, numbers and lengths bit for bit ...
            assert_eq!(tri.faces(), mesh.faces());
            for (e, &[a, b]) in mesh.edges().iter().enumerate() {
                assert_eq!(tri.edge_vertices(e), [a, b]);
                let length = norm(sub(mesh.positions()[b], mesh.positions()[a]));
                assert_eq!(tri.lengths()[e].to_bits(), length.to_bits());
            }
            // ... so its cotan weights are the input's computed from lengths, bit for bit, and
            // agree with the ones computed from positions to round-off.
            let mut from_lengths = vec![0.0; mesh.edge_count()];
            for edges in mesh.face_edges() {
                let lengths = edges.map(|e| {
                    let [a, b] = mesh.edges()[e];
                    norm(sub(mesh.positions()[b], mesh.positions()[a]))
                });
                let cot = super::super::length_geometry::corner_cotangents(lengths);
                for c in 0..3 {
                    from_lengths[edges[c]] += cot[c];
                }
            }
            for (e, s) in tri.edge_hodge_star().iter().enumerate() {
                assert_eq!(s.to_bits(), (from_lengths[e] / 2.0).to_bits());
                assert!((s - star[e]).abs() < 1e-13 * star[e].abs().max(1.0));
            }
        }
    }
}
