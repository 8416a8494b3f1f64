//! Products of a sparse symmetric matrix with tall dense blocks, in parallel over chunks of
//! columns.
//!
//! Why by hand: faer's `sparse_dense_matmul` (0.24) runs on one thread whatever `Par` it is
//! given and scatters each column of the sparse matrix into the output. For a symmetric `A` in
//! full (both triangles) CSC storage, column `c` of `A` is also row `c`, so `(A X)[c, :]` is a
//! *gather* over column `c`: each output row is written once, and the rows of a chunk of
//! [`CHUNK`] columns of `X` packed side by side ([`Row`]) are read contiguously. Chunks are
//! independent, so they run on rayon's threads; a chunk's buffers are `n` rows of [`CHUNK`]
//! values, so products with thousands of columns never hold more than a few chunks at a time.

use faer::sparse::SparseColMatRef;
use faer::{MatMut, MatRef, Par};
use rayon::prelude::*;

use crate::packed_rows::pack_columns;
/// Columns of one chunk, and one row of a chunk (see [`crate::packed_rows`]).
pub(crate) use crate::packed_rows::{Row, WIDTH as CHUNK};

/// `out[c] = Σ_r A[r, c] · rows[r]`: the rows of `A·X` for symmetric `A` (full storage,
/// `n × n`) and the packed chunk `rows` of `X` (`n` rows).
#[inline(always)]
pub(crate) fn gather_times(a: SparseColMatRef<'_, usize, f64>, rows: &[Row], out: &mut [Row]) {
    let col_ptr = a.symbolic().col_ptr();
    let row_idx = a.symbolic().row_idx();
    let values = a.val();
    for (c, target) in out.iter_mut().enumerate() {
        let mut sum = [0.0; CHUNK];
        for p in col_ptr[c]..col_ptr[c + 1] {
            let (v, x) = (values[p], &rows[row_idx[p]]);
            for (s, x) in sum.iter_mut().zip(x) {
                *s += v * x;
            }
        }
        *target = sum;
    }
}

/// [`gather_times`] and, from the same pass over `A`, `magnitudes[c] = Σ_r |A[r, c]| · |rows[r]|`
/// (the scale of the rounding errors of `A·X`).
#[inline(always)]
pub(crate) fn gather_times_and_magnitudes(
    a: SparseColMatRef<'_, usize, f64>,
    rows: &[Row],
    out: &mut [Row],
    magnitudes: &mut [Row],
) {
    let col_ptr = a.symbolic().col_ptr();
    let row_idx = a.symbolic().row_idx();
    let values = a.val();
    for (c, (target, magnitude)) in out.iter_mut().zip(magnitudes.iter_mut()).enumerate() {
        let (mut sum, mut scale) = ([0.0; CHUNK], [0.0; CHUNK]);
        for p in col_ptr[c]..col_ptr[c + 1] {
            let (v, x) = (values[p], &rows[row_idx[p]]);
            for j in 0..CHUNK {
                sum[j] += v * x[j];
                scale[j] += v.abs() * x[j].abs();
            }
        }
        *target = sum;
        *magnitude = scale;
    }
}

/// Columns `first..first + width` of `x` packed into rows (`width ≤ CHUNK`).
pub(crate) fn pack(x: MatRef<'_, f64>, first: usize, width: usize) -> Vec<Row> {
    let mut rows = vec![[0.0; CHUNK]; x.nrows()];
    pack_into(x, first, width, &mut rows);
    rows
}

/// [`pack`] into `rows` (`n` rows, overwritten).
pub(crate) fn pack_into(x: MatRef<'_, f64>, first: usize, width: usize, rows: &mut [Row]) {
    // Row by row (each packed row written once, whole) when the columns are contiguous.
    let columns: Option<Vec<&[f64]>> = (0..width)
        .map(|j| x.col(first + j).try_as_col_major().map(|c| c.as_slice()))
        .collect();
    match columns {
        Some(columns) => pack_columns(&columns, rows),
        None => {
            for (i, row) in rows.iter_mut().enumerate() {
                *row = std::array::from_fn(|j| if j < width { x[(i, first + j)] } else { 0.0 });
            }
        }
    }
}

