//! Two summaries of a sparse matrix that the pencils and their residual checks read off its
//! columns: the diagonal ([`diagonal_of`]) and the maximum absolute column sum `‖A‖₁`
//! ([`max_column_sum`]).

use faer::sparse::SparseColMatRef;

/// The diagonal of the `n × n` sparse `a` (0 where no entry is stored).
pub(crate) fn diagonal_of(a: SparseColMatRef<'_, usize, f64>) -> Vec<f64> {
    let col_ptr = a.symbolic().col_ptr();
    let row_idx = a.symbolic().row_idx();
    (0..a.ncols())
        .map(|c| {
            (col_ptr[c]..col_ptr[c + 1])
                .find(|&p| row_idx[p] == c)
                .map_or(0.0, |p| a.val()[p])
        })
        .collect()
}

/// The maximum absolute column sum `‖A‖₁` (an upper bound of `‖A‖₂`), at least the smallest
/// positive number.
pub(crate) fn max_column_sum(a: SparseColMatRef<'_, usize, f64>) -> f64 {
    let col_ptr = a.symbolic().col_ptr();
    (0..a.ncols())
        .map(|c| {
            a.val()[col_ptr[c]..col_ptr[c + 1]]
                .iter()
                .map(|v| v.abs())
                .sum::<f64>()
        })
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE)
}
