//! `tvf.spline` and `tvf.design`: fields from constraint sets, in the JSON format of the
//! command line's constraint files (Python passes the dict serialised as JSON).

use crate::basis_parts::BasisParts;
use crate::complex::Complex;
use crate::errors::{from_error, tvf_error, with_context};
use crate::interrupt::detached;
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::Path;
use tvf_core::discretization::HodgeComplex;
use tvf_core::SurfaceMesh;
use tvf_design::{
    checked_residuals, default_regularization, timed_reduced_design, timed_spline,
    CompiledConstraint, ConstraintResidual, ConstraintSet, DesignError, FullSoftDesign,
    ReducedBasis, SoftOptions,
};

/// Parses the constraint JSON (`origin` names it in messages) and compiles it on the complex.
fn constraints(
    complex: &Complex,
    json: &str,
    origin: &str,
) -> PyResult<(ConstraintSet, Vec<CompiledConstraint>)> {
    constraints_on(&complex.mesh, complex.complex.as_ref(), json, origin)
}

/// [`constraints`] on `complex` built on `mesh`.
pub fn constraints_on(
    mesh: &SurfaceMesh,
    complex: &dyn HodgeComplex,
    json: &str,
    origin: &str,
) -> PyResult<(ConstraintSet, Vec<CompiledConstraint>)> {
    let origin = Path::new(origin);
    let set = ConstraintSet::parse(json, origin).map_err(|e| from_error(&e))?;
    let compiled = set
        .compile_for(origin, mesh, complex)
        .map_err(|e| from_error(&e))?;
    Ok((set, compiled))
}

/// The field and its per-constraint residuals as a dict; a field with a non-finite coefficient
/// is an error.
pub fn result<'py>(
    py: Python<'py>,
    field: Vec<f64>,
    compiled: &[CompiledConstraint],
    omega: f64,
    origin: &str,
) -> PyResult<Bound<'py, PyDict>> {
    if let Some(i) = field.iter().position(|x| !x.is_finite()) {
        return Err(tvf_error(format!(
            "{origin}: the designed field is not finite (coefficient {i})"
        )));
    }
    let residuals: Vec<ConstraintResidual> =
        checked_residuals(&field, compiled, omega).map_err(|e| with_context(origin, &e))?;
    let out = PyDict::new(py);
    out.set_item("field", field.into_pyarray(py))?;
    let list = PyDict::new(py);
    for r in residuals {
        list.set_item(r.id, (r.absolute, r.relative))?;
    }
    out.set_item("residuals", list)?;
    Ok(out)
}

/// Soft-constrained design on the full field space (sparse `LDLᵀ` with refinement): dict
/// `field`, `residuals`.
#[pyfunction]
pub fn design<'py>(
    py: Python<'py>,
    complex: &Complex,
    constraints_json: &str,
    origin: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let c = complex.complex.as_ref();
    let (set, compiled) = constraints(complex, constraints_json, origin)?;
    let field = detached(py, || -> Result<Vec<f64>, DesignError> {
        let options = SoftOptions {
            omega: set.omega,
            regularization: default_regularization(c),
        };
        let design = FullSoftDesign::new(c, options, compiled.clone())?;
        Ok(design.solve().0)
    })?;
    let field = field.map_err(|e| {
        with_context(
            &format!(
                "{origin}: the full soft-design system (omega {:e}) cannot be factored",
                set.omega
            ),
            &e,
        )
    })?;
    result(py, field, &compiled, set.omega, origin)
}

/// A field in the given basis from the constraints of `constraints_json`: the spline (hard
/// constraints, `soft` false) or soft-constrained design (dense Cholesky of the reduced system
/// `(Λ + ωΛ² + CᵀWC) v = CᵀWc`, `soft` true); any complex. Dict `field` (`n1`), `residuals`
/// (`{id: (absolute, relative)}`).
#[pyfunction]
pub fn reduced<'py>(
    py: Python<'py>,
    complex: &Complex,
    basis: BasisParts<'py>,
    constraints_json: &str,
    origin: &str,
    soft: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let c = complex.complex.as_ref();
    reduced_solve(
        py,
        complex,
        basis,
        constraints_json,
        origin,
        |reduced, set, compiled| solve_reduced(c, soft, reduced, set, compiled),
    )
}

/// The spline (`soft` false) or the reduced soft design of `complex` in `reduced` with the
/// constraints `compiled` of `set`.
pub fn solve_reduced(
    complex: &dyn HodgeComplex,
    soft: bool,
    reduced: &ReducedBasis,
    set: &ConstraintSet,
    compiled: &[CompiledConstraint],
) -> Result<Vec<f64>, DesignError> {
    if !soft {
        return Ok(timed_spline(reduced, set.omega, compiled)?.field);
    }
    let options = SoftOptions {
        omega: set.omega,
        regularization: default_regularization(complex),
    };
    Ok(timed_reduced_design(reduced, options, compiled)?.field)
}

/// A field solved by `solve` in the reduced basis `basis` with the constraints of
/// `constraints_json` (without the GIL), with its residuals.
fn reduced_solve<'py>(
    py: Python<'py>,
    complex: &Complex,
    basis: BasisParts<'py>,
    constraints_json: &str,
    origin: &str,
    solve: impl Fn(&ReducedBasis, &ConstraintSet, &[CompiledConstraint]) -> Result<Vec<f64>, DesignError>
        + Send
        + Sync,
) -> PyResult<Bound<'py, PyDict>> {
    let (set, compiled) = constraints(complex, constraints_json, origin)?;
    let basis = complex.basis(basis)?;
    let field = detached(py, || {
        let reduced = ReducedBasis::from_spectral(&basis)?;
        solve(&reduced, &set, &compiled)
    })?;
    let field = field.map_err(|e| with_context(origin, &e))?;
    result(py, field, &compiled, set.omega, origin)
}
