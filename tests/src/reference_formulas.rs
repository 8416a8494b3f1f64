//! Independent re-derivations of the stiffness matrices from the explicit formulas (cotangents of
//! the 3D triangle angles), used to check the assembled `Gᵀ M_X G` and `G*ᵀ M_X G*`.

use sprs::CsMat;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::discretization::{FunctionSpace, HodgeComplex, HodgeOperators};
use tvf_core::SurfaceMesh;

/// Cotangent of the angle at corner `c` of face `t`, from 3D positions.
fn corner_cotangent(mesh: &SurfaceMesh, t: usize, c: usize) -> f64 {
    let o = mesh.corner(t, c);
    let a = mesh.corner(t, (c + 1) % 3);
    let b = mesh.corner(t, (c + 2) % 3);
    let u = [a[0] - o[0], a[1] - o[1], a[2] - o[2]];
    let v = [b[0] - o[0], b[1] - o[1], b[2] - o[2]];
    let dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let cross = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    dot / (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt()
}

/// The cotan matrix `S_ij = −(cot α_ij + cot β_ij)/2`, `S_ii = −Σ_j S_ij` (`V × V`).
pub fn cotan_matrix(mesh: &SurfaceMesh) -> CsMat<f64> {
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
pub fn crouzeix_raviart_matrix(mesh: &SurfaceMesh) -> CsMat<f64> {
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

/// `max |A − B| ≤ 1e-10 · max |B|` entry for entry.
pub fn assert_matrices_close(what: &str, a: &CsMat<f64>, b: &CsMat<f64>) {
    assert_eq!(a.shape(), b.shape(), "{what}: shapes differ");
    let difference = &a.to_csr() - &b.to_csr();
    let error = difference.data().iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let scale = b.data().iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(
        error <= 1e-10 * scale,
        "{what}: differs by {error:e} (max entry {scale:e})"
    );
}

/// The stiffness of whichever space is P1 (dimension `V`) equals the cotan matrix and that of
/// whichever is Crouzeix–Raviart (dimension `E`) equals the CR formula. Panics if a space has
/// neither dimension (the check only applies to P1/CR discretizations).
pub fn check_cotan_formula<H: HodgeComplex>(complex: &H, mesh: &SurfaceMesh) {
    let cotan = cotan_matrix(mesh);
    let cr = crouzeix_raviart_matrix(mesh);
    for (which, dimension, stiffness) in [
        (
            "potential",
            complex.potentials().dimension(),
            complex.potential_stiffness(),
        ),
        (
            "co-potential",
            complex.co_potentials().dimension(),
            complex.co_potential_stiffness(),
        ),
    ] {
        if dimension == mesh.vertex_count() {
            assert_matrices_close(&format!("{which} stiffness vs cotan"), &stiffness, &cotan);
        } else if dimension == mesh.edge_count() {
            assert_matrices_close(&format!("{which} stiffness vs CR formula"), &stiffness, &cr);
        } else {
            panic!("{which} space has dimension {dimension}: neither P1 nor Crouzeix-Raviart");
        }
    }
}
