//! [`PlanarTriangle`]: one triangle laid out in the plane of its frame — what every per-face
//! formula of the finite element spaces, the mass lumpings and the Whitney mass reads. It is laid
//! out from positions ([`crate::face_geometry::FaceGeometry::triangle`]) or from three edge
//! lengths ([`PlanarTriangle::from_lengths`], for an intrinsic triangulation) alike: every
//! matrix assembled from it depends only on the metric.

use tvf_core::intrinsic::{triangle_area, IntrinsicTriangulation};

/// A triangle in the 2D coordinates of its frame (`e1` along corner 0 → corner 1, `e2` the
/// +π/2 rotation of `e1`, the frame convention of `docs/conventions.md`): corner 0 at the origin,
/// corner 1 on the positive `e1` axis, corner 2 on the positive `e2` side (units of length), and
/// the area (length²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarTriangle {
    /// The corners in the frame, relative to corner 0 (so `corners[0] = (0, 0)`).
    pub corners: [[f64; 2]; 3],
    /// The area, positive for a non-degenerate triangle.
    pub area: f64,
}

impl PlanarTriangle {
    /// The triangle with side lengths `lengths` (`lengths[c]` opposite corner `c`), laid out as
    /// a face of a mesh is in its frame: corner 1 at `(l_2, 0)`, corner 2 at
    /// `((l_2² + l_1² − l_0²) / 2l_2, 2A / l_2)`. The area is Kahan's stable Heron formula
    /// ([`triangle_area`]); 0 (and corners not finite) when the lengths make no triangle.
    pub fn from_lengths(lengths: [f64; 3]) -> Self {
        let [l0, l1, l2] = lengths;
        let area = triangle_area(lengths);
        let x = (l2 * l2 + l1 * l1 - l0 * l0) / (2.0 * l2);
        let y = 2.0 * area / l2;
        Self {
            corners: [[0.0, 0.0], [l2, 0.0], [x, y]],
            area,
        }
    }

    /// Every face of `tri` laid out from its edge lengths ([`PlanarTriangle::from_lengths`]),
    /// `F` entries.
    pub fn of_intrinsic_faces(tri: &IntrinsicTriangulation) -> Vec<Self> {
        (0..tri.face_count())
            .map(|t| Self::from_lengths(tri.face_lengths(t)))
            .collect()
    }

    /// Gradients of the three P1 hat functions in the frame (pointwise, 1/length):
    /// `grad φ_c = J (p_{c+2} − p_{c+1}) / (2 A)`.
    pub fn hat_gradients(&self) -> [[f64; 2]; 3] {
        let p = &self.corners;
        let two_area = 2.0 * self.area;
        std::array::from_fn(|c| {
            let a = p[(c + 1) % 3];
            let b = p[(c + 2) % 3];
            let e = [b[0] - a[0], b[1] - a[1]];
            [-e[1] / two_area, e[0] / two_area]
        })
    }

    /// Cotangent of the interior angle at every corner (dimensionless).
    pub fn cotangents(&self) -> [f64; 3] {
        let p = &self.corners;
        let two_area = 2.0 * self.area;
        std::array::from_fn(|c| {
            let a = p[(c + 1) % 3];
            let b = p[(c + 2) % 3];
            let o = p[c];
            let u = [a[0] - o[0], a[1] - o[1]];
            let v = [b[0] - o[0], b[1] - o[1]];
            (u[0] * v[0] + u[1] * v[1]) / two_area
        })
    }

    /// Squared length of the side opposite every corner (length²).
    pub fn squared_edge_lengths(&self) -> [f64; 3] {
        let p = &self.corners;
        std::array::from_fn(|c| {
            let a = p[(c + 1) % 3];
            let b = p[(c + 2) % 3];
            (b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)
        })
    }

    /// The tangent vector `Σ_c d_c p_c` of a displacement `d` of barycentric coordinates (three
    /// components summing to 0), in the frame.
    pub fn vector_of_displacement(&self, d: [f64; 3]) -> [f64; 2] {
        let p = &self.corners;
        std::array::from_fn(|k| d[0] * p[0][k] + d[1] * p[1][k] + d[2] * p[2][k])
    }

    /// The displacement of barycentric coordinates `(⟨∇λ_c, v⟩)_c` of the frame vector `v`: the
    /// inverse of [`PlanarTriangle::vector_of_displacement`].
    pub fn displacement_of_vector(&self, v: [f64; 2]) -> [f64; 3] {
        self.hat_gradients().map(|g| g[0] * v[0] + g[1] * v[1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_layout_from_lengths_has_those_lengths_and_angles() {
        let t = PlanarTriangle::from_lengths([5.0, 4.0, 3.0]);
        // Sides 3, 4, 5: the right angle at corner 0, area 6.
        assert!((t.area - 6.0).abs() < 1e-14);
        let l2 = t.squared_edge_lengths();
        for (found, side) in l2.iter().zip([5.0f64, 4.0, 3.0]) {
            assert!((found - side * side).abs() < 1e-13, "{found}");
        }
        assert!(t.cotangents()[0].abs() < 1e-15);
        assert!(t.corners[2][1] > 0.0);
        let v = [0.3, -0.8];
        let back = t.vector_of_displacement(t.displacement_of_vector(v));
        assert!((back[0] - v[0]).abs() < 1e-15 && (back[1] - v[1]).abs() < 1e-15);
    }
}
