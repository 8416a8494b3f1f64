//! The two inner loops of block Gram–Schmidt on a block of rows, written by hand:
//! `out[k] += Σ_i B[i, k] · w[i]` ([`inner_add`]) and `z[i] −= Σ_k B[i, k] · c[k]`
//! ([`subtract`]), for a basis block `B` (`rows × m`, column-major, `m` a few hundred) and
//! packed blocks of up to [`CHUNK`] columns ([`Row`]s).
//!
//! Why by hand: these products have a tiny output (`m × 8` or `rows × 8`) and a long or wide
//! reduction, the shapes general matrix–matrix kernels handle worst; these loops ran about
//! twice as fast as faer's `matmul` (and OpenBLAS) on `Bᵀ W` and somewhat faster on
//! `Z − B C` (rates in `docs/performance.md`). A row of `W` (or `c`) is one or two vector registers wide and several columns of `B`
//! are consumed at once, so every loaded value of `B` feeds eight fused multiply–adds. The
//! loops are compiled twice, with and without AVX2 + FMA, and the variant is chosen at run time
//! (`kernel_dispatch.rs`).

use crate::kernel_dispatch::{fma_dispatch, multiply_add};
use crate::packed_rows::{Row, WIDTH as CHUNK};
use faer::MatRef;

/// Columns of `B` consumed together by [`inner_add`] (independent accumulators hide the FMA
/// latency).
const UNROLL: usize = 4;
/// Columns of `B` consumed together by [`subtract`]: each load and store of a row of `z` is
/// shared by this many multiply–adds (8 was faster than 4, see `docs/performance.md`).
const UPDATE_UNROLL: usize = 8;

