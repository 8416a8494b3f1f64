//! Independent re-derivations of operators from explicit formulas (cotangents and gradients of
//! the 3D triangles, nothing from `tvf-discretizations`), for the reference checks.

use crate::algebra_checks::max_abs_dense;
use crate::corpus::corner_cotangent;
use sprs::CsMat;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::discretization::{LinearOperator, Mass, NodeKind};
use tvf_core::geometry::{cross, dot, scale, sub};
use tvf_core::TriangleMesh;

/// The cotan matrix `S_ij = −(cot α_ij + cot β_ij)/2`, `S_ii = −Σ_j S_ij` (`V × V`, integrated,
/// positive semi-definite).
pub fn cotan_matrix(mesh: &TriangleMesh) -> CsMat<f64> {
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for (t, face) in mesh.faces().iter().enumerate() {
        for c in 0..3 {
            let w = corner_cotangent(mesh, t, c) / 2.0;
            let (i, j) = (face[(c + 1) % 3], face[(c + 2) % 3]);
            for (r, s, v) in [(i, j, -w), (j, i, -w), (i, i, w), (j, j, w)] {
                rows.push(r);
                cols.push(s);
                values.push(v);
            }
        }
    }
    let n = mesh.vertex_count();
    from_triplets(n, n, rows, cols, values)
}

/// The Crouzeix–Raviart stiffness (`E × E`): in face `t`, the edges opposite corners `i` and `j`
/// meet at corner `k` and couple by `−2 cot θ_k`; the edge opposite `i` gets `2 (cot θ_j + cot θ_k)`
/// on the diagonal.
pub fn crouzeix_raviart_matrix(mesh: &TriangleMesh) -> CsMat<f64> {
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for (t, edges) in mesh.face_edges().iter().enumerate() {
        let cot: [f64; 3] = std::array::from_fn(|c| corner_cotangent(mesh, t, c));
        for k in 0..3 {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            for (r, s) in [(edges[i], edges[j]), (edges[j], edges[i])] {
                rows.push(r);
                cols.push(s);
                values.push(-2.0 * cot[k]);
            }
            rows.push(edges[k]);
            cols.push(edges[k]);
            values.push(2.0 * (cot[i] + cot[j]));
        }
    }
    let n = mesh.edge_count();
    from_triplets(n, n, rows, cols, values)
}

/// The weighted dual-graph Laplacian on faces (`F × F`), DEC's `d1 ⋆1⁻¹ d1ᵀ`: two faces sharing
/// edge `e` couple by `−2/(cot α_e + cot β_e)`, the diagonal of face `t` is
/// `Σ_{e ∈ t} 2/(cot α_e + cot β_e)` (one cotangent on a boundary edge).
pub fn dual_graph_matrix(mesh: &TriangleMesh) -> CsMat<f64> {
    let sums = crate::corpus::cotangent_sums(mesh);
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for (e, faces) in mesh.edge_faces().iter().enumerate() {
        let w = 2.0 / sums[e];
        let used: Vec<usize> = faces
            .iter()
            .copied()
            .filter(|&t| t != tvf_core::NO_FACE)
            .collect();
        for &s in &used {
            for &t in &used {
                rows.push(s);
                cols.push(t);
                values.push(if s == t { w } else { -w });
            }
        }
    }
    let n = mesh.face_count();
    from_triplets(n, n, rows, cols, values)
}

/// The explicit stiffness of a space of scalar functions with nodes of kind `kind`: cotan for
/// vertices (P1 and DEC 0-forms), Crouzeix–Raviart for edges, the dual-graph Laplacian for faces
/// (DEC 2-forms); `None` for face frames (not a space of scalar functions).
pub fn explicit_stiffness(kind: NodeKind, mesh: &TriangleMesh) -> Option<CsMat<f64>> {
    match kind {
        NodeKind::Vertices => Some(cotan_matrix(mesh)),
        NodeKind::Edges => Some(crouzeix_raviart_matrix(mesh)),
        NodeKind::Faces => Some(dual_graph_matrix(mesh)),
        NodeKind::FaceFrames => None,
    }
}

/// `(max |A − B|, max |B|)` entry for entry; `None` when the shapes differ.
pub fn matrix_deviation(a: &CsMat<f64>, b: &CsMat<f64>) -> Option<(f64, f64)> {
    if a.shape() != b.shape() {
        return None;
    }
    let difference = &a.to_csr() - &b.to_csr();
    let error = difference.data().iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let scale = b.data().iter().fold(0.0f64, |m, x| m.max(x.abs()));
    Some((error, scale))
}

/// `max |A − B| ≤ 1e-10 · max |B|` entry for entry.
pub fn assert_matrices_close(what: &str, a: &CsMat<f64>, b: &CsMat<f64>) {
    assert_matrices_within(what, a, b, 1e-10);
}

