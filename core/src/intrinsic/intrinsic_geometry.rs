//! Geometry of an intrinsic triangulation from its edge lengths: face areas, angles, vertex
//! angle sums, cotan weights (the DEC Hodge star `⋆1`), vertex areas and the cotan Laplacian.

use super::length_geometry::{
    corner_angles, corner_cotangents, mixed_voronoi_shares, triangle_area,
};
use super::triangulation::{IntrinsicTriangulation, NO_HALFEDGE};
use sprs::{CsMat, TriMat};

impl IntrinsicTriangulation {
    /// Area of face `t` (units²).
    pub fn face_area(&self, t: usize) -> f64 {
        triangle_area(self.face_lengths(t))
    }

    /// Areas of all faces (units²), `F` entries.
    pub fn face_areas(&self) -> Vec<f64> {
        (0..self.face_count()).map(|t| self.face_area(t)).collect()
    }

    /// Total area (units²): the input's, up to round-off, whatever flips and splits were made.
    pub fn total_area(&self) -> f64 {
        self.face_areas().iter().sum()
    }

    /// Interior angles of face `t` (radians), `[θ0, θ1, θ2]` at corners 0, 1, 2.
    pub fn corner_angles(&self, t: usize) -> [f64; 3] {
        corner_angles(self.face_lengths(t))
    }

    /// Cotangents of the interior angles of face `t` (dimensionless), one per corner.
    pub fn corner_cotangents(&self, t: usize) -> [f64; 3] {
        corner_cotangents(self.face_lengths(t))
    }

    /// Sum of the interior angles at each vertex (radians), `V` entries: `2π` minus the angle
    /// defect at an interior vertex. Flips leave it unchanged (up to round-off); an inserted
    /// vertex has `2π` inside the surface, `π` on a boundary edge.
    pub fn vertex_angle_sums(&self) -> Vec<f64> {
        let mut sums = vec![0.0; self.vertex_count()];
        for (t, face) in self.faces.iter().enumerate() {
            for (c, angle) in self.corner_angles(t).into_iter().enumerate() {
                sums[face[c]] += angle;
            }
        }
        sums
    }

    /// `cot α + cot β` for every edge (dimensionless), `α`, `β` the angles opposite it in its
    /// two faces; a single cotangent on a boundary edge. The edge is Delaunay when this is
    /// `≥ 0`: the sum of the opposite angles is at most `π`.
    pub fn cotan_sums(&self) -> Vec<f64> {
        let mut sums = vec![0.0; self.edge_count()];
        for t in 0..self.face_count() {
            let cot = self.corner_cotangents(t);
            for (c, &value) in cot.iter().enumerate() {
                sums[self.halfedge_edge[3 * t + c]] += value;
            }
        }
        sums
    }

    /// The DEC Hodge star on 1-forms, `⋆1 = (cot α + cot β) / 2` per edge (dimensionless; one
    /// cotangent on a boundary edge), `E` entries: the ratio of the circumcentric dual edge's
    /// length to the primal edge's (signed: negative where the circumcentres are on the wrong
    /// side), and the diagonal of DEC's `M1`. Positive on every edge after
    /// [`IntrinsicTriangulation::refine`]; `≥ 0` up to round-off on interior edges after
    /// [`IntrinsicTriangulation::flip_to_delaunay`].
    pub fn edge_hodge_star(&self) -> Vec<f64> {
        self.cotan_sums().iter().map(|s| s / 2.0).collect()
    }

    /// Signed length of the circumcentric dual of every edge (units of length), `⋆1 · l_e`:
    /// the distance between the circumcentres of its two faces (from the edge's midpoint to its
    /// face's circumcentre on the boundary).
    pub fn dual_edge_lengths(&self) -> Vec<f64> {
        self.edge_hodge_star()
            .iter()
            .zip(&self.lengths)
            .map(|(s, l)| s * l)
            .collect()
    }

    /// Barycentric vertex areas (units²), `V` entries: a third of every adjacent face's area
    /// (a face with a repeated corner gives that vertex two thirds). Sum to the total area.
    pub fn barycentric_vertex_areas(&self) -> Vec<f64> {
        let mut areas = vec![0.0; self.vertex_count()];
        for (t, face) in self.faces.iter().enumerate() {
            let third = self.face_area(t) / 3.0;
            for &v in face {
                areas[v] += third;
            }
        }
        areas
    }

    /// Mixed Voronoi vertex areas (units²), `V` entries (Meyer, Desbrun, Schröder and Barr
    /// 2003): each vertex's circumcentric Voronoi cell in non-obtuse faces, `A/2` at an obtuse
    /// corner and `A/4` at the other two. Sum to the total area; DEC's `⋆0` for
    /// `dec-circumcentric`.
    pub fn mixed_voronoi_vertex_areas(&self) -> Vec<f64> {
        let mut areas = vec![0.0; self.vertex_count()];
        for (t, face) in self.faces.iter().enumerate() {
            let shares = mixed_voronoi_shares(self.face_lengths(t));
            for c in 0..3 {
                areas[face[c]] += shares[c];
            }
        }
        areas
    }

