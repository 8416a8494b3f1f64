//! Conversions between numpy arrays and the Rust types: sparse matrices travel as CSR parts
//! `(indptr, indices, data, (rows, cols))`, dense matrices as 2-D arrays.

use crate::errors::tvf_error;
use faer::Mat;
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use sprs::CsMat;
use tvf_core::discretization::sparse::{csr_arrays, CsrArrays};

/// CSR parts as Python passes them: `indptr`, `indices` (int64), `data` (float64), `shape`.
pub type CsrParts<'py> = (
    PyReadonlyArray1<'py, i64>,
    PyReadonlyArray1<'py, i64>,
    PyReadonlyArray1<'py, f64>,
    (usize, usize),
);

/// The CSR matrix `name` from its parts; malformed parts are a `TvfError` naming the matrix.
pub fn csr_from_parts(name: &str, parts: CsrParts<'_>) -> PyResult<CsMat<f64>> {
    let (indptr, indices, data, shape) = parts;
    let index = |what: &str, values: &[i64]| -> PyResult<Vec<usize>> {
        values
            .iter()
            .map(|&i| {
                usize::try_from(i).map_err(|_| tvf_error(format!("{name}: negative {what} {i}")))
            })
            .collect()
    };
    let indptr = index("row pointer", indptr.as_slice()?)?;
    let indices = index("column index", indices.as_slice()?)?;
    let data = data.as_slice()?.to_vec();
    if let Some(position) = data.iter().position(|x| !x.is_finite()) {
        return Err(tvf_error(format!(
            "{name} contains a non-finite value at stored entry {position}"
        )));
    }
    CsMat::try_new(shape, indptr, indices, data)
        .map_err(|(_, _, _, e)| tvf_error(format!("{name}: not a valid CSR matrix: {e}")))
}

/// The CSR parts of `matrix` as numpy arrays: `(indptr, indices, data, (rows, cols))`.
pub fn csr_to_parts<'py>(py: Python<'py>, matrix: &CsMat<f64>) -> PyResult<Bound<'py, PyTuple>> {
    let CsrArrays {
        indptr,
        indices,
        data,
        shape,
    } = csr_arrays(matrix);
    PyTuple::new(
        py,
        [
            indptr.into_pyarray(py).into_any(),
            indices.into_pyarray(py).into_any(),
            data.into_pyarray(py).into_any(),
            shape.into_pyobject(py)?.into_any(),
        ],
    )
}

/// A faer matrix as a 2-D numpy array (copied).
pub fn mat_to_numpy<'py>(py: Python<'py>, matrix: &faer::MatRef<'_, f64>) -> Bound<'py, PyAny> {
    let (rows, cols) = (matrix.nrows(), matrix.ncols());
    Array2::from_shape_fn((rows, cols), |(i, j)| matrix[(i, j)])
        .into_pyarray(py)
        .into_any()
}

/// Columns of a 2-D numpy array as a faer matrix.
pub fn numpy_to_mat(array: &numpy::PyReadonlyArray2<'_, f64>) -> Mat<f64> {
    let view = array.as_array();
    Mat::from_fn(view.nrows(), view.ncols(), |i, j| view[(i, j)])
}

/// `F` vectors as an `F × 3` array.
pub fn vectors_to_numpy<'py>(py: Python<'py>, vectors: &[[f64; 3]]) -> Bound<'py, PyAny> {
    Array2::from_shape_fn((vectors.len(), 3), |(t, k)| vectors[t][k])
        .into_pyarray(py)
        .into_any()
}

/// Per-face columns (`k` fields of `F` vectors each) as an `F × 3 × k` array.
pub fn face_fields_to_numpy<'py>(
    py: Python<'py>,
    columns: &[Vec<[f64; 3]>],
    faces: usize,
) -> Bound<'py, PyAny> {
    Array3::from_shape_fn((faces, 3, columns.len()), |(t, k, j)| columns[j][t][k])
        .into_pyarray(py)
        .into_any()
}

/// Rows of an `F × 3` array as vectors.
pub fn numpy_to_vectors(array: &numpy::PyReadonlyArray2<'_, f64>) -> PyResult<Vec<[f64; 3]>> {
    let view = array.as_array();
    if view.ncols() != 3 {
        return Err(tvf_error(format!(
            "face vectors: expected an F × 3 array, got {} columns",
            view.ncols()
        )));
    }
    Ok(view
        .rows()
        .into_iter()
        .map(|r| [r[0], r[1], r[2]])
        .collect())
}

/// The rows of `array` (`m × width`), each checked finite; `name` (the argument) and `width_is`
/// (what `width` is) word the errors, e.g. `fields: expected 12 per field (the field dimension)`.
pub fn checked_rows(
    array: &numpy::PyReadonlyArray2<'_, f64>,
    width: usize,
    name: &str,
    width_is: &str,
) -> PyResult<Vec<Vec<f64>>> {
    let view = array.as_array();
    if view.ncols() != width {
        return Err(tvf_error(format!(
            "{name}: expected {width} per field ({width_is}), got {}",
            view.ncols()
        )));
    }
    let rows: Vec<Vec<f64>> = view.rows().into_iter().map(|r| r.to_vec()).collect();
    if let Some(i) = rows.iter().position(|r| r.iter().any(|x| !x.is_finite())) {
        return Err(tvf_error(format!("{name}: row {i} has non-finite values")));
    }
    Ok(rows)
}
