//! `tvf.convergence`: catalog entries and Python builders through the convergence study of
//! `tvf convergence` (`tvf_convergence`) against the exact spectra of the unit
//! sphere and hemisphere.

use crate::check::python_complex;
use crate::errors::{from_error, tvf_error};
use crate::interrupt::{interruptible, Interruption};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tvf_convergence::study::{
    run_convergence, Candidate, ConvergenceConfig, ConvergenceReport, Surface,
};
use tvf_core::discretization::BoundaryCondition;
use tvf_discretizations::catalog_entry;

/// Runs the study. `candidates` are `(name, id_or_builder)` pairs; `surfaces` names from
/// `sphere`, `hemisphere-tangential`, `hemisphere-normal`. A dict `rows` (one dict per
/// candidate, surface and level) and `orders` (one per candidate, surface and family), with
/// the keys of `tvf convergence --json`. Ctrl+C in a builder (or any exception that is not an
/// `Exception`) stops the study and is raised as it is, not as a `TvfError`.
#[pyfunction]
#[pyo3(signature = (candidates, surfaces, levels, eigenvalues))]
pub fn convergence<'py>(
    py: Python<'py>,
    candidates: Vec<(String, Py<PyAny>)>,
    surfaces: Vec<String>,
    levels: Vec<u32>,
    eigenvalues: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let surfaces = surfaces
        .iter()
        .map(|name| surface(name))
        .collect::<PyResult<Vec<_>>>()?;
    if let Some(&level) = levels.iter().find(|&&l| l > 7) {
        return Err(tvf_error(format!(
            "level {level}: at most 7 (1.3 million sphere faces)"
        )));
    }
    let interruption = Interruption::default();
    let mut study: Vec<Candidate<'_>> = Vec::new();
    for (name, source) in &candidates {
        if let Ok(id) = source.extract::<String>(py) {
            let entry = catalog_entry(&id).map_err(|e| from_error(&e))?;
            study.push(Candidate::from_entry(entry));
            continue;
        }
        if surfaces.iter().any(|s| s.boundary().is_some()) {
            return Err(tvf_error(format!(
                "'{name}': a builder runs on closed meshes only (Complex.from_matrices); \
                 ask for surfaces=('sphere',)"
            )));
        }
        let build = source.clone_ref(py);
        let interruption = &interruption;
        study.push(Candidate::new(name.clone(), move |mesh, _| {
            python_complex(&build, mesh, interruption)
        }));
    }
    let config = ConvergenceConfig {
        surfaces,
        levels,
        eigenvalues,
    };
    // The study runs without the GIL; a Python builder takes it while it builds.
    let report = interruptible(py, &interruption, || {
        run_convergence(&study, &config, &|_, _, _| {})
    })?
    .map_err(|e| tvf_error(e.to_string()))?;
    report_dict(py, &report)
}

/// `sphere`, `hemisphere-tangential` or `hemisphere-normal`, each also `jittered-…` (irregular
/// refinements).
fn surface(name: &str) -> PyResult<Surface> {
    let (jittered, plain) = match name.strip_prefix("jittered-") {
        Some(plain) => (true, plain),
        None => (false, name),
    };
    match (plain.strip_prefix("hemisphere-"), jittered) {
        (None, false) if plain == "sphere" => Ok(Surface::Sphere),
        (None, true) if plain == "sphere" => Ok(Surface::JitteredSphere),
        (Some(condition), _) => BoundaryCondition::from_name(condition)
            .map(|b| match jittered {
                true => Surface::JitteredHemisphere(b),
                false => Surface::Hemisphere(b),
            })
            .ok_or_else(|| unknown_surface(name)),
        (None, _) => Err(unknown_surface(name)),
    }
}

fn unknown_surface(name: &str) -> PyErr {
    tvf_error(format!(
        "'{name}' is not a surface: sphere, hemisphere-tangential or hemisphere-normal, each \
         also jittered- (e.g. jittered-sphere)"
    ))
}

fn report_dict<'py>(py: Python<'py>, report: &ConvergenceReport) -> PyResult<Bound<'py, PyDict>> {
    let boundary = |s: Surface| s.boundary().map(|b| b.name());
    let mut rows = Vec::new();
    for r in &report.rows {
        let d = PyDict::new(py);
        d.set_item("discretization", &r.discretization)?;
        d.set_item("surface", r.surface.name())?;
        d.set_item("boundary", boundary(r.surface))?;
        d.set_item("level", r.level)?;
        d.set_item("faces", r.faces)?;
        d.set_item("h", r.h)?;
        d.set_item("integrable_error", r.integrable_error)?;
        d.set_item("cointegrable_error", r.cointegrable_error)?;
        d.set_item("seconds", r.seconds)?;
        rows.push(d);
    }
    let mut orders = Vec::new();
    for o in &report.orders {
        let d = PyDict::new(py);
        d.set_item("discretization", &o.discretization)?;
        d.set_item("surface", o.surface.name())?;
        d.set_item("boundary", boundary(o.surface))?;
        d.set_item("family", o.family.name())?;
        d.set_item("order", o.order.is_finite().then_some(o.order))?;
        orders.push(d);
    }
    let result = PyDict::new(py);
    result.set_item("rows", rows)?;
    result.set_item("orders", orders)?;
    Ok(result)
}
