//! `tvf._native.Operator`: a derived operator of a complex that is not a sparse matrix (it
//! contains the inverse of a sparse mass, or a mass stored as its inverse), applied through the
//! Rust [`LinearOperator`] — sparse products and the mass's Cholesky factorization — and never
//! formed. The Python half wraps it as a `scipy.sparse.linalg.LinearOperator`.

use crate::arrays::mat_to_numpy;
use crate::errors::tvf_error;
use faer::Mat;
use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use tvf_core::discretization::LinearOperator;

/// An `m × n` operator `A` of a complex, named as in `tvf.operators` (`S`, `L`, `M2`, …).
#[pyclass(frozen, module = "tvf._native")]
pub struct Operator {
    name: String,
    operator: LinearOperator,
}

impl Operator {
    /// Wraps `operator` under `name`.
    pub fn new(name: &str, operator: LinearOperator) -> Self {
        Self {
            name: name.to_string(),
            operator,
        }
    }

    /// `x` checked: `expected` entries, all finite.
    fn input(
        &self,
        x: &PyReadonlyArray1<'_, f64>,
        expected: usize,
        what: &str,
    ) -> PyResult<Vec<f64>> {
        let values = x.as_array().to_vec();
        if values.len() != expected {
            return Err(tvf_error(format!(
                "{}: {what} needs a vector of {expected} entries, got {}",
                self.name,
                values.len()
            )));
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(tvf_error(format!(
                "{}: {what}: the vector has a non-finite value at entry {i}",
                self.name
            )));
        }
        Ok(values)
    }

    /// `y` checked for non-finite values (a mass factorization that lost its accuracy).
    fn output(&self, y: &[f64], what: &str) -> PyResult<()> {
        match y.iter().position(|v| !v.is_finite()) {
            Some(i) => Err(tvf_error(format!(
                "{}: {what} gave a non-finite value at entry {i}",
                self.name
            ))),
            None => Ok(()),
        }
    }

    /// The columns of `x` (`expected × r`), checked.
    fn block(
        &self,
        x: &PyReadonlyArray2<'_, f64>,
        expected: usize,
        what: &str,
    ) -> PyResult<Mat<f64>> {
        let view = x.as_array();
        if view.nrows() != expected {
            return Err(tvf_error(format!(
                "{}: {what} needs {expected} rows, got {}",
                self.name,
                view.nrows()
            )));
        }
        if view.iter().any(|v| !v.is_finite()) {
            return Err(tvf_error(format!(
                "{}: {what}: the block has non-finite values",
                self.name
            )));
        }
        Ok(Mat::from_fn(view.nrows(), view.ncols(), |i, j| {
            view[(i, j)]
        }))
    }
}

#[pymethods]
impl Operator {
    /// The key of `tvf.operators` this operator is.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// `(m, n)`.
    #[getter]
    fn shape(&self) -> (usize, usize) {
        self.operator.shape()
    }

    /// `A x` (`n` entries in, `m` out).
    fn matvec<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let x = self.input(&x, self.operator.cols(), "matvec")?;
        let y = py.detach(|| self.operator.apply(&x));
        self.output(&y, "matvec")?;
        Ok(y.into_pyarray(py).into_any())
    }

    /// `Aᵀ x` (`m` entries in, `n` out).
    fn rmatvec<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let x = self.input(&x, self.operator.rows(), "rmatvec")?;
        let y = py.detach(|| self.operator.apply_transpose(&x));
        self.output(&y, "rmatvec")?;
        Ok(y.into_pyarray(py).into_any())
    }

    /// `A X` for an `n × r` block (`m × r` out).
    fn matmat<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let x = self.block(&x, self.operator.cols(), "matmat")?;
        let y = py.detach(|| self.operator.apply_block(x.as_ref()));
        if y.col_iter().any(|c| c.iter().any(|v| !v.is_finite())) {
            return Err(tvf_error(format!(
                "{}: matmat gave non-finite values",
                self.name
            )));
        }
        Ok(mat_to_numpy(py, &y.as_ref()))
    }

    /// `Aᵀ X` for an `m × r` block (`n × r` out).
    fn rmatmat<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let x = self.block(&x, self.operator.rows(), "rmatmat")?;
        let columns: Vec<Vec<f64>> = py.detach(|| {
            x.col_iter()
                .map(|c| {
                    let column: Vec<f64> = c.iter().copied().collect();
                    self.operator.apply_transpose(&column)
                })
                .collect()
        });
        if columns.iter().any(|c| c.iter().any(|v| !v.is_finite())) {
            return Err(tvf_error(format!(
                "{}: rmatmat gave non-finite values",
                self.name
            )));
        }
        let y = Mat::from_fn(self.operator.cols(), columns.len(), |i, j| columns[j][i]);
        Ok(mat_to_numpy(py, &y.as_ref()))
    }

    fn __repr__(&self) -> String {
        let (m, n) = self.operator.shape();
        format!("Operator('{}', {m} × {n})", self.name)
    }
}
