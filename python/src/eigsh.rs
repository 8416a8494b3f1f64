//! `tvf.eigsh`: tvf's generalized eigensolver (spectrum slicing with inertia-checked
//! completeness) on any sparse symmetric pencil `(A, diag(M))`.

use crate::arrays::{csr_from_parts, mat_to_numpy, CsrParts};
use crate::errors::with_context;
use crate::progress::Progress;
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::prelude::*;
use tvf_solvers::{lowest_eigenpairs, EigenOptions};

/// The lowest `k` eigenpairs of `A x = λ M x`: `(eigenvalues (k), eigenvectors (n × k),
/// residuals (k))`, eigenvectors `M`-orthonormal.
#[pyfunction]
#[pyo3(signature = (a, mass, k, seed = None, progress = None))]
pub fn eigsh<'py>(
    py: Python<'py>,
    a: CsrParts<'py>,
    mass: PyReadonlyArray1<'py, f64>,
    k: usize,
    seed: Option<u64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let a = csr_from_parts("A", a)?;
    let mass = mass.as_slice()?.to_vec();
    let reporter = Progress::new(progress);
    let pairs = py.detach(|| {
        let callback =
            |p: &tvf_solvers::EigenProgress| reporter.report("eigenpairs", p.confirmed, p.wanted);
        let mut options = EigenOptions {
            progress: Some(&callback),
            ..EigenOptions::default()
        };
        if let Some(seed) = seed {
            options.seed = seed;
        }
        lowest_eigenpairs(&a, &mass, k, &options)
    });
    reporter.finish()?;
    let pairs = pairs.map_err(|e| with_context("eigsh", &e))?;
    Ok((
        pairs.values.into_pyarray(py).into_any(),
        mat_to_numpy(py, &pairs.vectors.as_ref()),
        pairs.residuals.into_pyarray(py).into_any(),
    ))
}