/// `out[k] += Σ_i b[i, k] · w[i]` for `b: rows × m` (column-major, contiguous columns),
/// `w`: `rows` packed rows, `out`: `m` packed rows.
pub(crate) fn inner_add(out: &mut [Row], b: MatRef<'_, f64>, w: &[Row]) {
    assert!(
        out.len() == b.ncols() && w.len() == b.nrows(),
        "inner_add: shapes do not match"
    );
    fma_dispatch!(inner_add_body(out: &mut [Row], b: MatRef<'_, f64>, w: &[Row]));
}

/// `z[i] −= Σ_k b[i, k] · c[k]` for `b: rows × m` (column-major, contiguous columns),
/// `z`: `rows` packed rows, `c`: `m` packed rows.
pub(crate) fn subtract(z: &mut [Row], b: MatRef<'_, f64>, c: &[Row]) {
    assert!(
        c.len() == b.ncols() && z.len() == b.nrows(),
        "subtract: shapes do not match"
    );
    fma_dispatch!(subtract_fma(z, b, c) else subtract_body::<false>(z, b, c));
}

/// `gram[a] += Σ_i z[i][a] · w[i]` for packed rows `z` and `w` (`rows` each): `Zᵀ W` of two
/// packed blocks (`8 × 8`, row `a` in `gram[a]`).
pub(crate) fn gram_add(gram: &mut [Row; CHUNK], z: &[Row], w: &[Row]) {
    assert!(z.len() == w.len(), "gram_add: shapes do not match");
    fma_dispatch!(gram_add_body(gram: &mut [Row; CHUNK], z: &[Row], w: &[Row]));
}

#[inline(always)]
fn gram_add_body<const FUSED: bool>(gram: &mut [Row; CHUNK], z: &[Row], w: &[Row]) {
    let mut sums = *gram;
    for (row, weighted) in z.iter().zip(w) {
        for a in 0..CHUNK {
            for j in 0..CHUNK {
                sums[a][j] = multiply_add::<FUSED>(row[a], weighted[j], sums[a][j]);
            }
        }
    }
    *gram = sums;
}

/// [`subtract`] with AVX2 + FMA intrinsics: four columns of `b` at a time, whose negated
/// coefficients stay in eight registers for the whole pass, and rows in pairs (14 of the 16
/// vector registers). Compiled from [`subtract_body`], the coefficients of eight columns do not
/// fit in registers and are reloaded for every row, which is markedly slower (rates in
/// `docs/performance.md`); this one keeps up with [`inner_add`]. The
/// multiply–adds run in the same order as in [`subtract_body`], so the results are identical.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn subtract_fma(z: &mut [Row], b: MatRef<'_, f64>, c: &[Row]) {
    use std::arch::x86_64::*;
    const COLUMNS: usize = 4;
    let (rows, m) = (z.len(), b.ncols());
    let mut k = 0;
    while k + COLUMNS <= m {
        let columns: [&[f64]; COLUMNS] = std::array::from_fn(|u| &column(b, k + u)[..rows]);
        // SAFETY (all intrinsics below): the CPU has AVX2 + FMA (this function's features);
        // every pointer is in bounds: `i + 1 < rows` for the pairs, `i < rows` for the last row,
        // rows of `z` and `c` are 8 values (two 4-wide vectors at offsets 0 and 4).
        unsafe {
            let negated: [Row; COLUMNS] =
                std::array::from_fn(|u| std::array::from_fn(|j| -c[k + u][j]));
            let low: [__m256d; COLUMNS] =
                std::array::from_fn(|u| _mm256_loadu_pd(negated[u].as_ptr()));
            let high: [__m256d; COLUMNS] =
                std::array::from_fn(|u| _mm256_loadu_pd(negated[u].as_ptr().add(4)));
            let base = z.as_mut_ptr() as *mut f64;
            let mut i = 0;
            while i + 1 < rows {
                let first = base.add(8 * i);
                let second = base.add(8 * (i + 1));
                let mut a0 = _mm256_loadu_pd(first);
                let mut a1 = _mm256_loadu_pd(first.add(4));
                let mut b0 = _mm256_loadu_pd(second);
                let mut b1 = _mm256_loadu_pd(second.add(4));
                for u in 0..COLUMNS {
                    let x = _mm256_broadcast_sd(columns[u].get_unchecked(i));
                    let y = _mm256_broadcast_sd(columns[u].get_unchecked(i + 1));
                    a0 = _mm256_fmadd_pd(x, low[u], a0);
                    a1 = _mm256_fmadd_pd(x, high[u], a1);
                    b0 = _mm256_fmadd_pd(y, low[u], b0);
                    b1 = _mm256_fmadd_pd(y, high[u], b1);
                }
                _mm256_storeu_pd(first, a0);
                _mm256_storeu_pd(first.add(4), a1);
                _mm256_storeu_pd(second, b0);
                _mm256_storeu_pd(second.add(4), b1);
                i += 2;
            }
            if i < rows {
                let row = base.add(8 * i);
                let mut a0 = _mm256_loadu_pd(row);
                let mut a1 = _mm256_loadu_pd(row.add(4));
                for u in 0..COLUMNS {
                    let x = _mm256_broadcast_sd(columns[u].get_unchecked(i));
                    a0 = _mm256_fmadd_pd(x, low[u], a0);
                    a1 = _mm256_fmadd_pd(x, high[u], a1);
                }
                _mm256_storeu_pd(row, a0);
                _mm256_storeu_pd(row.add(4), a1);
            }
        }
        k += COLUMNS;
    }
    subtract_columns_from::<true>(k, z, b, c);
}

/// The contiguous column `k` of `b`.
#[inline(always)]
fn column<'a>(b: MatRef<'a, f64>, k: usize) -> &'a [f64] {
    b.col(k)
        .try_as_col_major()
        .expect("basis blocks have contiguous columns")
        .as_slice()
}

