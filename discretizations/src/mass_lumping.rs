//! Mass lumping: how each triangle's area is shared among the nodes of a function space.
//!
//! This is the plug-in point the paper names ("alternatively the Voronoi areas of the vertices
//! and edge midpoints can be used"). Every rule splits each triangle's area exactly among its
//! three nodes, so masses are positive and sum to the total area.

use crate::face_geometry::FaceGeometry;
use crate::planar_triangle::PlanarTriangle;
use tvf_core::TriangleMesh;

/// A rule that splits each triangle's area among the nodes of a function space.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum MassLumping {
    /// A third of every adjacent triangle's area per vertex / per edge (the paper's default).
    #[default]
    Barycentric,
    /// Voronoi-type areas.
    ///
    /// - **Vertices (P1)**: the mixed Voronoi areas of Meyer, Desbrun, Schröder and Barr (2003):
    ///   in a non-obtuse triangle, corner `i` gets `(|p_i p_j|² cot γ_k + |p_i p_k|² cot γ_j)/8`
    ///   (its Voronoi cell inside the triangle); in an obtuse triangle the obtuse corner gets
    ///   `A/2` and the other two `A/4`.
    /// - **Edge midpoints (Crouzeix–Raviart)**: the area of the part of the triangle that is
    ///   closer to that edge's midpoint than to the other two midpoints (the Voronoi cells of the
    ///   three midpoints, clipped to the triangle). Every cell contains a neighbourhood of its
    ///   midpoint, so the mass is positive even in obtuse or right triangles, where the
    ///   circumcentric "diamond" areas would vanish or turn negative.
    Voronoi,
}

impl MassLumping {
    /// Lower-case name as used on the command line (`barycentric`, `voronoi`).
    pub fn name(self) -> &'static str {
        match self {
            MassLumping::Barycentric => "barycentric",
            MassLumping::Voronoi => "voronoi",
        }
    }

    /// The share of `triangle`'s area of each corner vertex (P1 nodes), summing to its area.
    pub fn vertex_shares(self, triangle: &PlanarTriangle) -> [f64; 3] {
        let area = triangle.area;
        match self {
            MassLumping::Barycentric => [area / 3.0; 3],
            MassLumping::Voronoi => {
                let cot = triangle.cotangents();
                let len2 = triangle.squared_edge_lengths();
                match (0..3).find(|&c| cot[c] < 0.0) {
                    Some(obtuse) => {
                        std::array::from_fn(|c| if c == obtuse { area / 2.0 } else { area / 4.0 })
                    }
                    None => std::array::from_fn(|c| {
                        // Edge opposite corner c+1 joins c and c+2; opposite c+2 joins c and c+1.
                        let (j, k) = ((c + 1) % 3, (c + 2) % 3);
                        (len2[k] * cot[k] + len2[j] * cot[j]) / 8.0
                    }),
                }
            }
        }
    }

    /// The share of `triangle`'s area of the side opposite each corner (CR nodes), summing to
    /// its area.
    pub fn edge_shares(self, triangle: &PlanarTriangle) -> [f64; 3] {
        let area = triangle.area;
        match self {
            MassLumping::Barycentric => [area / 3.0; 3],
            MassLumping::Voronoi => {
                let p = &triangle.corners;
                let midpoints: [[f64; 2]; 3] = std::array::from_fn(|c| {
                    let (a, b) = (p[(c + 1) % 3], p[(c + 2) % 3]);
                    [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0]
                });
                std::array::from_fn(|c| {
                    let mut polygon = p.to_vec();
                    for other in [(c + 1) % 3, (c + 2) % 3] {
                        polygon = clip_closer_to(&polygon, midpoints[c], midpoints[other]);
                    }
                    polygon_area(&polygon)
                })
            }
        }
    }

    /// Lumped P1 masses (`V` entries, area); zero for a vertex no face uses.
    pub fn vertex_masses(self, mesh: &TriangleMesh, geometry: &FaceGeometry) -> Vec<f64> {
        lumped_masses(
            mesh.vertex_count(),
            mesh.faces().iter().copied(),
            (0..mesh.face_count()).map(|t| self.vertex_shares(&geometry.triangle(t))),
        )
    }

    /// Lumped Crouzeix–Raviart masses (`E` entries, area).
    pub fn edge_masses(self, mesh: &TriangleMesh, geometry: &FaceGeometry) -> Vec<f64> {
        lumped_masses(
            mesh.edge_count(),
            mesh.face_edges().iter().copied(),
            (0..mesh.face_count()).map(|t| self.edge_shares(&geometry.triangle(t))),
        )
    }
}

