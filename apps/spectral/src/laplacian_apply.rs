//! The Hodge–Laplacian applied to fields by sparse products, without assembling `L`.

use tvf_core::discretization::sparse::{mul_transpose_vec, mul_vec};
use tvf_core::discretization::{HodgeComplex, Mass};

/// `L v = d0 M0⁻¹ d0ᵀ M1 v + M1⁻¹ d1ᵀ M2 d1 v` for a field `v` (`n1` pointwise coefficients
/// in, `n1` out, units 1/length² times those of `v`). Equals `hodge_laplacian() · v` but costs a
/// few sparse products (and, for a non-diagonal mass, its solves) and no matrix assembly.
pub fn apply_hodge_laplacian<H: HodgeComplex + ?Sized>(complex: &H, field: &[f64]) -> Vec<f64> {
    let weighted = complex.m1().apply(field);
    let divergence = times_inverse(complex.m0(), &mul_transpose_vec(complex.d0(), &weighted));
    let exact = mul_vec(complex.d0(), &divergence);
    let curl = mul_vec(complex.d1(), field);
    let curl: Vec<f64> = match complex.m2().diagonal_values() {
        Some(m2) => curl.iter().zip(m2).map(|(x, w)| x * w).collect(),
        None => complex.m2().apply(&curl),
    };
    let co_exact = times_inverse(complex.m1(), &mul_transpose_vec(complex.d1(), &curl));
    exact.iter().zip(&co_exact).map(|(a, b)| a + b).collect()
}

/// `M⁻¹ x`: for a diagonal mass each entry times the reciprocal mass (the arithmetic of the
/// lumped complexes), else the mass's solve.
fn times_inverse(mass: &Mass, x: &[f64]) -> Vec<f64> {
    match mass.inverse_diagonal() {
        Some(inverse) => x.iter().zip(inverse).map(|(x, w)| x * w).collect(),
        None => mass.solve(x),
    }
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
