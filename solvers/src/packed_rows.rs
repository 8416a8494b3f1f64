//! Blocks of vectors packed in rows of [`WIDTH`] values (one 64-byte cache line per row): the
//! layout of the solver's hand-written loops (sparse products, Gram–Schmidt, triangular solves),
//! and the run-time choice of their AVX2 + FMA variants (the workspace is built for the
//! baseline x86-64 target, so each loop is compiled twice: portable and with AVX2 + FMA).

/// Values per packed row.
pub(crate) const WIDTH: usize = 8;

/// The values of up to [`WIDTH`] columns in one row (missing columns 0).
pub(crate) type Row = [f64; WIDTH];

/// Whether the loops compiled with AVX2 + FMA may run on this CPU.
pub(crate) fn has_avx2_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// `a + x · y`, fused when `FUSED` (only in functions compiled with FMA: elsewhere `mul_add`
/// would call a slow library routine).
#[inline(always)]
pub(crate) fn multiply_add<const FUSED: bool>(x: f64, y: f64, a: f64) -> f64 {
    if FUSED {
        x.mul_add(y, a)
    } else {
        a + x * y
    }
}

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
        for (i, row) in rows.iter_mut().enumerate() {
            *row = std::array::from_fn(|j| full[j][i]);
        }
        return;
    }
    for (i, row) in rows.iter_mut().enumerate() {
        *row = std::array::from_fn(|j| if j < width { columns[j][i] } else { 0.0 });
    }
}
