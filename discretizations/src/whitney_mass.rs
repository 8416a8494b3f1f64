//! The Whitney 1-form mass `∫ ⟨W_e, W_f⟩`: the Galerkin inner product of 1-forms on edges.

use crate::face_geometry::FaceGeometry;
use crate::planar_triangle::PlanarTriangle;
use sprs::CsMat;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::TriangleMesh;

/// `∫_T λ_a λ_b / |T| = (1 + δ_ab) / 12` for barycentric coordinates `a`, `b` of a triangle.
fn barycentric_product(a: usize, b: usize) -> f64 {
    if a == b {
        1.0 / 6.0
    } else {
        1.0 / 12.0
    }
}

/// The element mass of face `t`: `[c][d] = ∫_T ⟨W_c, W_d⟩` for the Whitney forms
/// `W_c = λ_j ∇λ_k − λ_k ∇λ_j` of the edges opposite corners `c` and `d`, each oriented from
/// corner `j = c+1` to corner `k = c+2` (so not yet by the mesh's edge orientation); units
/// dimensionless (`|T|` times 1/length²). Symmetric positive definite for a non-degenerate face.
///
/// With `∫_T λ_a λ_b = |T| (1 + δ_ab)/12` and `G_ab = ⟨∇λ_a, ∇λ_b⟩` (constant on `T`):
/// `∫ ⟨W_c, W_d⟩ = ∫λ_jλ_j' G_kk' − ∫λ_jλ_k' G_kj' − ∫λ_kλ_j' G_jk' + ∫λ_kλ_k' G_jj'`.
fn whitney_element_mass(triangle: &PlanarTriangle) -> [[f64; 3]; 3] {
    let g = triangle.hat_gradients();
    let gram = |a: usize, b: usize| g[a][0] * g[b][0] + g[a][1] * g[b][1];
    let area = triangle.area;
    let entry = |c: usize, d: usize| {
        let (j, k) = ((c + 1) % 3, (c + 2) % 3);
        let (jj, kk) = ((d + 1) % 3, (d + 2) % 3);
        area * (barycentric_product(j, jj) * gram(k, kk)
            - barycentric_product(j, kk) * gram(k, jj)
            - barycentric_product(k, jj) * gram(j, kk)
            + barycentric_product(k, kk) * gram(j, jj))
    };
    // One evaluation per pair, so that the matrix is exactly symmetric.
    std::array::from_fn(|c| std::array::from_fn(|d| entry(c.min(d), c.max(d))))
}

/// The Whitney 1-form mass `M1[e, f] = Σ_T ∫_T ⟨W_e, W_f⟩` (`E × E`, symmetric, CSR) for the
/// 1-forms of [`crate::WhitneyGalerkin`]: `W_e = W_(a,b) = λ_a ∇λ_b − λ_b ∇λ_a` for the edge
/// `e = (a, b)`, `a < b`, as [`TriangleMesh::edges`] numbers and orients it. `x ↦ xᵀ M1 x` is the
/// squared `L²` norm of the Whitney field of the 1-form `x`.
///
/// Positive definite on every mesh without degenerate faces (each element mass is, and every
/// edge has a face), with no condition on the angles; at most 5 entries per row on a closed
/// mesh (the edge and the other two edges of each of its faces). `d0ᵀ M1 d0` is the cotan
/// matrix: the Whitney field of `d0 f` is the gradient of the P1 function `f`.
pub fn whitney_mass(mesh: &TriangleMesh, geometry: &FaceGeometry) -> CsMat<f64> {
    // +1 where the mesh orients the edge opposite corner c from corner c+1 to corner c+2.
    let signs = mesh.faces().iter().map(|face| {
        std::array::from_fn(|c| {
            if face[(c + 1) % 3] < face[(c + 2) % 3] {
                1.0
            } else {
                -1.0
            }
        })
    });
    assemble_whitney_mass(
        mesh.edge_count(),
        mesh.face_edges().iter().copied(),
        signs,
        (0..mesh.face_count()).map(|t| geometry.triangle(t)),
    )
}

/// [`whitney_mass`] of `edge_count` edges from, per face, its edges `face_edges[t][c]` (opposite
/// corner `c`), the signs `signs[t][c]` (`+1` where the edge's orientation runs from corner
/// `c + 1` to `c + 2`) and its layout: the mesh's, or an intrinsic triangulation's.
pub(crate) fn assemble_whitney_mass(
    edge_count: usize,
    face_edges: impl ExactSizeIterator<Item = [usize; 3]>,
    signs: impl Iterator<Item = [f64; 3]>,
    triangles: impl Iterator<Item = PlanarTriangle>,
) -> CsMat<f64> {
    let capacity = 9 * face_edges.len();
    let (mut rows, mut cols, mut values) = (
        Vec::with_capacity(capacity),
        Vec::with_capacity(capacity),
        Vec::with_capacity(capacity),
    );
    for ((edges, sign), triangle) in face_edges.zip(signs).zip(triangles) {
        let element = whitney_element_mass(&triangle);
        for c in 0..3 {
            for d in 0..3 {
                rows.push(edges[c]);
                cols.push(edges[d]);
                values.push(sign[c] * sign[d] * element[c][d]);
            }
        }
    }
    from_triplets(edge_count, edge_count, rows, cols, values)
}
