//! Small helpers on `sprs::CsMat<f64>` (CSR) and diagonal matrices stored as slices, used by the
//! derived operators. All matrices returned here are in CSR storage with sorted indices.

use sprs::{CsMat, TriMat};
use std::borrow::Cow;

/// `a` in CSR storage: borrowed if it is stored so already, else converted.
pub fn as_csr(a: &CsMat<f64>) -> Cow<'_, CsMat<f64>> {
    if a.is_csr() {
        Cow::Borrowed(a)
    } else {
        Cow::Owned(a.to_csr())
    }
}

/// The diagonal matrix `diag(d)` (n×n, CSR).
pub fn diagonal(d: &[f64]) -> CsMat<f64> {
    let n = d.len();
    CsMat::new((n, n), (0..=n).collect(), (0..n).collect(), d.to_vec())
}

/// Entry-wise reciprocal `1/d_i` of a diagonal; a zero entry (e.g. the mass of a vertex no face
/// uses) maps to zero, so that the node stays decoupled instead of producing infinities.
pub fn reciprocal(d: &[f64]) -> Vec<f64> {
    d.iter()
        .map(|&x| if x == 0.0 { 0.0 } else { 1.0 / x })
        .collect()
}

/// `diag(d) · a`: scales row `i` of `a` by `d[i]`.
pub fn scale_rows(d: &[f64], a: &CsMat<f64>) -> CsMat<f64> {
    let mut out = to_csr(a);
    let indptr = out.indptr().to_proper().into_owned();
    let data = out.data_mut();
    for (row, window) in indptr.windows(2).enumerate() {
        for value in &mut data[window[0]..window[1]] {
            *value *= d[row];
        }
    }
    out
}

/// `a · diag(d)`: scales column `j` of `a` by `d[j]`.
pub fn scale_cols(a: &CsMat<f64>, d: &[f64]) -> CsMat<f64> {
    let mut out = to_csr(a);
    let indices = out.indices().to_vec();
    for (value, &col) in out.data_mut().iter_mut().zip(&indices) {
        *value *= d[col];
    }
    out
}

/// `aᵀ` in CSR storage.
pub fn transpose(a: &CsMat<f64>) -> CsMat<f64> {
    a.transpose_view().to_csr()
}

/// The product `a · b` (CSR).
pub fn product(a: &CsMat<f64>, b: &CsMat<f64>) -> CsMat<f64> {
    let a = as_csr(a);
    let b = as_csr(b);
    &*a * &*b
}

/// The sum `α·a + β·b` (CSR); shapes must agree.
pub fn linear_combination(alpha: f64, a: &CsMat<f64>, beta: f64, b: &CsMat<f64>) -> CsMat<f64> {
    let a = to_csr(a).map(|x| alpha * x);
    let b = to_csr(b).map(|x| beta * x);
    &a + &b
}

/// `a · x` for a dense vector `x` (length `a.cols()`).
pub fn mul_vec(a: &CsMat<f64>, x: &[f64]) -> Vec<f64> {
    debug_assert_eq!(a.cols(), x.len());
    if a.is_csr() {
        a.outer_iterator()
            .map(|row| row.iter().map(|(j, v)| v * x[j]).sum())
            .collect()
    } else {
        let mut y = vec![0.0; a.rows()];
        for (col, column) in a.outer_iterator().enumerate() {
            for (i, v) in column.iter() {
                y[i] += v * x[col];
            }
        }
        y
    }
}

/// `aᵀ · x` for a dense vector `x` (length `a.rows()`), without forming `aᵀ`.
pub fn mul_transpose_vec(a: &CsMat<f64>, x: &[f64]) -> Vec<f64> {
    let t = a.transpose_view();
    let mut y = vec![0.0; a.cols()];
    for (outer, lane) in t.outer_iterator().enumerate() {
        for (inner, v) in lane.iter() {
            if t.is_csr() {
                y[outer] += v * x[inner];
            } else {
                y[inner] += v * x[outer];
            }
        }
    }
    y
}

/// Assembles an `rows × cols` CSR matrix from triplets, summing duplicates.
pub fn from_triplets(
    rows: usize,
    cols: usize,
    row_indices: Vec<usize>,
    col_indices: Vec<usize>,
    values: Vec<f64>,
) -> CsMat<f64> {
    TriMat::from_triplets((rows, cols), row_indices, col_indices, values).to_csr()
}

/// The submatrix of `a` on the kept rows and columns, renumbered: `rows[i]` (`cols[j]`) is the
/// new index of old row `i` (column `j`), `usize::MAX` for one that is dropped; the result is a
/// `shape` CSR matrix (e.g. a stiffness restricted to the free nodes of a boundary condition).
pub fn restricted_to(
    a: &CsMat<f64>,
    rows: &[usize],
    cols: &[usize],
    shape: (usize, usize),
) -> CsMat<f64> {
    let (mut r, mut c, mut v) = (Vec::new(), Vec::new(), Vec::new());
    for (&value, (i, j)) in a.iter() {
        if rows[i] != usize::MAX && cols[j] != usize::MAX {
            r.push(rows[i]);
            c.push(cols[j]);
            v.push(value);
        }
    }
    from_triplets(shape.0, shape.1, r, c, v)
}

/// The same matrix in CSR storage (a copy if it already is).
pub fn to_csr(a: &CsMat<f64>) -> CsMat<f64> {
    if a.is_csr() {
        a.clone()
    } else {
        a.to_csr()
    }
}

/// The compressed-sparse-row arrays of a matrix as numpy and scipy store them: `indptr`
/// (`rows + 1`), `indices` and `data` (`nnz`), and the shape `(rows, cols)`.
#[derive(Debug, Clone, PartialEq)]
pub struct CsrArrays {
    /// Row starts, `rows + 1` entries.
    pub indptr: Vec<i64>,
    /// Column of each stored entry.
    pub indices: Vec<i64>,
    /// Value of each stored entry.
    pub data: Vec<f64>,
    /// `(rows, cols)`.
    pub shape: (usize, usize),
}

/// The CSR arrays of `a` (converted to row-major storage if it is column-major).
pub fn csr_arrays(a: &CsMat<f64>) -> CsrArrays {
    let csr = if a.is_csr() { a.clone() } else { a.to_csr() };
    CsrArrays {
        indptr: csr
            .indptr()
            .raw_storage()
            .iter()
            .map(|&i| i as i64)
            .collect(),
        indices: csr.indices().iter().map(|&i| i as i64).collect(),
        data: csr.data().to_vec(),
        shape: csr.shape(),
    }
}
