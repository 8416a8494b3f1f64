//! Dense products with tall matrices (`n` rows, a few hundred columns at most), split by rows
//! across threads.
//!
//! The Krylov bases of the eigensolver are `n × m` with `n` up to 10⁶ and `m` a few hundred,
//! and they are multiplied with blocks of `r ≈ 8` columns: `Bᵀ M Z` (`m × r`) and `Z − B C`.
//! Such products are bound by streaming `B` from memory. faer's parallel `matmul` splits the
//! small output into tiles and synchronises per tile, which on two cores was slower than one
//! thread. Here each thread instead takes a contiguous range of rows of `B` (and of `Z`) and runs
//! a sequential product on it, so every thread streams its own part of `B` exactly once; the
//! `m × r` partial inner products are summed at the end (one small reduction).

use super::mass::Mass;
use super::sparse_mass_products::{sparse_mass_inner, sparse_sweep};
use super::symmetric_products::{Row, CHUNK};
use super::tall_kernels;
use crate::calling_thread::join;
use crate::packed_rows::{contiguous, contiguous_columns_mut, pack_columns};
use faer::linalg::matmul::matmul;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par};

/// Fewest rows a thread gets; smaller products run on one thread.
const MIN_ROWS_PER_THREAD: usize = 4096;

/// Number of row ranges for `n` rows under `par`.
pub(crate) fn row_parts(n: usize, par: Par) -> usize {
    par.degree().min(n / MIN_ROWS_PER_THREAD).max(1)
}

/// `out ← out + alpha · lhs · rhs` (`accum = Add`) or `out ← alpha · lhs · rhs` (`Replace`) for
/// `lhs: n × m`, `rhs: m × c`, `out: n × c`, rows split across `par.degree()` threads.
pub(crate) fn tall_times(
    out: MatMut<'_, f64>,
    accum: Accum,
    lhs: MatRef<'_, f64>,
    rhs: MatRef<'_, f64>,
    alpha: f64,
    par: Par,
) {
    split_times(out, accum, lhs, rhs, alpha, row_parts(lhs.nrows(), par));
}

fn split_times(
    mut out: MatMut<'_, f64>,
    accum: Accum,
    lhs: MatRef<'_, f64>,
    rhs: MatRef<'_, f64>,
    alpha: f64,
    parts: usize,
) {
    if parts <= 1 {
        matmul(out.rb_mut(), accum, lhs, rhs, alpha, Par::Seq);
        return;
    }
    let left_parts = parts / 2;
    let split = lhs.nrows() * left_parts / parts;
    let (out_top, out_bottom) = out.split_at_row_mut(split);
    let (lhs_top, lhs_bottom) = lhs.split_at_row(split);
    join(
        || split_times(out_top, accum, lhs_top, rhs, alpha, left_parts),
        || {
            split_times(
                out_bottom,
                accum,
                lhs_bottom,
                rhs,
                alpha,
                parts - left_parts,
            )
        },
    );
}

/// Rows per block of [`tall_times_in_place`].
const IN_PLACE_ROWS: usize = 512;

/// `B[:, 0..p] ← B · Y` in place for `B: n × m` and `Y: m × p` (`p ≤ m`; the other columns of
/// `B` are left with stale values): each block of rows is multiplied into a small buffer and
/// written back, so no second `n × p` matrix is allocated (the thick restarts and Rayleigh–Ritz
/// rotations of bases with millions of rows). Row blocks run on `par.degree()` threads.
pub(crate) fn tall_times_in_place(b: MatMut<'_, f64>, y: MatRef<'_, f64>, par: Par) {
    assert!(
        y.nrows() == b.ncols() && y.ncols() <= b.ncols(),
        "tall_times_in_place: shapes do not match"
    );
    let parts = row_parts(b.nrows(), par);
    in_place_parts(b, y, parts);
}

