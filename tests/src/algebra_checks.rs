//! Algebraic checks: symmetry, semi-definiteness, masses, the complex property `d1 · d0 = 0`.

use crate::dense::generalized_eigenvalues;
use sprs::CsMat;
use tvf_core::discretization::sparse::{product, transpose};
use tvf_core::discretization::{FieldSpace, FunctionSpace, HodgeComplex, HodgeOperators};

fn max_abs(a: &CsMat<f64>) -> f64 {
    a.data().iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// `max |A − Aᵀ| ≤ 1e-12 · max |A|`.
pub fn check_symmetric(what: &str, a: &CsMat<f64>) {
    assert_eq!(a.rows(), a.cols(), "{what}: not square");
    let difference = &a.to_csr() - &transpose(a);
    let asymmetry = max_abs(&difference);
    assert!(
        asymmetry <= 1e-12 * max_abs(a),
        "{what}: asymmetry {asymmetry:e} vs max entry {:e}",
        max_abs(a)
    );
}

/// Smallest generalized eigenvalue of `(A, diag(mass))` is `≥ −1e-10 · largest` (dense).
pub fn check_psd(what: &str, a: &CsMat<f64>, mass: &[f64]) {
    let eigenvalues = generalized_eigenvalues(a, mass);
    let (min, max) = (eigenvalues[0], eigenvalues[eigenvalues.len() - 1]);
    assert!(
        min >= -1e-10 * max.abs(),
        "{what}: eigenvalue {min:e} (largest {max:e})"
    );
}

/// The symmetric matrices of a complex are symmetric: `S`, `B` and both stiffness matrices.
pub fn check_symmetric_operators<H: HodgeComplex>(complex: &H) {
    check_symmetric("potential stiffness", &complex.potential_stiffness());
    check_symmetric("co-potential stiffness", &complex.co_potential_stiffness());
    check_symmetric("Dirichlet energy S", &complex.dirichlet_energy());
    check_symmetric("biharmonic energy B", &complex.biharmonic_energy());
}

/// `S`, `B` and both stiffness matrices are positive semi-definite (dense; small meshes).
pub fn check_psd_operators<H: HodgeComplex>(complex: &H) {
    check_psd("S", &complex.dirichlet_energy(), complex.m1());
    check_psd("B", &complex.biharmonic_energy(), complex.m1());
    let exact = complex.exact_eigenproblem();
    check_psd("potential stiffness", &exact.stiffness, &exact.mass);
    let co_exact = complex.co_exact_eigenproblem();
    check_psd(
        "co-potential stiffness",
        &co_exact.stiffness,
        &co_exact.mass,
    );
}

/// All masses positive, each space's masses sum to the total area, `M2 = M_co⁻¹`, and the
/// dimensions agree.
pub fn check_masses<H: HodgeComplex>(complex: &H, total_area: f64) {
    let p = complex.potentials();
    let q = complex.co_potentials();
    let x = complex.fields();
    assert_eq!(complex.m0().len(), p.dimension());
    assert_eq!(complex.m1().len(), x.dimension());
    assert_eq!(complex.m2().len(), q.dimension());
    for (what, mass) in [("M0", p.mass()), ("M_co", q.mass()), ("M1", x.mass())] {
        assert!(mass.iter().all(|&m| m > 0.0), "{what}: non-positive mass");
    }
    for (what, sum) in [
        ("M0", p.mass().iter().sum::<f64>()),
        ("M_co", q.mass().iter().sum::<f64>()),
        ("M1 / 2", x.mass().iter().sum::<f64>() / 2.0),
    ] {
        assert!(
            (sum - total_area).abs() <= 1e-12 * total_area,
            "{what} sums to {sum}, area is {total_area}"
        );
    }
    for (m2, m) in complex.m2().iter().zip(q.mass()) {
        assert!(
            (m2 * m - 1.0).abs() < 1e-14,
            "M2 is not the inverse co-potential mass"
        );
    }
}

/// `d1 · d0 = 0` up to round-off: `max |d1 d0| ≤ 1e-12 · max|d1| · max|d0|`.
pub fn check_d1_d0_zero<H: HodgeComplex>(complex: &H) {
    let composed = product(complex.d1(), complex.d0());
    let scale = max_abs(complex.d1()) * max_abs(complex.d0());
    let error = max_abs(&composed);
    assert!(
        error <= 1e-12 * scale,
        "|d1 d0| = {error:e}, scale {scale:e}"
    );
}

/// Integrable ⟂ co-integrable: `(J G_co)ᵀ M1 d0 = 0` (conforming: `G*ᵀ J M_X G = 0`), computed
/// through the co-gradient, a path independent of `d1`.
pub fn check_integrable_orthogonal_to_cointegrable<H: HodgeComplex>(complex: &H) {
    let co_gradient = complex.co_gradient();
    let weighted = tvf_core::discretization::sparse::scale_rows(complex.m1(), complex.d0());
    let cross = product(&transpose(&co_gradient), &weighted);
    let scale = max_abs(&co_gradient) * max_abs(&weighted);
    let error = max_abs(&cross);
    assert!(
        error <= 1e-12 * scale,
        "|(J G_co)ᵀ M1 d0| = {error:e}, scale {scale:e}"
    );
}

/// `J² = −I`, `Jᵀ M1 J = M1`, and the frames are orthonormal, positively oriented, tangent.
pub fn check_field_space<H: HodgeComplex>(complex: &H) {
    let x = complex.fields();
    let j = x.rotation();
    let j2 = product(j, j);
    for (value, (r, c)) in j2.iter() {
        let expected = if r == c { -1.0 } else { 0.0 };
        assert!((value - expected).abs() < 1e-15, "J² ≠ −I at ({r},{c})");
    }
    assert_eq!(j2.nnz(), x.dimension());
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    for t in 0..x.face_count() {
        let [e1, e2] = x.frame(t);
        let n = x.normal(t);
        for (value, expected) in [
            (dot(e1, e1), 1.0),
            (dot(e2, e2), 1.0),
            (dot(e1, e2), 0.0),
            (dot(e1, n), 0.0),
            (dot(e2, n), 0.0),
        ] {
            assert!(
                (value - expected).abs() < 1e-12,
                "frame of face {t} not orthonormal"
            );
        }
        let c = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        assert!(
            (dot(c, n) - 1.0).abs() < 1e-12,
            "frame of face {t} negatively oriented"
        );
    }
}
