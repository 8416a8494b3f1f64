//! Per-face geometry shared by the tracers and the renderer: barycentric gradients, tangent
//! directions, vertex normals and the mean edge length.

use rayon::prelude::*;
use tvf_core::geometry::{cross, dot, norm, normalize, scale, sub};
use tvf_core::TriangleMesh;

/// Mean edge length of `mesh` (mesh length units); `0` for a mesh without edges.
pub fn mean_edge_length(mesh: &TriangleMesh) -> f64 {
    let p = mesh.positions();
    let edges = mesh.edges();
    if edges.is_empty() {
        return 0.0;
    }
    edges
        .iter()
        .map(|e| norm(sub(p[e[1]], p[e[0]])))
        .sum::<f64>()
        / edges.len() as f64
}

/// Unit vertex normals: area-weighted averages of the adjacent face normals (`V` entries).
pub fn vertex_normals(mesh: &TriangleMesh) -> Vec<[f64; 3]> {
    let mut normals = vec![[0.0; 3]; mesh.vertex_count()];
    for (t, f) in mesh.faces().iter().enumerate() {
        let n = mesh.face_normal_scaled(t);
        for &v in f {
            for k in 0..3 {
                normals[v][k] += n[k];
            }
        }
    }
    normals.iter().map(|&n| normalize(n)).collect()
}

/// `v` minus its component along the unit normal `n`.
pub fn tangential(v: [f64; 3], n: [f64; 3]) -> [f64; 3] {
    sub(v, scale(n, dot(v, n)))
}

/// Gradients of the three barycentric coordinates of each face (`F × 3` vectors, units
/// 1/length): `λ_c(x) = ∇λ_c · (x − p_{c+1})`, and `∇λ_c` points from the edge opposite
/// corner `c` towards corner `c`.
pub fn barycentric_gradients(mesh: &TriangleMesh) -> Vec<[[f64; 3]; 3]> {
    (0..mesh.face_count())
        .into_par_iter()
        .map(|t| {
            let n2 = mesh.face_normal_scaled(t); // length 2A
            let a2 = dot(n2, n2);
            let mut g = [[0.0; 3]; 3];
            if a2 > 0.0 {
                for (c, gc) in g.iter_mut().enumerate() {
                    let e = sub(mesh.corner(t, (c + 2) % 3), mesh.corner(t, (c + 1) % 3));
                    *gc = scale(cross(n2, e), 1.0 / a2);
                }
            }
            g
        })
        .collect()
}

/// Barycentric coordinates of `x` in face `t` given the face's gradients.
pub fn barycentric(mesh: &TriangleMesh, grads: &[[f64; 3]; 3], t: usize, x: [f64; 3]) -> [f64; 3] {
    let mut l = [0.0; 3];
    for (c, lc) in l.iter_mut().enumerate() {
        *lc = dot(grads[c], sub(x, mesh.corner(t, (c + 1) % 3)));
    }
    l
}

/// The point with barycentric coordinates `l` in face `t`.
pub fn point_at(mesh: &TriangleMesh, t: usize, l: [f64; 3]) -> [f64; 3] {
    let a = mesh.corner(t, 0);
    let b = mesh.corner(t, 1);
    let c = mesh.corner(t, 2);
    [
        l[0] * a[0] + l[1] * b[0] + l[2] * c[0],
        l[0] * a[1] + l[1] * b[1] + l[2] * c[1],
        l[0] * a[2] + l[1] * b[2] + l[2] * c[2],
    ]
}

/// Centroid of face `t`.
pub fn centroid(mesh: &TriangleMesh, t: usize) -> [f64; 3] {
    point_at(mesh, t, [1.0 / 3.0; 3])
}
