//! `tvf.compare`: discretizations side by side on one mesh, as `tvf compare` does — each
//! complex's basis of the K lowest fields (timed, its peak memory measured), and the report of
//! `tvf compare --json` (`tvf_spectral::ComparisonReport`): sizes, mass non-zeros, times and
//! ratios, eigenvalues per family against the reference's, principal angles between
//! eigenspace clusters.

use crate::complex::Complex;
use crate::errors::tvf_error;
use crate::interrupt::detached;
use pyo3::prelude::*;
use std::time::Instant;
use tvf_core::discretization::HodgeOperators;
use tvf_spectral::{
    compute_basis, BasisRequest, ComparedEntry, ComparisonReport, EntryMeasurements, ResidentPeak,
    SampledBasis,
};

/// Compares `complexes` (at least two, all on one mesh; `reference` the position of the one
/// the others are compared with) with bases of `count` fields, clusters of relative gap at most
/// `cluster_tolerance`; `assembly_seconds` (one per complex, NaN where unknown) are the times
/// their complexes took to build. Returns the JSON text of `tvf compare --json`.
#[pyfunction]
pub fn compare<'py>(
    py: Python<'py>,
    complexes: Vec<PyRef<'py, Complex>>,
    count: usize,
    reference: usize,
    cluster_tolerance: f64,
    assembly_seconds: Vec<f64>,
) -> PyResult<String> {
    if complexes.len() < 2 {
        return Err(tvf_error("compare needs at least two complexes"));
    }
    if count == 0 {
        return Err(tvf_error("k = 0: ask for at least one field"));
    }
    if reference >= complexes.len() || assembly_seconds.len() != complexes.len() {
        return Err(tvf_error(format!(
            "reference {reference} and {} assembly times for {} complexes",
            assembly_seconds.len(),
            complexes.len()
        )));
    }
    if !(0.0..1.0).contains(&cluster_tolerance) {
        return Err(tvf_error(format!(
            "cluster_tolerance {cluster_tolerance}: give a relative gap in [0, 1)"
        )));
    }
    let mesh = complexes[0].mesh.clone();
    let mesh_label = complexes[0].label.clone();
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
    let result = detached(py, || -> Result<String, String> {
        let entries = parts
            .iter()
            .zip(&assembly_seconds)
            .map(|(c, &assembly)| measure(c, count, assembly))
            .collect::<Result<Vec<_>, String>>()?;
        let report = ComparisonReport::new(
            mesh_label,
            &mesh,
            count,
            cluster_tolerance,
            reference,
            entries,
        )
        .map_err(|e| e.to_string())?;
        serde_json::to_string(&report.to_json()).map_err(|e| e.to_string())
    })?;
    result.map_err(tvf_error)
}

/// The basis of `count` fields of `c`, timed, with the resident memory it added at its peak.
fn measure(c: &Complex, count: usize, assembly_seconds: f64) -> Result<ComparedEntry, String> {
    let peak = ResidentPeak::start();
    let start = Instant::now();
    let request = BasisRequest::lowest(count, c.complex.field_dimension());
    let basis = compute_basis(c.complex.as_ref(), &request)
        .map_err(|e| format!("'{}': {e}", c.complex.id()))?;
    let basis_seconds = start.elapsed().as_secs_f64();
    let sampled = SampledBasis::new(c.complex.as_ref(), &basis)
        .map_err(|e| format!("'{}': {e}", c.complex.id()))?;
    drop(basis);
    let measurements = EntryMeasurements::new(
        sampled.id.clone(),
        c.complex.as_ref(),
        assembly_seconds,
        basis_seconds,
        peak.and_then(|p| p.added_bytes()),
    );
    Ok(ComparedEntry {
        measurements,
        sampled,
    })
}
