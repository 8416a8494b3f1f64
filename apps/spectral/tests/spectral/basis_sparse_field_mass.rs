//! The Fourier basis of complexes with a non-diagonal field mass `M1` (whitney-galerkin,
//! polygon-dec), solved by the iterative eigensolver (meshes above its dense threshold): the
//! eigenfunctions are normalised from their eigenvalues (`‖D φ‖²_{M1} = λ φᵀ M φ`) instead of
//! by forming the fields, so every field formed the old way (`d0 φ`, `−M1⁻¹ d1ᵀ ψ` by a solve
//! with `M1`) must be `M1`-unit to 1e-12; the basis's eigenfield residuals and
//! `M1`-orthonormality as for every complex.

use tvf_core::discretization::{BoundaryCondition, HodgeComplex, HodgeOperators};
use tvf_core::generate::{hemisphere, quad_torus, torus};
use tvf_discretizations::{PolygonDec, WhitneyGalerkin, DEFAULT_STABILISATION};
use tvf_spectral::{
    compute_basis, compute_eigenfunction_basis, eigen_residual, BasisRequest, FieldFamily,
};

/// The eigenfields of `complex` formed from its compact basis by the gradient and the
/// co-gradient (a block solve with `M1`), each `M1`-unit to 1e-12; the dense basis's fields are
/// those same fields, eigenfields of `L` and `M1`-orthonormal.
fn check_sparse_field_mass<H: HodgeComplex + ?Sized>(complex: &H, pairs: usize, what: &str) {
    assert!(
        complex.m1().diagonal_values().is_none(),
        "{what}: M1 is sparse"
    );
    let request = BasisRequest::pairs(pairs).with_seed(5);
    let (compact, report) = compute_eigenfunction_basis(complex, &request).unwrap();
    assert!(
        report.solves > 0,
        "{what}: the iterative eigensolver ran (not the dense path)"
    );
    let families = compact.families().to_vec();
    let mut checked = [0usize; 2];
    for (i, family) in families.iter().enumerate() {
        let slot = match family {
            FieldFamily::Integrable => 0,
            FieldFamily::Cointegrable => 1,
            FieldFamily::Harmonic => continue,
        };
        let field = compact.field(complex, i);
        let norm = complex.field_inner(&field, &field).sqrt();
        assert!(
            (norm - 1.0).abs() <= 1e-12,
            "{what}: {family:?} field {i} (λ = {}) has M1 norm 1 {:+e}",
            compact.eigenvalues()[i],
            norm - 1.0
        );
        checked[slot] += 1;
    }
    assert!(checked[0] > 0 && checked[1] > 0, "{what}: {checked:?}");

    let basis = compute_basis(complex, &request).unwrap();
    assert_eq!(basis.eigenvalues(), compact.eigenvalues());
    let fields = basis.fields();
    let column = |j: usize| {
        (0..fields.nrows())
            .map(|r| fields[(r, j)])
            .collect::<Vec<f64>>()
    };
    let columns: Vec<Vec<f64>> = (0..basis.len()).map(column).collect();
    for (j, u) in columns.iter().enumerate() {
        let lambda = basis.eigenvalues()[j];
        let residual = eigen_residual(complex, lambda, u);
        assert!(
            residual <= 1e-8 * lambda.max(1.0),
            "{what}: field {j} (λ = {lambda}) residual {residual:e}"
        );
        let formed = compact.field(complex, j);
        let scale = formed.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (a, b) in u.iter().zip(&formed) {
            assert!(
                (a - b).abs() <= 1e-12 * scale,
                "{what}: field {j}: {a} vs {b}"
            );
        }
    }
    let mut worst = 0.0f64;
    for i in 0..columns.len() {
        for j in 0..=i {
            let target = if i == j { 1.0 } else { 0.0 };
            worst = worst.max((complex.field_inner(&columns[i], &columns[j]) - target).abs());
        }
    }
    assert!(worst <= 1e-9, "{what}: M1-orthonormality error {worst:e}");
}

#[test]
fn whitney_galerkin_fields_are_m1_unit_from_their_eigenvalues() {
    let mesh = torus(3.0, 1.0, 36, 16).unwrap();
    let complex = WhitneyGalerkin::new(&mesh).unwrap();
    check_sparse_field_mass(&complex, 30, "whitney-galerkin torus");
}

#[test]
fn whitney_galerkin_fields_with_boundary_are_m1_unit_from_their_eigenvalues() {
    let mesh = hemisphere(14);
    for boundary in BoundaryCondition::ALL {
        let complex = WhitneyGalerkin::with_boundary(&mesh, boundary).unwrap();
        check_sparse_field_mass(
            &complex,
            30,
            &format!("whitney-galerkin hemisphere {boundary:?}"),
        );
    }
}

#[test]
fn polygon_dec_fields_are_m1_unit_from_their_eigenvalues() {
    let mesh = quad_torus(3.0, 1.0, 36, 16).unwrap();
    let complex =
        PolygonDec::with_boundary(&mesh, BoundaryCondition::default(), DEFAULT_STABILISATION)
            .unwrap();
    check_sparse_field_mass(&complex, 30, "polygon-dec quad torus");
}
