//! The harmonic fields of a complex (`2g` per closed component, `2g + b − 1` per component with
//! `b` boundary loops), with how good they are.

use crate::laplacian_apply::{apply_hodge_laplacian, field_norm};
use crate::BasisError;
use faer::Mat;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_discretizations::HodgeDecomposer;

/// An `M1`-orthonormal basis of the harmonic fields and its quality.
#[derive(Debug, Clone)]
pub struct HarmonicFields {
    /// The fields, `n1 × h` with `h = harmonic_dimension()` (`2g` summed over components).
    pub fields: Mat<f64>,
    /// `max |Γᵀ M1 Γ − I|` over all entries: distance from orthonormal.
    pub orthonormality_error: f64,
    /// `max_i ‖L Γ_i‖_{M1}` (units 1/length²; the fields are `M1`-unit): distance from `ker L`.
    pub kernel_residual: f64,
}

/// Projects `h = complex.topology().harmonic_dimension` random fields (seeded) onto the harmonic space
/// (two Poisson solves each: remove the integrable and co-integrable parts), orthonormalises them
/// in `M1` and re-projects (by [`HodgeDecomposer::harmonic_basis`]), then measures the result.
/// On a genus-0 mesh nothing is factored and the result has no column.
pub fn harmonic_fields<H: HodgeComplex + ?Sized>(
    complex: &H,
    seed: u64,
) -> Result<HarmonicFields, BasisError> {
    let rows = complex.field_dimension();
    let h = complex.topology().harmonic_dimension;
    if h == 0 {
        return Ok(HarmonicFields {
            fields: Mat::zeros(rows, 0),
            orthonormality_error: 0.0,
            kernel_residual: 0.0,
        });
    }
    let basis = HodgeDecomposer::new(complex)?.harmonic_basis(seed)?;
    let fields = Mat::from_fn(rows, basis.len(), |r, j| basis[j][r]);
    let mut orthonormality_error = 0.0f64;
    for (i, a) in basis.iter().enumerate() {
        for (j, b) in basis.iter().enumerate() {
            let target = if i == j { 1.0 } else { 0.0 };
            orthonormality_error =
                orthonormality_error.max((complex.field_inner(a, b) - target).abs());
        }
    }
    let kernel_residual = basis
        .iter()
        .map(|g| field_norm(complex, &apply_hodge_laplacian(complex, g)))
        .fold(0.0, f64::max);
    Ok(HarmonicFields {
        fields,
        orthonormality_error,
        kernel_residual,
    })
}
