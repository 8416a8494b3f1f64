//! [`IntrinsicTriangulation::refine`]: intrinsic Delaunay refinement of the edges that flips
//! cannot make strictly Delaunay.

use super::delaunay_flips::{EdgeQueue, DELAUNAY_FLIP_TOLERANCE};
use super::error::IntrinsicError;
use super::triangulation::{IntrinsicTriangulation, NO_HALFEDGE};
use crate::TriangleMesh;

/// Relative margin of strict Delaunay-ness guaranteed by [`IntrinsicTriangulation::refine`]
/// (dimensionless): afterwards every edge has `cot α + cot β` (one cotangent on the boundary)
/// `> STRICT_DELAUNAY_MARGIN · max(1, |cot α| + |cot β|)`, so `⋆1 > 5e-13` everywhere.
pub const STRICT_DELAUNAY_MARGIN: f64 = DELAUNAY_FLIP_TOLERANCE;

/// Where an interior edge that is cocircular after flipping is split: a fraction along it in
/// `0.5 ± SPLIT_SPREAD`, drawn from a hash of the new vertex's index (so refinement is
/// deterministic). Not the same fraction every time: on a grid of squares the midpoint of a
/// diagonal is the circumcentre and the four triangles it makes are cocircular with their
/// neighbours again at half the size, and any fixed fraction puts the new vertices of
/// neighbouring cells at mirror positions about the side they share (cocircular again).
const SPLIT_SPREAD: f64 = 0.1;

/// A fraction in `0.5 ± SPLIT_SPREAD` from `seed` (SplitMix64).
fn interior_split_fraction(seed: usize) -> f64 {
    let mut z = (seed as u64).wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    let unit = (z >> 11) as f64 / (1u64 << 53) as f64;
    0.5 + SPLIT_SPREAD * (2.0 * unit - 1.0)
}

/// Limits of [`IntrinsicTriangulation::refine`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RefineOptions {
    /// Most vertices to insert before failing with [`IntrinsicError::InsertionLimit`]; `None`
    /// allows as many as the input has edges, plus 1000.
    pub max_insertions: Option<usize>,
}

/// What [`IntrinsicTriangulation::refine`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RefineReport {
    /// Edge flips, the initial Delaunay flipping included.
    pub flips: usize,
    /// Vertices inserted (by edge splits).
    pub inserted: usize,
}