/// The lumped mass of each of `node_count` nodes (area): the sum of the shares `shares[t][c]` of
/// every face `t` whose corner (or side) `c` is node `nodes[t][c]`.
pub(crate) fn lumped_masses(
    node_count: usize,
    nodes: impl Iterator<Item = [usize; 3]>,
    shares: impl Iterator<Item = [f64; 3]>,
) -> Vec<f64> {
    let mut mass = vec![0.0; node_count];
    for (face_nodes, face_shares) in nodes.zip(shares) {
        for c in 0..3 {
            mass[face_nodes[c]] += face_shares[c];
        }
    }
    mass
}

/// The part of a convex polygon closer to `keep` than to `other` (Sutherland–Hodgman against the
/// perpendicular bisector).
fn clip_closer_to(polygon: &[[f64; 2]], keep: [f64; 2], other: [f64; 2]) -> Vec<[f64; 2]> {
    // Inside: |x − keep|² ≤ |x − other|²  ⇔  s(x) = 2 x·(other − keep) − |other|² + |keep|² ≤ 0.
    let d = [other[0] - keep[0], other[1] - keep[1]];
    let offset = other[0] * other[0] + other[1] * other[1] - keep[0] * keep[0] - keep[1] * keep[1];
    let s = |x: [f64; 2]| 2.0 * (x[0] * d[0] + x[1] * d[1]) - offset;
    let mut out = Vec::with_capacity(polygon.len() + 1);
    for i in 0..polygon.len() {
        let a = polygon[i];
        let b = polygon[(i + 1) % polygon.len()];
        let (sa, sb) = (s(a), s(b));
        if sa <= 0.0 {
            out.push(a);
        }
        if (sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0) {
            let w = sa / (sa - sb);
            out.push([a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])]);
        }
    }
    out
}

/// Area of a simple polygon (absolute value of the shoelace formula).
fn polygon_area(polygon: &[[f64; 2]]) -> f64 {
    let n = polygon.len();
    let twice: f64 = (0..n)
        .map(|i| {
            let (a, b) = (polygon[i], polygon[(i + 1) % n]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum();
    twice.abs() / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::generate::icosphere;

    fn right_triangle_geometry() -> (TriangleMesh, FaceGeometry) {
        let mesh = TriangleMesh::new(
            vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]],
            vec![[0, 1, 2]],
        )
        .unwrap();
        let geometry = FaceGeometry::new(&mesh).unwrap();
        (mesh, geometry)
    }

    #[test]
    fn shares_sum_to_the_face_area() {
        let mesh = icosphere(2);
        let geometry = FaceGeometry::new(&mesh).unwrap();
        for lumping in [MassLumping::Barycentric, MassLumping::Voronoi] {
            for t in 0..mesh.face_count() {
                let area = geometry.areas[t];
                let v: f64 = lumping.vertex_shares(&geometry.triangle(t)).iter().sum();
                let e: f64 = lumping.edge_shares(&geometry.triangle(t)).iter().sum();
                assert!((v - area).abs() < 1e-14 * area.max(1.0));
                assert!((e - area).abs() < 1e-14 * area.max(1.0));
            }
        }
    }

    #[test]
    fn voronoi_shares_of_a_right_triangle() {
        // Legs 2, area 2. Right angle at corner 0: Meyer's rule gives the Voronoi split
        // (cot 90° = 0): corner 0 gets (4·1 + 4·1)/8 = 1, the others 1/2 each.
        let (_, geometry) = right_triangle_geometry();
        let v = MassLumping::Voronoi.vertex_shares(&geometry.triangle(0));
        assert!((v[0] - 1.0).abs() < 1e-14 && (v[1] - 0.5).abs() < 1e-14);
        // Midpoints (1,1) [hypotenuse, opposite corner 0], (0,1), (1,0). The hypotenuse
        // midpoint's cell is {x ≥ 1/2, y ≥ 1/2} inside the triangle: a right triangle with legs
        // 1, area 1/2; the two legs' cells share the remaining 3/2 equally.
        let e = MassLumping::Voronoi.edge_shares(&geometry.triangle(0));
        assert!((e[0] - 0.5).abs() < 1e-14, "{e:?}");
        assert!((e[1] - e[2]).abs() < 1e-14);
        assert!((e[1] - 0.75).abs() < 1e-14);
    }
}
