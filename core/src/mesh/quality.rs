//! Geometric measures of a mesh: corner angles, angle range and enclosed (signed) volume.

use super::triangle_mesh::TriangleMesh;
use crate::geometry::{cross, dot, norm, sub};

/// Interior angles (radians) of the triangle `p`, `angles[c]` at corner `c`.
///
/// Uses `atan2(|u×v|, u·v)`, accurate for nearly flat and nearly degenerate corners.
pub fn triangle_angles(p: [[f64; 3]; 3]) -> [f64; 3] {
    let mut angles = [0.0; 3];
    for (c, angle) in angles.iter_mut().enumerate() {
        let u = sub(p[(c + 1) % 3], p[c]);
        let v = sub(p[(c + 2) % 3], p[c]);
        *angle = norm(cross(u, v)).atan2(dot(u, v));
    }
    angles
}

impl TriangleMesh {
    /// Interior angles (radians) of face `t`, `[α0, α1, α2]` at corners 0, 1, 2.
    pub fn corner_angles(&self, t: usize) -> [f64; 3] {
        triangle_angles(self.faces()[t].map(|i| self.positions()[i]))
    }

    /// Smallest and largest interior angle over all faces, in degrees.
    pub fn angle_range_deg(&self) -> (f64, f64) {
        let mut range = (f64::INFINITY, f64::NEG_INFINITY);
        for t in 0..self.face_count() {
            for angle in self.corner_angles(t) {
                range.0 = range.0.min(angle.to_degrees());
                range.1 = range.1.max(angle.to_degrees());
            }
        }
        range
    }

    /// Signed enclosed volume `Σ_t p0 · (p1 × p2) / 6` (units of length³).
    ///
    /// Positive for a closed mesh whose normals point outward; on a mesh with boundary the value
    /// depends on the origin and means little.
    pub fn signed_volume(&self) -> f64 {
        self.faces()
            .iter()
            .map(|f| {
                let [p0, p1, p2] = f.map(|i| self.positions()[i]);
                dot(p0, cross(p1, p2))
            })
            .sum::<f64>()
            / 6.0
    }
}

#[cfg(test)]
mod tests {
    use crate::generate::icosphere;

    #[test]
    fn icosphere_volume_and_angles() {
        let mesh = icosphere(3);
        let volume = mesh.signed_volume();
        // Inscribed polyhedron: slightly below 4π/3, and positive (outward normals).
        assert!(volume > 4.0 && volume < 4.0 * std::f64::consts::PI / 3.0);
        let (min, max) = mesh.angle_range_deg();
        assert!(min > 45.0 && max < 80.0, "{min} {max}");
        for t in 0..mesh.face_count() {
            let sum: f64 = mesh.corner_angles(t).iter().sum();
            assert!((sum - std::f64::consts::PI).abs() < 1e-12);
        }
    }
}