impl IntrinsicTriangulation {
    /// Intrinsic Delaunay refinement: flips to Delaunay, then splits the edges flips cannot
    /// cure and flips again, until every edge is strictly Delaunay.
    ///
    /// Two kinds of edges stay non-strict after flipping: an interior edge between two
    /// cocircular triangles (`cot α + cot β = 0`: a zero `⋆1`, the dual edge has no length),
    /// and a boundary edge opposite an obtuse or right angle (`cot γ ≤ 0`), which is never
    /// flipped. Each is split — a boundary edge at its midpoint, or at a power-of-two distance
    /// from an input vertex at its end (Shewchuk's concentric shells, so that splits near a
    /// sharp boundary corner do not cascade); an interior edge at a fraction in `0.5 ± 0.1` of
    /// its length drawn from a hash of the new vertex's number (deterministic; a fixed fraction
    /// makes the cells of a regular grid cocircular again, at every scale) — and the faces
    /// around the new vertex are flipped back to Delaunay. New vertices lie on the input surface
    /// (see [`IntrinsicTriangulation::vertex_location`]); a split point is kept at least 1% of
    /// the stretch between two crossings of input edges away from them.
    ///
    /// **Guarantee** on success: every edge, interior and boundary, has `cot α + cot β` (a
    /// single cotangent on the boundary) `> STRICT_DELAUNAY_MARGIN · max(1, |cot α| + |cot β|)`,
    /// so `⋆1 > 5e-13` on every edge, a margin above round-off (DEC's `DELAUNAY_TOLERANCE` test
    /// `2⋆1 > 1e-12` passes); interior edges stay Delaunay, the surface, its total area and the
    /// angle sums at input vertices are unchanged (inserted vertices have `2π`, or `π` on the
    /// boundary). Termination is not proven for every input (refinement near small boundary
    /// angles is delicate); the insertion limit makes it fail instead. Fails with
    /// [`IntrinsicError::InsertionLimit`] rather than insert more than
    /// [`RefineOptions::max_insertions`] vertices, with [`IntrinsicError::InputMismatch`] if
    /// `mesh` is not the input, and with the errors of
    /// [`IntrinsicTriangulation::flip_to_delaunay`].
    pub fn refine(
        &mut self,
        mesh: &TriangleMesh,
        options: RefineOptions,
    ) -> Result<RefineReport, IntrinsicError> {
        self.check_input(mesh)?;
        let limit = options
            .max_insertions
            .unwrap_or(self.input_counts[1] + 1000);
        let mut flips = EdgeQueue::default();
        let mut candidates = EdgeQueue::default();
        for e in 0..self.edge_count() {
            flips.push(e);
            candidates.push(e);
        }
        let mut report = RefineReport {
            flips: self.flip_until_delaunay(&mut flips, Some(&mut candidates))?,
            inserted: 0,
        };
        loop {
            while let Some(e) = candidates.pop() {
                if !self.needs_split(e) {
                    continue;
                }
                if report.inserted >= limit {
                    return Err(IntrinsicError::InsertionLimit {
                        inserted: report.inserted,
                        remaining: self.not_strictly_delaunay_edges().len(),
                    });
                }
                let h = self.edge_halfedge[e];
                let mut faces = vec![h / 3];
                if self.twin[h] != NO_HALFEDGE {
                    faces.push(self.twin[h] / 3);
                }
                let first_new = self.face_count();
                self.split_edge(e, self.split_fraction(e), mesh)?;
                report.inserted += 1;
                faces.extend(first_new..self.face_count());
                for t in faces {
                    for f in self.face_edges(t) {
                        flips.push(f);
                        candidates.push(f);
                    }
                }
                report.flips += self.flip_until_delaunay(&mut flips, Some(&mut candidates))?;
            }
            let left = self.not_strictly_delaunay_edges();
            if left.is_empty() {
                self.check_faces()?;
                return Ok(report);
            }
            for e in left {
                candidates.push(e);
            }
        }
    }

    /// The edges that are not strictly Delaunay, ascending: `cot α + cot β` (one cotangent on
    /// the boundary) at most `STRICT_DELAUNAY_MARGIN · max(1, |cot α| + |cot β|)`. After
    /// [`IntrinsicTriangulation::flip_to_delaunay`] these are the cocircular interior edges
    /// (`⋆1 = 0` up to round-off) and the boundary edges opposite an obtuse or right angle: what
    /// [`IntrinsicTriangulation::refine`] splits. Empty after refinement.
    pub fn not_strictly_delaunay_edges(&self) -> Vec<usize> {
        (0..self.edge_count())
            .filter(|&e| self.needs_split(e))
            .collect()
    }

    /// Whether edge `e` is not strictly Delaunay by [`STRICT_DELAUNAY_MARGIN`].
    pub(crate) fn needs_split(&self, e: usize) -> bool {
        let (sum, scale) = self.cotan_sum_and_scale(e);
        sum <= STRICT_DELAUNAY_MARGIN * scale
    }

    /// Where to split edge `e`, as a fraction along its reference halfedge.
    fn split_fraction(&self, e: usize) -> f64 {
        if !self.is_boundary_edge(e) {
            return interior_split_fraction(self.vertex_count());
        }
        let [tail, head] = self.edge_vertices(e);
        let input = self.input_counts[0];
        let length = self.lengths[e];
        match (tail < input, head < input) {
            (true, false) => concentric_shell(length) / length,
            (false, true) => 1.0 - concentric_shell(length) / length,
            _ => 0.5,
        }
    }
}