#[inline(always)]
fn inner_add_body<const FUSED: bool>(out: &mut [Row], b: MatRef<'_, f64>, w: &[Row]) {
    let m = b.ncols();
    let mut k = 0;
    while k + UNROLL <= m {
        let columns: [&[f64]; UNROLL] = std::array::from_fn(|u| &column(b, k + u)[..w.len()]);
        let mut sums = [[0.0; CHUNK]; UNROLL];
        for (i, row) in w.iter().enumerate() {
            for u in 0..UNROLL {
                let x = columns[u][i];
                for j in 0..CHUNK {
                    sums[u][j] = multiply_add::<FUSED>(x, row[j], sums[u][j]);
                }
            }
        }
        for u in 0..UNROLL {
            for j in 0..CHUNK {
                out[k + u][j] += sums[u][j];
            }
        }
        k += UNROLL;
    }
    for (k, target) in out.iter_mut().enumerate().skip(k) {
        let values = column(b, k);
        let mut sum = [0.0; CHUNK];
        for (x, row) in values.iter().zip(w) {
            for j in 0..CHUNK {
                sum[j] = multiply_add::<FUSED>(*x, row[j], sum[j]);
            }
        }
        for j in 0..CHUNK {
            target[j] += sum[j];
        }
    }
}

#[inline(always)]
fn subtract_body<const FUSED: bool>(z: &mut [Row], b: MatRef<'_, f64>, c: &[Row]) {
    let m = b.ncols();
    let mut k = 0;
    while k + UPDATE_UNROLL <= m {
        let columns: [&[f64]; UPDATE_UNROLL] =
            std::array::from_fn(|u| &column(b, k + u)[..z.len()]);
        let coefficients: [Row; UPDATE_UNROLL] =
            std::array::from_fn(|u| std::array::from_fn(|j| -c[k + u][j]));
        for (i, row) in z.iter_mut().enumerate() {
            let mut value = *row;
            for u in 0..UPDATE_UNROLL {
                let x = columns[u][i];
                for j in 0..CHUNK {
                    value[j] = multiply_add::<FUSED>(x, coefficients[u][j], value[j]);
                }
            }
            *row = value;
        }
        k += UPDATE_UNROLL;
    }
    subtract_columns_from::<FUSED>(k, z, b, c);
}

/// The columns `first..` of [`subtract`], one at a time (those left over by the unrolled loops).
#[inline(always)]
fn subtract_columns_from<const FUSED: bool>(
    first: usize,
    z: &mut [Row],
    b: MatRef<'_, f64>,
    c: &[Row],
) {
    for (k, coefficient) in c.iter().enumerate().skip(first) {
        let values = column(b, k);
        for (x, row) in values.iter().zip(z.iter_mut()) {
            for j in 0..CHUNK {
                row[j] = multiply_add::<FUSED>(*x, -coefficient[j], row[j]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    #[test]
    fn kernels_match_plain_sums() {
        let (rows, m) = (37, 11);
        let b = Mat::from_fn(rows, m, |i, k| ((i * 5 + k * 3) % 13) as f64 - 6.0);
        let w: Vec<Row> = (0..rows)
            .map(|i| std::array::from_fn(|j| ((i + 2 * j) % 7) as f64 - 3.0))
            .collect();
        let c: Vec<Row> = (0..m)
            .map(|k| std::array::from_fn(|j| ((k * 3 + j) % 5) as f64 - 2.0))
            .collect();
        // Integer data: every variant must give the exact sums. The dispatching functions
        // (FMA where the CPU has it) and the portable loops are both checked.
        type Inner = fn(&mut [Row], MatRef<'_, f64>, &[Row]);
        type Subtract = fn(&mut [Row], MatRef<'_, f64>, &[Row]);
        let variants: [(Inner, Subtract); 2] = [
            (inner_add, subtract),
            (inner_add_body::<false>, subtract_body::<false>),
        ];
        for (inner, update) in variants {
            let mut out: Vec<Row> = (0..m).map(|k| [k as f64; CHUNK]).collect();
            inner(&mut out, b.as_ref(), &w);
            for k in 0..m {
                for j in 0..CHUNK {
                    let expected = k as f64 + (0..rows).map(|i| b[(i, k)] * w[i][j]).sum::<f64>();
                    assert_eq!(out[k][j], expected);
                }
            }
            let mut z = w.clone();
            update(&mut z, b.as_ref(), &c);
            for i in 0..rows {
                for j in 0..CHUNK {
                    let expected = w[i][j] - (0..m).map(|k| b[(i, k)] * c[k][j]).sum::<f64>();
                    assert_eq!(z[i][j], expected);
                }
            }
        }
    }
}
