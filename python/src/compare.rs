//! `tvf.compare`: discretizations side by side on one mesh, as `tvf compare` does — each
//! complex's basis of the K lowest fields (timed), its eigenvalues against the first's index by
//! index, and how much of each eigenfield lies in the span of the other's fields
//! (`tvf_spectral::BasisComparison`).

use crate::complex::Complex;
use crate::errors::tvf_error;
use crate::interrupt::detached;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::time::Instant;
use tvf_core::discretization::HodgeOperators;
use tvf_spectral::{compute_basis, BasisComparison, BasisRequest, SampledBasis};

/// One compared complex: its sampled basis and the seconds its basis took.
struct Compared {
    sampled: SampledBasis,
    field_dimension: usize,
    seconds: f64,
}

/// Compares `complexes` (at least two, all on one mesh; the first is the reference) with bases
/// of `count` fields. A dict: `reference` (id), `entries` (per complex: `discretization`,
/// `field_dimension`, `eigenvalues`, `basis_seconds`), `comparisons` (per complex after the
/// first: `first`, `second`, `eigenvalue_differences`, `second_in_first`, `first_in_second`).
#[pyfunction]
pub fn compare<'py>(
    py: Python<'py>,
    complexes: Vec<PyRef<'py, Complex>>,
    count: usize,
) -> PyResult<Bound<'py, PyDict>> {
    if complexes.len() < 2 {
        return Err(tvf_error("compare needs at least two complexes"));
    }
    if count == 0 {
        return Err(tvf_error("k = 0: ask for at least one field"));
    }
    let mesh = complexes[0].mesh.clone();
    if let Some(other) = complexes[1..]
        .iter()
        .find(|c| c.mesh.fingerprint() != mesh.fingerprint())
    {
        return Err(tvf_error(format!(
            "'{}' is built on another mesh than '{}': compare complexes of one mesh",
            other.complex.id(),
            complexes[0].complex.id()
        )));
    }
    let parts: Vec<&Complex> = complexes.iter().map(|c| &**c).collect();
    let result = detached(py, || -> Result<_, String> {
        let compared = parts
            .iter()
            .map(|c| {
                let start = Instant::now();
                let request = BasisRequest::lowest(count, c.complex.field_dimension());
                let basis = compute_basis(c.complex.as_ref(), &request)
                    .map_err(|e| format!("'{}': {e}", c.complex.id()))?;
                let seconds = start.elapsed().as_secs_f64();
                let sampled = SampledBasis::new(c.complex.as_ref(), &basis)
                    .map_err(|e| format!("'{}': {e}", c.complex.id()))?;
                Ok(Compared {
                    sampled,
                    field_dimension: c.complex.field_dimension(),
                    seconds,
                })
            })
            .collect::<Result<Vec<_>, String>>()?;
        let comparisons = compared[1..]
            .iter()
            .map(|c| BasisComparison::new(&mesh, &compared[0].sampled, &c.sampled))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| e.to_string())?;
        Ok((compared, comparisons))
    })?;
    let (compared, comparisons) = result.map_err(tvf_error)?;
    let out = PyDict::new(py);
    out.set_item("reference", &compared[0].sampled.id)?;
    out.set_item("entries", entry_dicts(py, &compared)?)?;
    let comparison_dicts = comparisons
        .iter()
        .map(|c| {
            let d = PyDict::new(py);
            d.set_item("first", &c.first)?;
            d.set_item("second", &c.second)?;
            d.set_item("eigenvalue_differences", c.eigenvalue_differences.clone())?;
            d.set_item("second_in_first", c.second_in_first.clone())?;
            d.set_item("first_in_second", c.first_in_second.clone())?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    out.set_item("comparisons", comparison_dicts)?;
    Ok(out)
}

/// One dict per compared complex.
fn entry_dicts<'py>(py: Python<'py>, compared: &[Compared]) -> PyResult<Vec<Bound<'py, PyDict>>> {
    compared
        .iter()
        .map(|c| {
            let d = PyDict::new(py);
            d.set_item("discretization", &c.sampled.id)?;
            d.set_item("field_dimension", c.field_dimension)?;
            d.set_item("eigenvalues", c.sampled.eigenvalues.clone())?;
            d.set_item("basis_seconds", c.seconds)?;
            Ok(d)
        })
        .collect()
}
