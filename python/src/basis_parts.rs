//! The way back from Python's basis arrays (what `tvf.basis` returned: eigenvalues, family
//! names, coefficients) to a [`SpectralBasis`], for the functions that work in a basis.

use crate::arrays::numpy_to_mat;
use crate::errors::{tvf_error, with_context};
use numpy::{PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_spectral::{FieldFamily, SpectralBasis};

/// Basis arrays as Python passes them: eigenvalues, families, `n1 × k` coefficients.
pub type BasisParts<'py> = (
    PyReadonlyArray1<'py, f64>,
    Vec<String>,
    PyReadonlyArray2<'py, f64>,
);

/// A [`SpectralBasis`] of `complex` from Python's arrays (eigenvalues, family names,
/// `n1 × k` coefficients), checked against the complex.
pub fn spectral_basis(
    complex: &dyn HodgeComplex,
    eigenvalues: PyReadonlyArray1<'_, f64>,
    families: Vec<String>,
    coefficients: PyReadonlyArray2<'_, f64>,
) -> PyResult<SpectralBasis> {
    let families = families
        .iter()
        .map(|name| match name.as_str() {
            "harmonic" => Ok(FieldFamily::Harmonic),
            "integrable" => Ok(FieldFamily::Integrable),
            "cointegrable" => Ok(FieldFamily::Cointegrable),
            other => Err(tvf_error(format!(
                "basis: '{other}' is not a family: harmonic, integrable or cointegrable"
            ))),
        })
        .collect::<PyResult<Vec<_>>>()?;
    let fields = numpy_to_mat(&coefficients);
    if fields.nrows() != complex.field_dimension() {
        return Err(tvf_error(format!(
            "basis: its fields have {} coefficients, the discretization '{}' has {}",
            fields.nrows(),
            complex.id(),
            complex.field_dimension()
        )));
    }
    if fields.col_iter().any(|c| c.iter().any(|x| !x.is_finite())) {
        return Err(tvf_error("basis: its fields contain non-finite values"));
    }
    SpectralBasis::new(
        eigenvalues.as_slice()?.to_vec(),
        families,
        fields,
        complex.m1().clone(),
    )
    .map_err(|e| with_context("basis", &e))
}
