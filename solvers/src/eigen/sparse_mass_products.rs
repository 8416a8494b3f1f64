//! The Gram–Schmidt products of `tall_products.rs` in the inner product of a sparse mass `M`
//! (full symmetric storage, rows in the order of the vectors): `Bᵀ M z`, `zᵀ M z` and the
//! M-norms of the columns of `z`, a block of rows at a time.
//!
//! With a diagonal `M` the weighted rows `M z` of a row block need only that block of `z`, so
//! the diagonal sweep fuses the update of `z` and the inner products in one pass. A row of
//! `M z` needs the rows of `z` adjacent in `M`, which may lie in any block, so here the update
//! `z ← z − S C` is one pass (the tall product) and the inner products another: each row block
//! gathers its rows of `M z` into a small packed buffer (no `n × r` copy) and feeds the same
//! packed kernels as the diagonal sweep ([`tall_kernels`]). Rows are split across threads.

use super::symmetric_products::{Row, CHUNK};
use super::tall_kernels;
use super::tall_products::{row_parts, tall_times, Sweep};
use crate::calling_thread::join;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::SparseColMatRef;
use faer::{Accum, Mat, MatMut, MatRef, Par};
use std::ops::Range;

/// Rows per block of the projections (the packed buffers of one block stay in the L2 cache).
const BLOCK_ROWS: usize = 4096;

/// [`super::tall_products::sweep`] for a sparse `m`: `z ← z − Σ_i S_i C_i`, then `Bᵀ M z` for
/// each basis in `project`, the squared M-norms of the columns of `z` and, when `with_gram` and
/// `r ≤ CHUNK`, `zᵀ M z`.
pub(crate) fn sparse_sweep(
    mut z: MatMut<'_, f64>,
    subtract: &[(MatRef<'_, f64>, MatRef<'_, f64>)],
    project: &[MatRef<'_, f64>],
    m: SparseColMatRef<'_, usize, f64>,
    with_gram: bool,
    par: Par,
) -> Sweep {
    for (s, c) in subtract {
        if s.ncols() > 0 {
            tall_times(z.rb_mut(), Accum::Add, *s, *c, -1.0, par);
        }
    }
    let with_gram = with_gram && z.ncols() <= CHUNK;
    let parts = row_parts(z.nrows(), par);
    project_rows(z.rb(), m, project, with_gram, 0..z.nrows(), parts)
}

/// `Bᵀ M Z` (`p × r`) for `B: n × p` (contiguous columns), `Z: n × r`.
pub(crate) fn sparse_mass_inner(
    b: MatRef<'_, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    z: MatRef<'_, f64>,
    par: Par,
) -> Mat<f64> {
    let parts = row_parts(z.nrows(), par);
    let mut sweep = project_rows(z, m, &[b], false, 0..z.nrows(), parts);
    sweep
        .inner
        .pop()
        .unwrap_or_else(|| Mat::zeros(0, z.ncols()))
}

/// Squared M-norms of the columns of `z`.
pub(crate) fn sparse_squared_norms(
    m: SparseColMatRef<'_, usize, f64>,
    z: MatRef<'_, f64>,
) -> Vec<f64> {
    project_rows(z, m, &[], false, 0..z.nrows(), 1).squared_norms
}

/// The inner products of [`sparse_sweep`] over the rows `range` of `z` (`n × r`, contiguous
/// columns), split into `parts` row ranges run concurrently (partial sums added).
fn project_rows(
    z: MatRef<'_, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    project: &[MatRef<'_, f64>],
    with_gram: bool,
    range: Range<usize>,
    parts: usize,
) -> Sweep {
    if parts > 1 {
        let left_parts = parts / 2;
        let split = range.start + range.len() * left_parts / parts;
        let (mut a, b) = join(
            || project_rows(z, m, project, with_gram, range.start..split, left_parts),
            || {
                project_rows(
                    z,
                    m,
                    project,
                    with_gram,
                    split..range.end,
                    parts - left_parts,
                )
            },
        );
        for (x, y) in a.inner.iter_mut().zip(&b.inner) {
            *x += y;
        }
        for (x, y) in a.squared_norms.iter_mut().zip(&b.squared_norms) {
            *x += y;
        }
        if let (Some(x), Some(y)) = (a.gram.as_mut(), b.gram.as_ref()) {
            *x += y;
        }
        return a;
    }
    let r = z.ncols();
    let chunks = r.div_ceil(CHUNK);
    let mut sums: Vec<Vec<Vec<Row>>> = project
        .iter()
        .map(|b| vec![vec![[0.0; CHUNK]; b.ncols()]; chunks])
        .collect();
    let mut squared_norms = vec![0.0; r];
    let mut gram_rows = [[0.0; CHUNK]; CHUNK];
    let block_rows = BLOCK_ROWS.min(range.len().max(1));
    let mut values = vec![[0.0; CHUNK]; block_rows];
    let mut weighted = vec![[0.0; CHUNK]; block_rows];
    let mut start = range.start;
    while start < range.end {
        let rows = block_rows.min(range.end - start);
        for chunk in 0..chunks {
            let first = chunk * CHUNK;
            let width = CHUNK.min(r - first);
            let columns: Vec<&[f64]> = (0..width)
                .map(|j| crate::packed_rows::contiguous(z.col(first + j)))
                .collect();
            weighted_rows(m, &columns, start, &mut weighted[..rows]);
            for (i, row) in values[..rows].iter_mut().enumerate() {
                *row = std::array::from_fn(|j| {
                    if j < width {
                        columns[j][start + i]
                    } else {
                        0.0
                    }
                });
            }
            for (row, w) in values[..rows].iter().zip(&weighted[..rows]) {
                for j in 0..width {
                    squared_norms[first + j] += w[j] * row[j];
                }
            }
            if with_gram {
                tall_kernels::gram_add(&mut gram_rows, &values[..rows], &weighted[..rows]);
            }
            for (b, sum) in project.iter().zip(sums.iter_mut()) {
                if b.ncols() > 0 {
                    tall_kernels::inner_add(
                        &mut sum[chunk],
                        b.subrows(start, rows),
                        &weighted[..rows],
                    );
                }
            }
        }
        start += rows;
    }
    let inner = project
        .iter()
        .zip(&sums)
        .map(|(b, sum)| Mat::from_fn(b.ncols(), r, |k, j| sum[j / CHUNK][k][j % CHUNK]))
        .collect();
    Sweep {
        inner,
        squared_norms,
        gram: with_gram.then(|| Mat::from_fn(r, r, |a, b| gram_rows[a][b])),
    }
}

