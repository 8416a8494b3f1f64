//! Blocks of vectors packed in rows of [`WIDTH`] values (one 64-byte cache line per row): the
//! layout of the solver's hand-written loops (sparse products, Gram–Schmidt, triangular solves;
//! their two compilations are chosen in `kernel_dispatch.rs`).

use crate::kernel_dispatch::fma_dispatch;

/// Values per packed row.
pub(crate) const WIDTH: usize = 8;

/// The values of up to [`WIDTH`] columns in one row (missing columns 0).
pub(crate) type Row = [f64; WIDTH];

/// The values of a column with unit row stride (the blocks of the solver's loops are column-major
/// with contiguous columns).
pub(crate) fn contiguous(column: faer::ColRef<'_, f64>) -> &[f64] {
    column
        .try_as_col_major()
        .expect("blocks have contiguous columns")
        .as_slice()
}

/// The columns of `block` as mutable slices (see [`contiguous`]).
pub(crate) fn contiguous_columns_mut(block: faer::MatMut<'_, f64>) -> Vec<&mut [f64]> {
    block
        .col_iter_mut()
        .map(|column| {
            column
                .try_as_col_major_mut()
                .expect("blocks have contiguous columns")
                .as_slice_mut()
        })
        .collect()
}

/// Packs the equally long `columns` (at most [`WIDTH`]) into `rows` (one row per entry; missing
/// columns 0), row by row: each packed row is written once, whole, and the columns are read
/// as sequential streams.
pub(crate) fn pack_columns(columns: &[&[f64]], rows: &mut [Row]) {
    let width = columns.len();
    assert!(
        width <= WIDTH && columns.iter().all(|c| c.len() == rows.len()),
        "pack_columns: shapes do not match"
    );
    if let Ok(full) = <&[&[f64]; WIDTH]>::try_from(columns) {
        fma_dispatch!(pack_full_avx2(full, rows) else pack_full_rows(full, rows, 0));
        return;
    }
    for (i, row) in rows.iter_mut().enumerate() {
        *row = std::array::from_fn(|j| if j < width { columns[j][i] } else { 0.0 });
    }
}

/// Rows `first..` of [`pack_columns`] with all [`WIDTH`] columns, one value at a time.
fn pack_full_rows(full: &[&[f64]; WIDTH], rows: &mut [Row], first: usize) {
    for (i, row) in rows.iter_mut().enumerate().skip(first) {
        *row = std::array::from_fn(|j| full[j][i]);
    }
}

/// [`pack_columns`] of [`WIDTH`] columns with AVX2: four rows at a time, as two 4 × 4
/// transposes of four values loaded from each column (eight vector loads, sixteen shuffles and
/// eight vector stores, against 32 scalar loads and stores).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn pack_full_avx2(full: &[&[f64]; WIDTH], rows: &mut [Row]) {
    use std::arch::x86_64::*;
    let n = rows.len();
    assert!(
        full.iter().all(|column| column.len() == n),
        "pack_columns: shapes do not match"
    );
    let quads = n / 4;
    // SAFETY (all intrinsics below): the CPU has AVX2 (this function's features); every column
    // holds `n` values (asserted above), so the loads at `4q..4q + 4` with
    // `4q + 4 ≤ n` are in bounds, and so are the stores into rows `4q..4q + 4`, two 4-wide
    // halves each.
    unsafe {
        let target = rows.as_mut_ptr() as *mut f64;
        for q in 0..quads {
            let i = 4 * q;
            let loaded: [__m256d; WIDTH] =
                std::array::from_fn(|j| _mm256_loadu_pd(full[j].as_ptr().add(i)));
            for half in 0..2 {
                let [a, b, c, d] = [
                    loaded[4 * half],
                    loaded[4 * half + 1],
                    loaded[4 * half + 2],
                    loaded[4 * half + 3],
                ];
                let ab_even = _mm256_unpacklo_pd(a, b);
                let ab_odd = _mm256_unpackhi_pd(a, b);
                let cd_even = _mm256_unpacklo_pd(c, d);
                let cd_odd = _mm256_unpackhi_pd(c, d);
                let out = target.add(WIDTH * i + 4 * half);
                _mm256_storeu_pd(out, _mm256_permute2f128_pd(ab_even, cd_even, 0x20));
                _mm256_storeu_pd(out.add(WIDTH), _mm256_permute2f128_pd(ab_odd, cd_odd, 0x20));
                _mm256_storeu_pd(
                    out.add(2 * WIDTH),
                    _mm256_permute2f128_pd(ab_even, cd_even, 0x31),
                );
                _mm256_storeu_pd(
                    out.add(3 * WIDTH),
                    _mm256_permute2f128_pd(ab_odd, cd_odd, 0x31),
                );
            }
        }
    }
    pack_full_rows(full, rows, 4 * quads);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Packing eight columns gives row `i` = their `i`-th values, for lengths that are and are
    /// not multiples of the four rows the vector path packs at a time; narrower blocks are
    /// padded with zeros.
    #[test]
    fn packed_rows_hold_the_columns_values() {
        for n in [0, 1, 4, 7, 13] {
            let columns: Vec<Vec<f64>> = (0..WIDTH)
                .map(|j| (0..n).map(|i| (100 * j + i) as f64).collect())
                .collect();
            for width in [WIDTH, 3] {
                let slices: Vec<&[f64]> = columns[..width].iter().map(Vec::as_slice).collect();
                let mut rows = vec![[f64::NAN; WIDTH]; n];
                pack_columns(&slices, &mut rows);
                for (i, row) in rows.iter().enumerate() {
                    for j in 0..WIDTH {
                        let expected = if j < width { (100 * j + i) as f64 } else { 0.0 };
                        assert_eq!(row[j], expected, "n = {n}, width = {width}");
                    }
                }
            }
        }
    }
}