/// The buffers a chunk's callback of [`map_column_chunks`] works in, contents unspecified on
/// entry: three of `n` rows, and one the callback sizes as it needs (a mixed pencil's inner
/// solves), kept from chunk to chunk.
pub(crate) struct ChunkWork<'a> {
    pub(crate) rows: [&'a mut [Row]; 3],
    pub(crate) extra: &'a mut Vec<Row>,
}

/// One worker's buffers: the packed chunk (`n` rows) and its [`ChunkWork`].
type ChunkSpace<'a> = (&'a mut [Row], ChunkWork<'a>);

/// The `n`-row buffers of [`map_column_chunks_reusing`], kept by its caller from call to call
/// (and of [`map_column_chunks`] when its scratch is too short).
pub(crate) struct ChunkBuffers {
    /// The current chunk, packed.
    packed: Vec<Row>,
    rows: [Vec<Row>; 3],
    extra: Vec<Row>,
}

impl ChunkBuffers {
    fn new(n: usize) -> Self {
        Self {
            packed: vec![[0.0; CHUNK]; n],
            rows: std::array::from_fn(|_| vec![[0.0; CHUNK]; n]),
            extra: Vec::new(),
        }
    }

    fn space(&mut self) -> ChunkSpace<'_> {
        let [a, b, c] = &mut self.rows;
        (
            &mut self.packed,
            ChunkWork {
                rows: [a, b, c],
                extra: &mut self.extra,
            },
        )
    }
}

/// One [`ChunkSpace`] of `n` rows per entry of `extras`, cut from `scratch`; `None` if it is
/// too short (`4·n·CHUNK` values per space).
fn spaces_in<'a>(
    scratch: &'a mut [f64],
    n: usize,
    extras: &'a mut [Vec<Row>],
) -> Option<Vec<ChunkSpace<'a>>> {
    if scratch.len() < extras.len() * 4 * n * CHUNK {
        return None;
    }
    let (mut rest, _) = scratch.as_chunks_mut::<CHUNK>();
    let mut spaces = Vec::with_capacity(extras.len());
    for extra in extras {
        let (packed, tail) = std::mem::take(&mut rest).split_at_mut(n);
        let (a, tail) = tail.split_at_mut(n);
        let (b, tail) = tail.split_at_mut(n);
        let (c, tail) = tail.split_at_mut(n);
        rest = tail;
        spaces.push((
            packed,
            ChunkWork {
                rows: [a, b, c],
                extra,
            },
        ));
    }
    Some(spaces)
}

/// Calls `work(first, width, rows, buffers)` for every chunk of [`CHUNK`] columns of `x`
/// (`rows`: the chunk packed, `width` its columns; `buffers`: the worker's work space) and
/// returns the results in column order; when `par` allows more than one thread, the chunks are
/// cut into that many runs of neighbouring chunks, which run on rayon's threads. Each run's
/// buffers are cut from `scratch` (stale values, e.g. a slice's idle Krylov basis), or made
/// afresh where it is too short: fresh buffers on every call were, at 253,440 faces, a third of
/// the process's page faults (`docs/performance.md`).
pub(crate) fn map_column_chunks<T: Send>(
    x: MatRef<'_, f64>,
    par: Par,
    scratch: &mut [f64],
    work: impl Fn(usize, usize, &[Row], &mut ChunkWork<'_>) -> T + Sync,
) -> Vec<T> {
    let (n, chunks) = (x.nrows(), x.ncols().div_ceil(CHUNK));
    let runs = par.degree().clamp(1, chunks.max(1));
    let one = |(packed, work_space): &mut ChunkSpace<'_>, chunk: usize| {
        let first = chunk * CHUNK;
        let width = CHUNK.min(x.ncols() - first);
        pack_into(x, first, width, packed);
        work(first, width, packed, work_space)
    };
    let mut extras: Vec<Vec<Row>> = (0..runs).map(|_| Vec::new()).collect();
    let mut owned: Vec<ChunkBuffers> = Vec::new();
    let spaces = match spaces_in(scratch, n, &mut extras) {
        Some(spaces) => spaces,
        None => {
            owned.extend((0..runs).map(|_| ChunkBuffers::new(n)));
            owned.iter_mut().map(ChunkBuffers::space).collect()
        }
    };
    let run_of = |r: usize| r * chunks / runs..(r + 1) * chunks / runs;
    // One run (`Par::Seq`) stays on the calling thread: rayon runs a lone item inline.
    spaces
        .into_par_iter()
        .enumerate()
        .map(|(r, mut space)| run_of(r).map(|c| one(&mut space, c)).collect::<Vec<T>>())
        .collect::<Vec<Vec<T>>>()
        .into_iter()
        .flatten()
        .collect()
}