fn in_place_parts(mut b: MatMut<'_, f64>, y: MatRef<'_, f64>, parts: usize) {
    if parts <= 1 {
        let p = y.ncols();
        let mut buffer = Mat::<f64>::zeros(IN_PLACE_ROWS, p);
        let mut start = 0;
        while start < b.nrows() {
            let rows = IN_PLACE_ROWS.min(b.nrows() - start);
            let block = b.rb_mut().subrows_mut(start, rows);
            let mut product = buffer.as_mut().subrows_mut(0, rows);
            matmul(
                product.rb_mut(),
                Accum::Replace,
                block.as_ref(),
                y,
                1.0,
                Par::Seq,
            );
            block.subcols_mut(0, p).copy_from(product.as_ref());
            start += rows;
        }
        return;
    }
    let left_parts = parts / 2;
    let split = b.nrows() * left_parts / parts;
    let (top, bottom) = b.split_at_row_mut(split);
    join(
        || in_place_parts(top, y, left_parts),
        || in_place_parts(bottom, y, parts - left_parts),
    );
}

/// Rows per block of [`sweep`]: long enough for the hardware prefetchers to stream each column
/// segment (128 KB), short enough that the block of the columns updated in the same sweep (in
/// the Gram–Schmidt sweeps, the last two Krylov blocks: 16 columns, 2 MB) is still in the
/// last-level cache when the inner products read it again. Shorter blocks and whole columns
/// made the inner-product sweep slower, longer ones did not help, and the update sweep does not
/// care (timings in `docs/performance.md`).
const SWEEP_ROWS: usize = 16384;

/// Values of the weighted row block of [`mass_inner`] (256 KiB).
const WEIGHTED_VALUES: usize = 32768;

/// Columns `CHUNK·chunk .. CHUNK·(chunk + 1)` of `c` (`p × r`), packed as `p` rows (missing
/// columns 0).
fn pack_chunk(c: MatRef<'_, f64>, chunk: usize) -> Vec<Row> {
    let first = chunk * CHUNK;
    let width = CHUNK.min(c.ncols() - first);
    (0..c.nrows())
        .map(|k| std::array::from_fn(|j| if j < width { c[(k, first + j)] } else { 0.0 }))
        .collect()
}

/// What one [`sweep`] computed.
pub(crate) struct Sweep {
    /// `Bᵀ M z` (`p × r`) for each basis `B` in `project`, with `z` after the update.
    pub inner: Vec<Mat<f64>>,
    /// Squared M-norms of the columns of `z` after the update.
    pub squared_norms: Vec<f64>,
    /// `zᵀ M z` (`r × r`) after the update, when asked for and `r ≤ CHUNK` (the Gram matrix
    /// CholeskyQR starts from, at 8 multiply–adds per value of `z` while its rows are in cache).
    pub gram: Option<Mat<f64>>,
}