/// The power of two nearest `length / 2` between a third and two thirds of `length` (a closed
/// interval of ratio 2 always holds one).
fn concentric_shell(length: f64) -> f64 {
    let mut d = (length / 2.0).log2().round().exp2();
    if d < length / 3.0 {
        d *= 2.0;
    }
    if d > 2.0 * length / 3.0 {
        d /= 2.0;
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::torus;
    use crate::intrinsic::test_meshes::{non_delaunay_meshes, obtuse_triangle, square_grid};
    use std::f64::consts::PI;

    #[test]
    fn shells_are_powers_of_two_near_the_middle() {
        for length in [0.3, 1.0, 1.4, 3.0, 1e-5, 7e4] {
            let d = concentric_shell(length);
            assert!(
                d >= length / 3.0 && d <= 2.0 * length / 3.0,
                "{length}: {d}"
            );
            assert_eq!(d.log2().fract(), 0.0);
        }
    }

    /// Refines `mesh` and checks the guarantee and what must not change.
    fn refine_and_check(name: &str, mesh: &TriangleMesh) -> RefineReport {
        let mut tri = IntrinsicTriangulation::new(mesh).unwrap();
        let before = tri.vertex_angle_sums();
        let report = tri.refine(mesh, RefineOptions::default()).unwrap();
        tri.check_invariants().unwrap();
        for e in 0..tri.edge_count() {
            let (sum, scale) = tri.cotan_sum_and_scale(e);
            assert!(
                sum > STRICT_DELAUNAY_MARGIN * scale,
                "{name}: edge {e}: {sum}"
            );
        }
        assert!(tri.not_strictly_delaunay_edges().is_empty());
        assert!(tri.edge_hodge_star().iter().all(|&s| s > 0.0), "{name}");
        let area = mesh.total_area();
        assert!((tri.total_area() - area).abs() < 1e-12 * area, "{name}");
        let after = tri.vertex_angle_sums();
        for v in 0..mesh.vertex_count() {
            assert!((after[v] - before[v]).abs() < 1e-11, "{name}: vertex {v}");
        }
        for (v, &sum) in after.iter().enumerate().skip(mesh.vertex_count()) {
            let on_boundary = (0..tri.edge_count())
                .any(|e| tri.is_boundary_edge(e) && tri.edge_vertices(e).contains(&v));
            let expected = if on_boundary { PI } else { 2.0 * PI };
            assert!(
                (sum - expected).abs() < 1e-11,
                "{name}: inserted vertex {v}: {sum}"
            );
        }
        let sub = tri.common_subdivision(mesh).unwrap();
        for f in 0..mesh.face_count() {
            let covered: f64 = sub.input_face_overlaps(f).iter().map(|o| o.area).sum();
            assert!(
                (covered - mesh.face_area(f)).abs() < 1e-12 * area,
                "{name}: face {f}"
            );
        }
        assert_eq!(report.inserted, tri.inserted_vertex_count());
        report
    }

    #[test]
    fn refinement_makes_every_edge_strictly_delaunay() {
        let report = refine_and_check("obtuse triangle", &obtuse_triangle());
        assert!(report.inserted >= 1);
        let report = refine_and_check("square grid", &square_grid(6));
        assert!(report.inserted >= 36, "{report:?}");
        let report = refine_and_check("torus", &torus(2.0, 0.6, 16, 9).unwrap());
        assert!(report.inserted > 0);
        for (name, mesh) in non_delaunay_meshes() {
            refine_and_check(name, &mesh);
        }
    }

    #[test]
    fn the_insertion_limit_is_an_error() {
        let mesh = square_grid(4);
        let mut tri = IntrinsicTriangulation::new(&mesh).unwrap();
        let options = RefineOptions {
            max_insertions: Some(3),
        };
        let err = tri.refine(&mesh, options).unwrap_err();
        assert!(
            matches!(err, IntrinsicError::InsertionLimit { inserted: 3, .. }),
            "{err}"
        );
    }
}