/// `max |A − B| ≤ tolerance · max |B|` entry for entry.
pub fn assert_matrices_within(what: &str, a: &CsMat<f64>, b: &CsMat<f64>, tolerance: f64) {
    let deviation = matrix_deviation(a, b);
    let (error, scale) = deviation.unwrap_or_else(|| panic!("{what}: shapes differ"));
    assert!(
        error <= tolerance * scale,
        "{what}: differs by {error:e} (max entry {scale:e})"
    );
}

/// Two derived operators agree: `max |A − B| ≤ 1e-10 · max |B|` entry for entry, as sparse
/// matrices where both are, else formed densely (small meshes only).
pub fn assert_operators_close(what: &str, a: &LinearOperator, b: &LinearOperator) {
    if let (Some(a), Some(b)) = (a.as_sparse(), b.as_sparse()) {
        return assert_matrices_close(what, a, b);
    }
    assert_eq!(a.shape(), b.shape(), "{what}: shapes differ");
    let (a, b) = (a.to_dense(), b.to_dense());
    let error = max_abs_dense(&(&a - &b));
    let scale = max_abs_dense(&b);
    assert!(
        error <= 1e-10 * scale,
        "{what}: differs by {error:e} (max entry {scale:e})"
    );
}

/// A derived operator equals an explicit sparse matrix (`max |A − B| ≤ 1e-10 · max |B|`): entry
/// for entry if it is sparse, else formed densely.
pub fn assert_operator_equals(what: &str, a: &LinearOperator, b: &CsMat<f64>) {
    assert_operators_close(what, a, &LinearOperator::Sparse(b.clone()));
}

/// The 3D gradients on face `t` of the piecewise linear basis functions with nodes of kind
/// `kind` that are non-zero on `t`: `(node, ∇ψ)`. P1 hat of corner `c`:
/// `n × (p_{c+2} − p_{c+1}) / 2A`; Crouzeix–Raviart function of the edge opposite corner `c`:
/// `1 − 2 φ_c`, gradient `−2 ∇φ_c`. `None` for other kinds.
pub fn basis_gradients(
    kind: NodeKind,
    mesh: &TriangleMesh,
    t: usize,
) -> Option<[(usize, [f64; 3]); 3]> {
    let p: [[f64; 3]; 3] = std::array::from_fn(|c| mesh.corner(t, c));
    let scaled_normal = cross(sub(p[1], p[0]), sub(p[2], p[0]));
    let two_area_squared = dot(scaled_normal, scaled_normal);
    // n / 2A = scaled_normal / |scaled_normal|², since |scaled_normal| = 2A.
    let hat = |c: usize| {
        scale(
            cross(scaled_normal, sub(p[(c + 2) % 3], p[(c + 1) % 3])),
            1.0 / two_area_squared,
        )
    };
    match kind {
        NodeKind::Vertices => Some(std::array::from_fn(|c| (mesh.faces()[t][c], hat(c)))),
        NodeKind::Edges => Some(std::array::from_fn(|c| {
            (mesh.face_edges()[t][c], scale(hat(c), -2.0))
        })),
        NodeKind::Faces | NodeKind::FaceFrames => None,
    }
}

/// Pointwise divergence and curl of a piecewise constant field (one 3D tangent vector `v_t` per
/// face) on the nodes of a space of kind `kind` with mass `mass` (`n × n`, the space's inner
/// product): `div = −M⁻¹ d` and `curl = M⁻¹ c` with the integrated values
/// `d_i = Σ_t A_t ⟨∇ψ_i, v_t⟩` and `c_i = Σ_t A_t ⟨∇ψ_i, n_t × v_t⟩` (`n` entries each; a lumped
/// mass divides node by node). Panics for kinds without [`basis_gradients`].
pub fn explicit_divergence_and_curl(
    kind: NodeKind,
    mesh: &TriangleMesh,
    mass: &Mass,
    vectors: &[[f64; 3]],
) -> (Vec<f64>, Vec<f64>) {
    let mut divergence = vec![0.0; mass.len()];
    let mut curl = vec![0.0; mass.len()];
    for (t, &v) in vectors.iter().enumerate() {
        let area = mesh.face_area(t);
        let rotated = cross(mesh.face_normal(t), v);
        let gradients = basis_gradients(kind, mesh, t)
            .unwrap_or_else(|| panic!("no explicit basis gradients for {}", kind.name()));
        for (node, gradient) in gradients {
            divergence[node] -= area * dot(gradient, v);
            curl[node] += area * dot(gradient, rotated);
        }
    }
    (mass.solve(&divergence), mass.solve(&curl))
}