/// One pass over the rows of `z` (`n × r`): `z ← z − Σ_i S_i C_i` for the pairs
/// `(S_i: n × p_i, C_i: p_i × r)` in `subtract`, then `Bᵀ M z` for each basis `B` (`n × q`) in
/// `project` and the squared M-norms of the columns of `z`, all from the updated rows while
/// they are in cache. Block Gram–Schmidt reads each basis twice per pass (inner products, then
/// the update), and the bases (`n × m`, `m` a few hundred) are far larger than the caches; with
/// the update of one pass and the inner products of the next fused in one sweep, a basis is read
/// once per pass. Rows are split across `par.degree()` threads.
///
/// A sparse `M` takes [`sparse_sweep`] (two passes: see `sparse_mass_products.rs`).
pub(crate) fn sweep(
    z: MatMut<'_, f64>,
    subtract: &[(MatRef<'_, f64>, MatRef<'_, f64>)],
    project: &[MatRef<'_, f64>],
    mass: Mass<'_>,
    with_gram: bool,
    par: Par,
) -> Sweep {
    let mass = match mass {
        Mass::Diagonal(mass) => mass,
        Mass::Sparse(m) => return sparse_sweep(z, subtract, project, m, with_gram, par),
    };
    let parts = row_parts(z.nrows(), par);
    let with_gram = with_gram && z.ncols() <= CHUNK;
    split_sweep(z, 0, subtract, project, mass, with_gram, parts)
}

/// [`sweep`] of the rows of `z` (row `first_row` onwards of the bases and the mass) split in
/// `parts` ranges, each on its own thread, and their sums added up.
fn split_sweep(
    z: MatMut<'_, f64>,
    first_row: usize,
    subtract: &[(MatRef<'_, f64>, MatRef<'_, f64>)],
    project: &[MatRef<'_, f64>],
    mass: &[f64],
    with_gram: bool,
    parts: usize,
) -> Sweep {
    if parts <= 1 {
        return RowSweep::new(subtract, project, mass, with_gram, z.rb()).run(z, first_row);
    }
    let left_parts = parts / 2;
    let split = z.nrows() * left_parts / parts;
    let (top, bottom) = z.split_at_row_mut(split);
    let (mut a, b) = join(
        || {
            split_sweep(
                top, first_row, subtract, project, mass, with_gram, left_parts,
            )
        },
        || {
            split_sweep(
                bottom,
                first_row + split,
                subtract,
                project,
                mass,
                with_gram,
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
    a
}

/// One thread's [`sweep`]: blocks of [`SWEEP_ROWS`] rows of `z`, each a chunk of [`CHUNK`]
/// columns at a time packed in rows, updated, weighted by `M` and multiplied into the sums.
struct RowSweep<'s, 'a> {
    subtract: &'s [(MatRef<'a, f64>, MatRef<'a, f64>)],
    /// The coefficients `C_i` of `subtract`, per chunk of columns of `z`, packed in rows.
    packed_coefficients: Vec<Vec<Vec<Row>>>,
    project: &'s [MatRef<'a, f64>],
    mass: &'s [f64],
    with_gram: bool,
    /// `Bᵀ M z` for each basis `B` of `project`, per chunk of columns of `z` (`q` packed rows).
    sums: Vec<Vec<Vec<Row>>>,
    squared_norms: Vec<f64>,
    gram_rows: [Row; CHUNK],
}

impl<'s, 'a> RowSweep<'s, 'a> {
    /// Zero sums and buffers for the sweep of `z`.
    fn new(
        subtract: &'s [(MatRef<'a, f64>, MatRef<'a, f64>)],
        project: &'s [MatRef<'a, f64>],
        mass: &'s [f64],
        with_gram: bool,
        z: MatRef<'_, f64>,
    ) -> Self {
        let chunks = z.ncols().div_ceil(CHUNK);
        let packed_coefficients = subtract
            .iter()
            .map(|(_, c)| (0..chunks).map(|chunk| pack_chunk(*c, chunk)).collect())
            .collect();
        let sums = project
            .iter()
            .map(|b| vec![vec![[0.0; CHUNK]; b.ncols()]; chunks])
            .collect();
        Self {
            subtract,
            packed_coefficients,
            project,
            mass,
            with_gram,
            sums,
            squared_norms: vec![0.0; z.ncols()],
            gram_rows: [[0.0; CHUNK]; CHUNK],
        }
    }

    /// Sweeps the rows of `z`, which are rows `first_row..` of the bases and the mass.
    fn run(mut self, mut z: MatMut<'_, f64>, first_row: usize) -> Sweep {
        let r = z.ncols();
        // The chunk of the current block of rows, packed, and the same rows times `M`.
        let mut block = vec![[0.0; CHUNK]; SWEEP_ROWS.min(z.nrows())];
        let mut weighted = block.clone();
        let mut start = 0;
        while start < z.nrows() {
            let rows = SWEEP_ROWS.min(z.nrows() - start);
            for chunk in 0..r.div_ceil(CHUNK) {
                let first = chunk * CHUNK;
                let width = CHUNK.min(r - first);
                let part = z
                    .rb_mut()
                    .subcols_mut(first, width)
                    .subrows_mut(start, rows);
                let (values, weights) = (&mut block[..rows], &mut weighted[..rows]);
                self.chunk(part, first_row + start, chunk, values, weights);
            }
            start += rows;
        }
        let mut inner: Vec<Mat<f64>> = self
            .project
            .iter()
            .map(|b| Mat::zeros(b.ncols(), r))
            .collect();
        for (total, sum) in inner.iter_mut().zip(&self.sums) {
            for (chunk, rows) in sum.iter().enumerate() {
                let first = chunk * CHUNK;
                for j in 0..CHUNK.min(r - first) {
                    for (k, row) in rows.iter().enumerate() {
                        total[(k, first + j)] = row[j];
                    }
                }
            }
        }
        let gram_rows = self.gram_rows;
        Sweep {
            inner,
            squared_norms: self.squared_norms,
            gram: self
                .with_gram
                .then(|| Mat::from_fn(r, r, |a, b| gram_rows[a][b])),
        }
    }

    /// One chunk `part` of a block of rows of `z` (its rows are rows `global..` of the bases
    /// and the mass; its columns the chunk `chunk`): packed into `values`, updated by
    /// `subtract`, weighted by `M` into `weighted`, its M-norms and products with the bases of
    /// `project` (and its Gram matrix) added to the sums, and written back.
    fn chunk(
        &mut self,
        part: MatMut<'_, f64>,
        global: usize,
        chunk: usize,
        values: &mut [Row],
        weighted: &mut [Row],
    ) {
        let (rows, width) = (part.nrows(), part.ncols());
        let first = chunk * CHUNK;
        let columns: Vec<&[f64]> = (0..width).map(|j| contiguous(part.rb().col(j))).collect();
        pack_columns(&columns, values);
        for ((s, _), coefficients) in self.subtract.iter().zip(&self.packed_coefficients) {
            if s.ncols() > 0 {
                tall_kernels::subtract(values, s.subrows(global, rows), &coefficients[chunk]);
            }
        }
        let mut chunk_norms = [0.0; CHUNK];
        for (i, (row, w)) in values.iter().zip(weighted.iter_mut()).enumerate() {
            let m = self.mass[global + i];
            for j in 0..CHUNK {
                w[j] = m * row[j];
                chunk_norms[j] += w[j] * row[j];
            }
        }
        let weighted = &*weighted;
        if self.with_gram {
            tall_kernels::gram_add(&mut self.gram_rows, values, weighted);
        }
        for j in 0..width {
            self.squared_norms[first + j] += chunk_norms[j];
        }
        for (b, sum) in self.project.iter().zip(self.sums.iter_mut()) {
            if b.ncols() > 0 {
                tall_kernels::inner_add(&mut sum[chunk], b.subrows(global, rows), weighted);
            }
        }
        let mut columns = contiguous_columns_mut(part);
        for (i, row) in values.iter().enumerate() {
            for (j, column) in columns.iter_mut().enumerate() {
                column[i] = row[j];
            }
        }
    }
}

/// Columns `first..first + count` of `matrix`, moved to the front in place and the rest cut
/// off (eigenvectors of a million-unknown problem are gigabytes: no second copy).
pub fn keep_columns(mut matrix: Mat<f64>, first: usize, count: usize) -> Mat<f64> {
    assert!(
        first + count <= matrix.ncols(),
        "keep_columns: columns {first}..{} of {}",
        first + count,
        matrix.ncols()
    );
    if first > 0 {
        for j in 0..count {
            // Column `first + j` is column `first − 1` of the right part.
            let (target, source) = matrix.as_mut().split_at_col_mut(j + 1);
            target.col_mut(j).copy_from(source.col(first - 1));
        }
    }
    let rows = matrix.nrows();
    matrix.truncate(rows, count);
    matrix
}

/// `Bᵀ M Z` (`p × r`) for `B: n × p`, `Z: n × r` and the mass `M`, rows split across
/// `par.degree()` threads (partial products summed). A sparse `M` needs contiguous columns in
/// `B` and `Z` (see [`sparse_mass_inner`]).
pub(crate) fn mass_inner(
    b: MatRef<'_, f64>,
    mass: Mass<'_>,
    z: MatRef<'_, f64>,
    par: Par,
) -> Mat<f64> {
    match mass {
        Mass::Diagonal(mass) => split_inner(b, Some(mass), z, row_parts(b.nrows(), par)),
        Mass::Sparse(m) => sparse_mass_inner(b, m, z, par),
    }
}

/// Removes from `Z` (`n × r`, in place) its `M`-projection onto the columns of `B` (`n × p`,
/// `M`-orthonormal): `Z ← Z − B (Bᵀ M Z)`, the step that keeps eigenvectors of neighbouring
/// spectrum-slicing intervals `M`-orthogonal. Costs the two `n × p × r` products.
pub(crate) fn remove_mass_projection(
    mut z: MatMut<'_, f64>,
    b: MatRef<'_, f64>,
    mass: Mass<'_>,
    par: Par,
) {
    let overlap = mass_inner(b, mass, z.rb(), par);
    tall_times(z.rb_mut(), Accum::Add, b, overlap.as_ref(), -1.0, par);
}

/// `Bᵀ Z` (`p × r`) for `B: n × p`, `Z: n × r`, rows split as in [`mass_inner`].
pub(crate) fn tall_inner(b: MatRef<'_, f64>, z: MatRef<'_, f64>, par: Par) -> Mat<f64> {
    split_inner(b, None, z, row_parts(b.nrows(), par))
}

/// `Bᵀ W Z` with `W = diag(weight)` (identity for `None`) on `parts` row ranges.
fn split_inner(
    b: MatRef<'_, f64>,
    weight: Option<&[f64]>,
    z: MatRef<'_, f64>,
    parts: usize,
) -> Mat<f64> {
    if parts <= 1 {
        let mut c = Mat::zeros(b.ncols(), z.ncols());
        let Some(weight) = weight else {
            matmul(c.as_mut(), Accum::Replace, b.transpose(), z, 1.0, Par::Seq);
            return c;
        };
        // W Z a block of rows at a time, in one small buffer (a weighted copy of all of Z would
        // be a fresh n × r allocation on every call, whose first touch costs more than the
        // product on small blocks).
        let rows_per_block = (WEIGHTED_VALUES / z.ncols().max(1)).clamp(64, 4096);
        let mut weighted = Mat::<f64>::zeros(rows_per_block.min(z.nrows()), z.ncols());
        let mut start = 0;
        while start < z.nrows() {
            let rows = rows_per_block.min(z.nrows() - start);
            let mut block = weighted.as_mut().subrows_mut(0, rows);
            block.copy_from(z.subrows(start, rows));
            for j in 0..block.ncols() {
                let column = block.rb_mut().col_mut(j);
                for (x, w) in column.iter_mut().zip(&weight[start..start + rows]) {
                    *x *= w;
                }
            }
            let accum = if start == 0 {
                Accum::Replace
            } else {
                Accum::Add
            };
            matmul(
                c.as_mut(),
                accum,
                b.subrows(start, rows).transpose(),
                block.rb(),
                1.0,
                Par::Seq,
            );
            start += rows;
        }
        return c;
    }
    let left_parts = parts / 2;
    let split = b.nrows() * left_parts / parts;
    let (b_top, b_bottom) = b.split_at_row(split);
    let (z_top, z_bottom) = z.split_at_row(split);
    let (w_top, w_bottom) = match weight {
        Some(w) => {
            let (top, bottom) = w.split_at(split);
            (Some(top), Some(bottom))
        }
        None => (None, None),
    };
    let (mut top, bottom) = join(
        || split_inner(b_top, w_top, z_top, left_parts),
        || split_inner(b_bottom, w_bottom, z_bottom, parts - left_parts),
    );
    top += &bottom;
    top
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::num::NonZeroUsize;

    fn sample(n: usize, c: usize, seed: usize) -> Mat<f64> {
        Mat::from_fn(n, c, |i, j| {
            ((i * 31 + j * 17 + seed) % 101) as f64 / 50.0 - 1.0
        })
    }

    #[test]
    fn split_products_match_sequential_ones() {
        let n = 3 * MIN_ROWS_PER_THREAD + 5;
        let (b, z, c) = (sample(n, 13, 1), sample(n, 4, 2), sample(13, 4, 3));
        let mass: Vec<f64> = (0..n).map(|i| 0.5 + (i % 7) as f64).collect();
        let par = Par::Rayon(NonZeroUsize::new(3).expect("non-zero"));

        let sequential = mass_inner(b.as_ref(), Mass::Diagonal(&mass), z.as_ref(), Par::Seq);
        let split = mass_inner(b.as_ref(), Mass::Diagonal(&mass), z.as_ref(), par);
        let scale = sequential.norm_max();
        assert!((&sequential - &split).norm_max() <= 1e-13 * scale);
        let plain = tall_inner(b.as_ref(), z.as_ref(), par);
        let mut expected_plain = Mat::<f64>::zeros(13, 4);
        for j in 0..4 {
            for i in 0..13 {
                expected_plain[(i, j)] = (0..n).map(|r| b[(r, i)] * z[(r, j)]).sum::<f64>();
            }
        }
        assert!((&expected_plain - &plain).norm_max() <= 1e-12 * expected_plain.norm_max());

        let mut out_sequential = z.clone();
        let mut out_split = z.clone();
        tall_times(
            out_sequential.as_mut(),
            Accum::Add,
            b.as_ref(),
            c.as_ref(),
            -1.0,
            Par::Seq,
        );
        tall_times(
            out_split.as_mut(),
            Accum::Add,
            b.as_ref(),
            c.as_ref(),
            -1.0,
            par,
        );
        assert_eq!(out_sequential, out_split, "row-split updates are exact");
        let mut expected = z.clone();
        for j in 0..4 {
            for i in 0..n {
                expected[(i, j)] -= (0..13).map(|p| b[(i, p)] * c[(p, j)]).sum::<f64>();
            }
        }
        assert!((&expected - &out_split).norm_max() <= 1e-12 * expected.norm_max());

        // In place, with a partial last row block: the first 4 columns become B·Y.
        let y = sample(13, 4, 5);
        let mut in_place = b.clone();
        tall_times_in_place(in_place.as_mut(), y.as_ref(), par);
        let product = &b * &y;
        let first = in_place.as_ref().subcols(0, 4);
        assert!((first - &product).norm_max() <= 1e-12 * product.norm_max());

        // A sweep over 11 columns (a full chunk and a partial one), on three row ranges with
        // partial row blocks: z − B C, then Lᵀ M z, Bᵀ M z and the squared M-norms of z.
        let n = 2 * SWEEP_ROWS + 3 * MIN_ROWS_PER_THREAD + 17;
        let (basis, other, z) = (sample(n, 13, 6), sample(n, 5, 7), sample(n, 11, 8));
        let coefficients = sample(13, 11, 9);
        let mass: Vec<f64> = (0..n).map(|i| 0.5 + (i % 7) as f64).collect();
        let mut updated = z.clone();
        let result = sweep(
            updated.as_mut(),
            &[(basis.as_ref(), coefficients.as_ref())],
            &[other.as_ref(), basis.as_ref()],
            Mass::Diagonal(&mass),
            true,
            par,
        );
        assert!(
            result.gram.is_none(),
            "no Gram matrix of more than eight columns"
        );
        let expected = &z - &basis * &coefficients;
        assert!((&updated - &expected).norm_max() <= 1e-12 * expected.norm_max());
        for (b, inner) in [&other, &basis].into_iter().zip(&result.inner) {
            let exact = mass_inner(
                b.as_ref(),
                Mass::Diagonal(&mass),
                expected.as_ref(),
                Par::Seq,
            );
            assert!((inner - &exact).norm_max() <= 1e-12 * exact.norm_max());
        }
        for (j, norm) in result.squared_norms.iter().enumerate() {
            let exact = (0..n)
                .map(|i| mass[i] * expected[(i, j)].powi(2))
                .sum::<f64>();
            assert!((norm - exact).abs() <= 1e-12 * exact);
        }

        // The Gram matrix of an eight-column update, summed over the row ranges.
        let mut updated = z.as_ref().subcols(0, 8).to_owned();
        let result = sweep(
            updated.as_mut(),
            &[(basis.as_ref(), coefficients.as_ref().subcols(0, 8))],
            &[],
            Mass::Diagonal(&mass),
            true,
            par,
        );
        let gram = result.gram.expect("the Gram matrix of eight columns");
        let exact = mass_inner(
            updated.as_ref(),
            Mass::Diagonal(&mass),
            updated.as_ref(),
            Par::Seq,
        );
        assert!((&gram - &exact).norm_max() <= 1e-12 * exact.norm_max());

        let kept = keep_columns(b.clone(), 3, 6);
        assert_eq!(kept, b.as_ref().subcols(3, 6).to_owned());
    }
}
