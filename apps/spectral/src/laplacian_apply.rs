//! The Hodge–Laplacian applied to fields by sparse products, without assembling `L`.

use tvf_core::discretization::sparse::{mul_transpose_vec, mul_vec};
use tvf_core::discretization::HodgeComplex;

/// `L v = d0 M0⁻¹ d0ᵀ M1 v + M1⁻¹ d1ᵀ M2 d1 v` for a field `v` (`2F` pointwise coefficients in,
/// `2F` pointwise coefficients out, units 1/length² times those of `v`). Equals
/// `hodge_laplacian() · v` but costs four sparse products and no matrix assembly.
pub fn apply_hodge_laplacian<H: HodgeComplex + ?Sized>(complex: &H, field: &[f64]) -> Vec<f64> {
    let weighted = complex.m1().apply(field);
    let divergence: Vec<f64> = mul_transpose_vec(complex.d0(), &weighted)
        .iter()
        .zip(complex.m0().inverse())
        .map(|(x, w)| x * w)
        .collect();
    let exact = mul_vec(complex.d0(), &divergence);
    let curl: Vec<f64> = mul_vec(complex.d1(), field)
        .iter()
        .zip(complex.m2().values())
        .map(|(x, w)| x * w)
        .collect();
    let co_exact = mul_transpose_vec(complex.d1(), &curl);
    exact
        .iter()
        .zip(&co_exact)
        .zip(complex.m1().inverse())
        .map(|((a, b), w)| a + b * w)
        .collect()
}

/// The `M1` norm `√(vᵀ M1 v)` of a field (integrated: units of `v` times length).
pub fn field_norm<H: HodgeComplex + ?Sized>(complex: &H, field: &[f64]) -> f64 {
    complex.m1().inner(field, field).sqrt()
}

/// `‖L u − λ u‖_{M1}`: how far `(λ, u)` is from an eigenpair of the Hodge–Laplacian.
pub fn eigen_residual<H: HodgeComplex + ?Sized>(
    complex: &H,
    eigenvalue: f64,
    field: &[f64],
) -> f64 {
    let lu = apply_hodge_laplacian(complex, field);
    let residual: Vec<f64> = lu
        .iter()
        .zip(field)
        .map(|(l, u)| l - eigenvalue * u)
        .collect();
    field_norm(complex, &residual)
}