/// `out[i] = Σ_c M[start + i, c] · (z[c, 0], …, z[c, width − 1])` for the columns of `z`
/// (`width ≤ CHUNK`, missing columns 0): rows `start..start + out.len()` of `M Z`, packed.
fn weighted_rows(
    m: SparseColMatRef<'_, usize, f64>,
    columns: &[&[f64]],
    start: usize,
    out: &mut [Row],
) {
    let col_ptr = m.symbolic().col_ptr();
    let row_idx = m.symbolic().row_idx();
    let values = m.val();
    for (i, target) in out.iter_mut().enumerate() {
        let c = start + i;
        let mut sum = [0.0; CHUNK];
        for p in col_ptr[c]..col_ptr[c + 1] {
            let (v, row) = (values[p], row_idx[p]);
            for (s, column) in sum.iter_mut().zip(columns) {
                *s += v * column[row];
            }
        }
        *target = sum;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::{SparseColMat, Triplet};
    use std::num::NonZeroUsize;

    /// A banded SPD matrix (full storage), `n × n`.
    fn banded(n: usize) -> SparseColMat<usize, f64> {
        let mut triplets = Vec::new();
        for i in 0..n {
            triplets.push(Triplet::new(i, i, 4.0 + (i % 3) as f64));
            for offset in [1, 9, 300] {
                if i + offset < n {
                    let v = ((i * 5 + offset) % 7) as f64 / 10.0 - 0.3;
                    triplets.push(Triplet::new(i, i + offset, v));
                    triplets.push(Triplet::new(i + offset, i, v));
                }
            }
        }
        SparseColMat::try_new_from_triplets(n, n, &triplets).expect("valid")
    }

    /// The sweep equals the dense formulas (update, `Bᵀ M z`, norms, Gram), on one thread and
    /// on two (rows split across blocks and threads: the products reach across both).
    #[test]
    fn sparse_sweep_matches_dense_products() {
        let n = 2 * 4096 + 4099;
        let m = banded(n);
        let dense_m = m.to_dense();
        let b = Mat::from_fn(n, 13, |i, j| ((i * 3 + j * 11) % 29) as f64 / 14.0 - 1.0);
        let s = Mat::from_fn(n, 4, |i, j| ((i * 7 + j) % 13) as f64 / 6.0 - 1.0);
        let c = Mat::from_fn(4, 6, |i, j| (i + 2 * j) as f64 / 5.0);
        let z0 = Mat::from_fn(n, 6, |i, j| ((i * 17 + j * 5) % 31) as f64 / 15.0 - 1.0);
        let updated = &z0 - &s * &c;
        let mz = &dense_m * &updated;
        let expected_inner = b.transpose() * &mz;
        let expected_gram = updated.transpose() * &mz;
        for par in [
            Par::Seq,
            Par::Rayon(NonZeroUsize::new(2).expect("non-zero")),
        ] {
            let mut z = z0.clone();
            let sweep = sparse_sweep(
                z.as_mut(),
                &[(s.as_ref(), c.as_ref())],
                &[b.as_ref()],
                m.as_ref(),
                true,
                par,
            );
            assert!((&z - &updated).norm_max() <= 1e-12 * updated.norm_max());
            let scale = expected_inner.norm_max();
            assert!((&sweep.inner[0] - &expected_inner).norm_max() <= 1e-11 * scale);
            let gram = sweep.gram.expect("r ≤ 8");
            assert!((&gram - &expected_gram).norm_max() <= 1e-11 * expected_gram.norm_max());
            for j in 0..6 {
                let e = expected_gram[(j, j)];
                assert!((sweep.squared_norms[j] - e).abs() <= 1e-11 * e.abs());
            }
            let inner = sparse_mass_inner(b.as_ref(), m.as_ref(), updated.as_ref(), par);
            assert!((&inner - &expected_inner).norm_max() <= 1e-11 * scale);
        }
    }
}
