//! `tvf.check`: the core conformance checks of the test suite on a complex, as a report.

use crate::complex::Complex;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tvf_conformance::check_report::core_check_report;

/// One dict per check: `name`, `status` (`passed`/`failed`/`skipped`), `measured`, `limit`,
/// `detail`.
#[pyfunction]
pub fn check<'py>(py: Python<'py>, complex: &Complex) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let report = py.detach(|| core_check_report(complex.complex.as_ref(), &complex.mesh));
    report
        .outcomes
        .iter()
        .map(|o| {
            let d = PyDict::new(py);
            d.set_item("name", &o.name)?;
            d.set_item("status", o.status.name())?;
            d.set_item("measured", o.measured)?;
            d.set_item("limit", o.limit)?;
            d.set_item("detail", &o.detail)?;
            Ok(d)
        })
        .collect()
}
