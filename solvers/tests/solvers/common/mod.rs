//! Test matrices built in code: grid Laplacians with irregular masses, direct sums.

use sprs::{CsMat, TriMat};

/// Irregular but deterministic positive masses in [0.5, 1.5).
pub fn irregular_masses(n: usize, salt: u64) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let mut x = (i as u64)
                .wrapping_mul(6364136223846793005)
                .wrapping_add(salt.wrapping_mul(1442695040888963407));
            x ^= x >> 33;
            x = x.wrapping_mul(0xff51afd7ed558ccd);
            x ^= x >> 33;
            0.5 + (x % 10_000) as f64 / 10_000.0
        })
        .collect()
}

/// Graph Laplacian (full storage, CSC) of an undirected graph with given weighted edges.
pub fn graph_laplacian(n: usize, edges: &[(usize, usize, f64)]) -> CsMat<f64> {
    let mut t = TriMat::new((n, n));
    for &(a, b, w) in edges {
        t.add_triplet(a, b, -w);
        t.add_triplet(b, a, -w);
        t.add_triplet(a, a, w);
        t.add_triplet(b, b, w);
    }
    for i in 0..n {
        t.add_triplet(i, i, 0.0);
    }
    t.to_csc()
}

/// Path (1D grid) Laplacian with unit weights.
pub fn path_laplacian(n: usize) -> CsMat<f64> {
    let edges: Vec<_> = (0..n.saturating_sub(1)).map(|i| (i, i + 1, 1.0)).collect();
    graph_laplacian(n, &edges)
}

/// `nx × ny` grid Laplacian; `periodic` wraps both directions (a torus: eigenvalues with
/// multiplicities 2 and 4 when nx = ny).
pub fn grid_laplacian(nx: usize, ny: usize, periodic: bool) -> CsMat<f64> {
    let id = |i: usize, j: usize| i + nx * j;
    let mut edges = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            if i + 1 < nx {
                edges.push((id(i, j), id(i + 1, j), 1.0));
            } else if periodic {
                edges.push((id(i, j), id(0, j), 1.0));
            }
            if j + 1 < ny {
                edges.push((id(i, j), id(i, j + 1), 1.0));
            } else if periodic {
                edges.push((id(i, j), id(i, 0), 1.0));
            }
        }
    }
    graph_laplacian(nx * ny, &edges)
}

/// Block-diagonal direct sum of square matrices.
pub fn direct_sum(blocks: &[CsMat<f64>]) -> CsMat<f64> {
    let n: usize = blocks.iter().map(|b| b.rows()).sum();
    let mut t = TriMat::new((n, n));
    let mut offset = 0;
    for b in blocks {
        for (v, (i, j)) in b.iter() {
            t.add_triplet(offset + i, offset + j, *v);
        }
        offset += b.rows();
    }
    t.to_csc()
}

/// `A + shift·diag(mass)` in full storage.
pub fn add_diagonal(a: &CsMat<f64>, mass: &[f64], shift: f64) -> CsMat<f64> {
    let mut t = TriMat::new(a.shape());
    for (v, (i, j)) in a.iter() {
        t.add_triplet(i, j, *v);
    }
    for (i, m) in mass.iter().enumerate() {
        t.add_triplet(i, i, shift * m);
    }
    t.to_csc()
}

/// `y = A x` for a full-storage sparse matrix.
pub fn matvec(a: &CsMat<f64>, x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; a.rows()];
    for (v, (i, j)) in a.iter() {
        y[i] += v * x[j];
    }
    y
}

/// Largest absolute difference between two slices.
pub fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}