/// [`map_column_chunks`] on the calling thread alone, with the buffers `buffers` (made for `x`'s
/// rows if they are missing or of another length, and left there for the next call): for
/// callers that go through many narrow blocks of the same `n`, where fresh buffers per call
/// would cost a fresh `4 × n × CHUNK` values each time.
pub(crate) fn map_column_chunks_reusing<T>(
    x: MatRef<'_, f64>,
    buffers: &mut Option<ChunkBuffers>,
    mut work: impl FnMut(usize, usize, &[Row], &mut ChunkWork<'_>) -> T,
) -> Vec<T> {
    let n = x.nrows();
    let buffers = match buffers {
        Some(b) if b.packed.len() == n => b,
        _ => buffers.insert(ChunkBuffers::new(n)),
    };
    let (packed, mut work_space) = buffers.space();
    (0..x.ncols().div_ceil(CHUNK))
        .map(|chunk| {
            let first = chunk * CHUNK;
            let width = CHUNK.min(x.ncols() - first);
            pack_into(x, first, width, packed);
            work(first, width, packed, &mut work_space)
        })
        .collect()
}

/// `out ← A x` for the `n × n` symmetric sparse `a` (full storage) and `x`, `out` of shape
/// `n × s`, in parallel over chunks of columns under `par`.
pub(crate) fn symmetric_times(
    out: MatMut<'_, f64>,
    a: SparseColMatRef<'_, usize, f64>,
    x: MatRef<'_, f64>,
    par: Par,
) {
    assert!(
        a.nrows() == a.ncols()
            && x.nrows() == a.ncols()
            && out.nrows() == a.nrows()
            && out.ncols() == x.ncols(),
        "symmetric_times: shapes do not match"
    );
    times_by_chunks(out, x, par, |rows, product| gather_times(a, rows, product));
}

/// `out ← A x` (`n × s`, `A` square) one chunk of `CHUNK` columns at a time, in parallel over
/// the chunks under `par`: `rows_times(rows, product)` writes `product ← A X` of one packed
/// chunk `X` (`n` rows).
pub(crate) fn times_by_chunks(
    out: MatMut<'_, f64>,
    x: MatRef<'_, f64>,
    par: Par,
    rows_times: impl Fn(&[Row], &mut [Row]) + Sync,
) {
    let n = out.nrows();
    let one = |(chunk, mut target): (usize, MatMut<'_, f64>)| {
        let width = target.ncols();
        let rows = pack(x, chunk * CHUNK, width);
        let mut product = vec![[0.0; CHUNK]; n];
        rows_times(&rows, &mut product);
        for j in 0..width {
            for (i, row) in product.iter().enumerate() {
                target[(i, j)] = row[j];
            }
        }
    };
    if par.degree() > 1 {
        out.par_col_chunks_mut(CHUNK).enumerate().for_each(one);
    } else {
        let mut rest = out;
        let mut chunk = 0;
        while rest.ncols() > 0 {
            let width = CHUNK.min(rest.ncols());
            let (head, tail) = rest.split_at_col_mut(width);
            one((chunk, head));
            rest = tail;
            chunk += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::{SparseColMat, Triplet};
    use faer::Mat;
    use std::num::NonZeroUsize;

    /// A symmetric `n × n` matrix with a few off-diagonals and mixed signs, full storage.
    fn symmetric(n: usize) -> SparseColMat<usize, f64> {
        let mut triplets = Vec::new();
        for i in 0..n {
            triplets.push(Triplet::new(i, i, 3.0 + (i % 5) as f64));
            for offset in [1, 7, 40] {
                if i + offset < n {
                    let v = ((i * 13 + offset) % 11) as f64 / 5.0 - 1.0;
                    triplets.push(Triplet::new(i, i + offset, v));
                    triplets.push(Triplet::new(i + offset, i, v));
                }
            }
        }
        SparseColMat::try_new_from_triplets(n, n, &triplets).expect("valid triplets")
    }

    #[test]
    fn chunked_products_match_the_dense_product() {
        let n = 300;
        let a = symmetric(n);
        let dense = a.to_dense();
        // 19 columns: two full chunks and a partial one.
        let x = Mat::from_fn(n, 19, |i, j| ((i * 7 + j * 3) % 17) as f64 - 8.0);
        let expected = &dense * &x;
        for par in [
            Par::Seq,
            Par::Rayon(NonZeroUsize::new(2).expect("non-zero")),
        ] {
            let mut out = Mat::<f64>::zeros(n, 19);
            symmetric_times(out.as_mut(), a.as_ref(), x.as_ref(), par);
            assert!((&out - &expected).norm_max() <= 1e-12 * expected.norm_max());
        }
        let magnitudes = Mat::from_fn(n, n, |i, j| dense[(i, j)].abs());
        let expected_magnitudes = &magnitudes * Mat::from_fn(n, 19, |i, j| x[(i, j)].abs());
        let sums = map_column_chunks(
            x.as_ref(),
            Par::Seq,
            &mut [],
            |first, width, rows, _work| {
                let (mut out, mut magnitudes) = (vec![[0.0; CHUNK]; n], vec![[0.0; CHUNK]; n]);
                gather_times_and_magnitudes(a.as_ref(), rows, &mut out, &mut magnitudes);
                (first, width, out, magnitudes)
            },
        );
        assert_eq!(sums.len(), 3);
        for (first, width, out, magnitudes) in sums {
            for j in 0..width {
                for i in 0..n {
                    assert!((out[i][j] - expected[(i, first + j)]).abs() <= 1e-12);
                    let magnitude = expected_magnitudes[(i, first + j)];
                    assert!((magnitudes[i][j] - magnitude).abs() <= 1e-12);
                }
            }
            for rows in [&out, &magnitudes] {
                assert!(rows
                    .iter()
                    .all(|row| row[width..].iter().all(|&v| v == 0.0)));
            }
        }
    }
    #[test]
    fn chunk_buffers_are_cut_from_scratch_that_has_room() {
        let n = 300;
        let a = symmetric(n);
        let x = Mat::from_fn(n, 19, |i, j| ((i * 5 + j * 11) % 13) as f64 - 6.0);
        let expected = a.to_dense() * &x;
        for (par, runs) in [
            (Par::Seq, 1),
            (Par::Rayon(NonZeroUsize::new(2).expect("non-zero")), 2),
        ] {
            let room = runs * 4 * n * CHUNK;
            for (len, cut) in [(room, true), (room - 1, false)] {
                // Stale values: nothing may depend on them.
                let mut scratch = vec![f64::NAN; len];
                let range = scratch.as_ptr_range();
                let (start, end) = (range.start as usize, range.end as usize);
                let results =
                    map_column_chunks(x.as_ref(), par, &mut scratch, |first, width, rows, work| {
                        let [product, _, _] = &mut work.rows;
                        gather_times(a.as_ref(), rows, product);
                        let at = product.as_ptr() as usize;
                        let columns: Vec<Vec<f64>> = (0..width)
                            .map(|j| product.iter().map(|row| row[j]).collect())
                            .collect();
                        let padded = rows
                            .iter()
                            .all(|row| row[width..].iter().all(|&v| v == 0.0));
                        (first, columns, padded, (start..end).contains(&at))
                    });
                assert_eq!(results.len(), 3);
                for (first, columns, padded, in_scratch) in results {
                    assert!(padded);
                    assert_eq!(in_scratch, cut, "runs {runs}, scratch of {len} values");
                    for (j, column) in columns.iter().enumerate() {
                        for (i, value) in column.iter().enumerate() {
                            assert!((value - expected[(i, first + j)]).abs() <= 1e-12);
                        }
                    }
                }
            }
        }
    }
}
