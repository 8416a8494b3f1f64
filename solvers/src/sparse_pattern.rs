//! Sparse CSR matrices with a fixed, growing pattern: a system that keeps the union of every
//! pattern it has seen refactors numerically, with the symbolic analysis reused, when its
//! entries change.

use sprs::CsMat;

/// Position of `(row, col)` in the CSR data of `matrix`, if the pattern holds it.
pub fn position(matrix: &CsMat<f64>, row: usize, col: usize) -> Option<usize> {
    let start = matrix.indptr().index(row);
    let end = matrix.indptr().index(row + 1);
    matrix.indices()[start..end]
        .binary_search(&col)
        .ok()
        .map(|k| start + k)
}

/// `matrix` (CSR, sorted) with its pattern extended by `extra` positions, stored as explicit zeros.
pub fn with_extra_entries(matrix: &CsMat<f64>, extra: &[(usize, usize)]) -> CsMat<f64> {
    let n = matrix.rows();
    let mut per_row: Vec<Vec<(usize, f64)>> = (0..n)
        .map(|r| {
            let lane = matrix
                .outer_view(r)
                .map(|v| v.iter().map(|(c, &x)| (c, x)).collect())
                .unwrap_or_default();
            lane
        })
        .collect();
    for &(r, c) in extra {
        per_row[r].push((c, 0.0));
    }
    let mut indptr = Vec::with_capacity(n + 1);
    let mut indices = Vec::new();
    let mut data = Vec::new();
    indptr.push(0);
    for mut lane in per_row {
        lane.sort_by_key(|e| e.0);
        let mut last = None;
        for (c, x) in lane {
            if last == Some(c) {
                if let Some(v) = data.last_mut() {
                    *v += x;
                }
            } else {
                indices.push(c);
                data.push(x);
                last = Some(c);
            }
        }
        indptr.push(indices.len());
    }
    CsMat::new((n, matrix.cols()), indptr, indices, data)
}
