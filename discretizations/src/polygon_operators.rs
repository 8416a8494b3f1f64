//! The per-polygon operators of polygonal DEC (de Goes, Butts, Desbrun, *Discrete Differential
//! Operators on Polygonal Meshes*, ACM TOG 39(4), 2020, §4): the flat `V_f`, the sharp `U_f`,
//! the projection `P_f = I − V_f U_f` and the local inner product of 1-forms
//! `M_f = |a_f| U_fᵀ U_f + β P_fᵀ P_f`, all in the mesh's edge orientation.

use tvf_core::geometry::{cross, dot, scale, sub};
use tvf_core::mesh::Mesh;
use tvf_core::mesh::{polygon_centroid, polygon_vector_area};

/// The operators of one polygon with `n` corners `p_0 … p_{n−1}` (counter-clockwise), vector
/// area `a_f = ½ Σ p_c × p_{c+1}`, area `A_f = |a_f|`, normal `n_f = a_f/A_f` and centroid
/// `m_f` (the corner average). Side `c` joins corner `c` to corner `c + 1`; `signs[c]` is `+1`
/// where that side runs along its mesh edge `(a, b)`, `a < b`, and `−1` where it runs against it,
/// so every operator acts on 1-forms as the complex stores them (integrals from `a` to `b`).
#[derive(Debug, Clone)]
pub struct PolygonOperators {
    /// The vector area `a_f` (units of length²).
    pub vector_area: [f64; 3],
    /// `A_f = |a_f|` (units of length²).
    pub area: f64,
    /// `±1` per side: the side's direction against its mesh edge's orientation.
    pub signs: Vec<f64>,
    /// The sharp `U_f` (`3 × n`, by columns): `U_f[:, c] = signs[c] · a_f × (s_c − m_f) / A_f²`,
    /// `s_c` the midpoint of side `c` (units 1/length). It maps the 1-form of a constant field
    /// `v` to `v` projected onto the plane normal to `a_f`.
    pub sharp: Vec<[f64; 3]>,
    /// The flat `V_f` (`n × 3`, by rows): `V_f[c] = (I − n_f n_fᵀ)(p_b − p_a)` for side `c`'s
    /// mesh edge `(a, b)` (units of length).
    pub flat: Vec<[f64; 3]>,
}

impl PolygonOperators {
    /// The operators of face `f` of `mesh`.
    pub fn of<M: Mesh + ?Sized>(mesh: &M, f: usize) -> Self {
        let corners = mesh.face_corners().corners(f);
        let points: Vec<[f64; 3]> = corners.iter().map(|&v| mesh.positions()[v]).collect();
        let n = points.len();
        let vector_area = polygon_vector_area(&points);
        let area_squared = dot(vector_area, vector_area);
        let area = area_squared.sqrt();
        let normal = scale(vector_area, 1.0 / area);
        let centroid = polygon_centroid(&points);
        let mut signs = Vec::with_capacity(n);
        let mut sharp = Vec::with_capacity(n);
        let mut flat = Vec::with_capacity(n);
        for c in 0..n {
            let (from, to) = (points[c], points[(c + 1) % n]);
            let sign = if corners[c] < corners[(c + 1) % n] {
                1.0
            } else {
                -1.0
            };
            let midpoint = scale([from[0] + to[0], from[1] + to[1], from[2] + to[2]], 0.5);
            let u = cross(vector_area, sub(midpoint, centroid));
            sharp.push(scale(u, sign / area_squared));
            let edge = scale(sub(to, from), sign);
            flat.push(sub(edge, scale(normal, dot(normal, edge))));
            signs.push(sign);
        }
        Self {
            vector_area,
            area,
            signs,
            sharp,
            flat,
        }
    }

    /// Number of sides `n`.
    pub fn side_count(&self) -> usize {
        self.sharp.len()
    }

    /// The projection `P_f = I − V_f U_f` (`n × n`, row-major): the part of a 1-form on the
    /// polygon that its sharp does not see (zero on the 1-forms of constant fields).
    pub fn projection(&self) -> Vec<f64> {
        let n = self.side_count();
        let mut p = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                let identity = if i == j { 1.0 } else { 0.0 };
                p[i * n + j] = identity - dot(self.flat[i], self.sharp[j]);
            }
        }
        p
    }

    /// The local inner product of 1-forms `M_f = A_f U_fᵀ U_f + β P_fᵀ P_f` (`n × n`,
    /// row-major, symmetric; dimensionless): the first term is exact on the 1-forms of constant
    /// fields, the second (`β > 0`) makes `M_f` positive definite on the rest (the virtual-element
    /// stabilisation of de Goes et al. 2020, eq. 18).
    pub fn inner_product(&self, beta: f64) -> Vec<f64> {
        let n = self.side_count();
        let p = self.projection();
        let mut m = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                let stabilisation: f64 = (0..n).map(|k| p[k * n + i] * p[k * n + j]).sum();
                m[i * n + j] = self.area * dot(self.sharp[i], self.sharp[j]) + beta * stabilisation;
            }
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::generate::{cube_sphere, quad_torus};
    use tvf_core::geometry::add;
    use tvf_core::SurfaceMesh;

    /// `U_f V_f = I − n nᵀ` on every polygon, planar or not: the sharp of the flat of a vector
    /// is its projection onto the polygon's plane (de Goes et al. 2020, §4.3).
    #[test]
    fn sharp_after_flat_projects_onto_the_polygon_plane() {
        for mesh in [
            SurfaceMesh::from(cube_sphere(3).unwrap()),
            SurfaceMesh::from(quad_torus(1.0, 0.3, 7, 5).unwrap()),
        ] {
            for f in 0..mesh.face_count() {
                let ops = PolygonOperators::of(&mesh, f);
                let n = scale(ops.vector_area, 1.0 / ops.area);
                let v = [0.3, -1.2, 0.8];
                let flat: Vec<f64> = ops.flat.iter().map(|&row| dot(row, v)).collect();
                let sharp = flat
                    .iter()
                    .zip(&ops.sharp)
                    .fold([0.0; 3], |sum, (&x, &row)| add(sum, scale(row, x)));
                let expected = sub(v, scale(n, dot(n, v)));
                assert!(
                    tvf_core::geometry::norm(sub(sharp, expected)) < 1e-12,
                    "face {f}: {sharp:?} vs {expected:?}"
                );
            }
        }
    }
}