    /// The cotan Laplacian `d0ᵀ ⋆1 d0` (`V × V`, CSR, symmetric positive semi-definite on a
    /// Delaunay triangulation, integrated): `−⋆1` summed over the edges between `u ≠ v` off the
    /// diagonal, the negated row sums on it. An edge from a vertex to itself contributes
    /// nothing (its `d0` row is zero).
    pub fn cotan_laplacian(&self) -> CsMat<f64> {
        let n = self.vertex_count();
        let star = self.edge_hodge_star();
        let mut triplets = TriMat::with_capacity((n, n), 4 * self.edge_count());
        for (e, &w) in star.iter().enumerate() {
            let [u, v] = self.edge_vertices(e);
            if u != v {
                triplets.add_triplet(u, v, -w);
                triplets.add_triplet(v, u, -w);
                triplets.add_triplet(u, u, w);
                triplets.add_triplet(v, v, w);
            }
        }
        triplets.to_csr()
    }

    /// `cot α + cot β` of edge `e` and the scale its round-off is measured against,
    /// `max(1, |cot α| + |cot β|)` (single cotangent on the boundary).
    pub(crate) fn cotan_sum_and_scale(&self, e: usize) -> (f64, f64) {
        let h = self.edge_halfedge[e];
        let mut sum = 0.0;
        let mut scale = 0.0;
        for g in [h, self.twin[h]] {
            if g != NO_HALFEDGE {
                let cot = corner_cotangents(self.face_lengths(g / 3))[g % 3];
                sum += cot;
                scale += cot.abs();
            }
        }
        (sum, f64::max(1.0, scale))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{disk, icosphere};
    use crate::geometry::{cross, dot, norm, sub};
    use std::f64::consts::PI;

    #[test]
    fn matches_the_input_geometry() {
        let mesh = icosphere(2);
        let tri = IntrinsicTriangulation::new(&mesh).unwrap();
        for t in 0..mesh.face_count() {
            assert!((tri.face_area(t) - mesh.face_area(t)).abs() < 1e-15);
            let a = tri.corner_angles(t);
            let b = mesh.corner_angles(t);
            for c in 0..3 {
                assert!((a[c] - b[c]).abs() < 1e-14);
            }
        }
        let areas = tri.barycentric_vertex_areas();
        let voronoi = tri.mixed_voronoi_vertex_areas();
        let total = mesh.total_area();
        assert!((areas.iter().sum::<f64>() - total).abs() < 1e-13 * total);
        assert!((voronoi.iter().sum::<f64>() - total).abs() < 1e-13 * total);
    }

    #[test]
    fn cotan_weights_from_positions_agree() {
        let mesh = disk(4);
        let tri = IntrinsicTriangulation::new(&mesh).unwrap();
        let mut expected = vec![0.0; mesh.edge_count()];
        for (t, face) in mesh.faces().iter().enumerate() {
            for c in 0..3 {
                let p = mesh.positions();
                let (o, a, b) = (p[face[c]], p[face[(c + 1) % 3]], p[face[(c + 2) % 3]]);
                let (u, v) = (sub(a, o), sub(b, o));
                expected[mesh.face_edges()[t][c]] += dot(u, v) / norm(cross(u, v)) / 2.0;
            }
        }
        for (s, x) in tri.edge_hodge_star().iter().zip(&expected) {
            assert!((s - x).abs() < 1e-13 * x.abs().max(1.0), "{s} {x}");
        }
        // The Laplacian annihilates constants and is symmetric.
        let l = tri.cotan_laplacian();
        for (row, vec) in l.outer_iterator().enumerate() {
            let sum: f64 = vec.iter().map(|(_, &x)| x).sum();
            assert!(sum.abs() < 1e-12, "row {row}: {sum}");
            for (col, &x) in vec.iter() {
                assert_eq!(l.get(col, row).copied(), Some(x));
            }
        }
    }

    #[test]
    fn angle_sums_of_a_flat_disk() {
        let tri = IntrinsicTriangulation::new(&disk(3)).unwrap();
        let sums = tri.vertex_angle_sums();
        // The centre is interior and flat; boundary vertices of a polygon approximating the
        // circle have angle sums just below π.
        assert!((sums[0] - 2.0 * PI).abs() < 1e-13);
        assert!(sums
            .iter()
            .skip(1)
            .all(|&s| s > 0.0 && s <= 2.0 * PI + 1e-13));
    }
}
