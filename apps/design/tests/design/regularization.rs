//! The default regularization `ε = 1e-10 · tr(M1⁻¹ S) / n1` against the trace computed densely:
//! exact where `S` is sparse and `M1` diagonal, the seeded probe estimate within 10 % where `M1`
//! is not diagonal (the Whitney mass).

use crate::non_diagonal::{dense_dirichlet, dense_field_mass, whitney_galerkin};
use faer::linalg::solvers::Solve;
use faer::Side;
use tvf_core::discretization::{BoundaryCondition, HodgeComplex, HodgeOperators};
use tvf_core::generate::{icosphere, jitter};
use tvf_design::default_regularization;
use tvf_discretizations::catalog_entry;

/// `tr(M1⁻¹ S)` from dense matrices (a closed mesh: every field node is free).
fn dense_trace<H: HodgeComplex + ?Sized>(complex: &H) -> f64 {
    let mass = dense_field_mass(complex);
    let laplacian = mass
        .llt(Side::Lower)
        .expect("M1 is SPD")
        .solve(dense_dirichlet(complex));
    (0..laplacian.nrows()).map(|i| laplacian[(i, i)]).sum()
}

/// The trace `default_regularization` stands for: `ε · 1e10 · n1`.
fn trace_of_regularization<H: HodgeComplex + ?Sized>(complex: &H) -> f64 {
    default_regularization(complex) * 1e10 * complex.field_dimension() as f64
}

#[test]
fn the_trace_is_exact_with_a_diagonal_mass_and_the_probe_estimate_close_otherwise() {
    let mesh = jitter(&icosphere(2), 0.2, 5).expect("mesh");
    let lumped = catalog_entry("conforming-barycentric")
        .expect("in the catalog")
        .build(&mesh)
        .expect("complex");
    let lumped = lumped.as_ref();
    assert!(lumped.m1().diagonal_values().is_some());
    let (exact, computed) = (dense_trace(lumped), trace_of_regularization(lumped));
    assert!(
        (computed - exact).abs() <= 1e-12 * exact,
        "computed {computed:e}, exact {exact:e}"
    );

    let whitney = whitney_galerkin(&mesh, BoundaryCondition::default());
    assert!(
        whitney.m1().diagonal_values().is_none(),
        "the estimate is used"
    );
    let (exact, estimate) = (dense_trace(&whitney), trace_of_regularization(&whitney));
    let relative = (estimate - exact).abs() / exact;
    assert!(relative < 0.1, "estimate {estimate:e}, exact {exact:e}");
}
