//! `tvf.eigsh`: tvf's generalized eigensolver (spectrum slicing with inertia-checked
//! completeness) on any sparse symmetric pencil `(A, M)`, `M` a positive diagonal or a sparse
//! symmetric positive definite matrix.

use crate::arrays::{csr_from_parts, mat_to_numpy, CsrParts};
use crate::errors::{tvf_error, with_context};
use crate::interrupt::{interruptible, Interruption};
use crate::masses::{mass_from_input, Given, MassInput};
use crate::progress::Progress;
use numpy::IntoPyArray;
use pyo3::prelude::*;
use tvf_core::discretization::MassStorage;
use tvf_solvers::{
    lowest_eigenpairs_of, EigenOptions, EigenRequest, Eigenpairs, MassMatrix, Pencil, SolverError,
};

/// The lowest `k` eigenpairs of `A x = λ M x`: `(eigenvalues (k), eigenvectors (n × k),
/// residuals (k))`, eigenvectors `M`-orthonormal. `mass` is the diagonal of `M` or its CSR
/// parts (square, finite, symmetric to round-off; positive definite, checked by the solver's
/// Cholesky factorization).
#[pyfunction]
#[pyo3(signature = (a, mass, k, seed = None, progress = None))]
pub fn eigsh<'py>(
    py: Python<'py>,
    a: CsrParts<'py>,
    mass: MassInput<'py>,
    k: usize,
    seed: Option<u64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let a = csr_from_parts("A", a)?;
    let mass = mass_from_input("M (the mass matrix)", mass, Given::Mass)?;
    if mass.len() != a.rows() {
        return Err(tvf_error(format!(
            "M (the mass matrix) has {} rows, A has {}",
            mass.len(),
            a.rows()
        )));
    }
    let interruption = Interruption::default();
    let reporter = Progress::new(progress, &interruption);
    let pairs = interruptible(py, &interruption, || -> Result<Eigenpairs, SolverError> {
        let callback =
            |p: &tvf_solvers::EigenProgress| reporter.report("eigenpairs", p.confirmed, p.wanted);
        let mut options = EigenOptions {
            progress: Some(&callback),
            ..EigenOptions::default()
        };
        if let Some(seed) = seed {
            options.seed = seed;
        }
        let pencil = match mass.storage() {
            MassStorage::Diagonal(values) => Pencil::new(&a, values)?,
            MassStorage::Sparse(matrix) => Pencil::with_mass(&a, MassMatrix::Sparse(matrix))?,
        };
        let request = EigenRequest {
            pencil: &pencil,
            count: k,
            top: None,
            seed: options.seed,
        };
        let solution = lowest_eigenpairs_of(&[request], &options).map_err(|e| e.source)?;
        solution
            .pairs
            .into_iter()
            .next()
            .ok_or_else(|| SolverError::NoConvergence {
                reason: "the driver returned no result".into(),
            })
    })?;
    let pairs = pairs.map_err(|e| with_context("eigsh", &e))?;
    let finite = |values: &[f64]| values.iter().all(|v| v.is_finite());
    if !finite(&pairs.values)
        || !finite(&pairs.residuals)
        || pairs
            .vectors
            .col_iter()
            .any(|c| c.iter().any(|v| !v.is_finite()))
    {
        return Err(tvf_error("eigsh: the eigenpairs are not finite"));
    }
    Ok((
        pairs.values.into_pyarray(py).into_any(),
        mat_to_numpy(py, &pairs.vectors.as_ref()),
        pairs.residuals.into_pyarray(py).into_any(),
    ))
}
