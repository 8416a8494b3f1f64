//! The Fourier basis on the real meshes of `../shared/meshes` (skipped when absent, a failure
//! under `CI=true`): exactly 2g harmonic fields in the kernel of `L` (kitten 2, eight 4, 3holes
//! 6), every field an eigenfield, `M_X`-orthonormal. A few dozen eigenfields per mesh keep this
//! fast.

use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::io::load_mesh;
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};
use tvf_spectral::{compute_basis, eigen_residual, BasisRequest, FieldFamily, SpectralBasis};
use tvf_test_support::shared_mesh;

fn check<H: HodgeComplex + ?Sized>(
    complex: &H,
    basis: &SpectralBasis,
    harmonic: usize,
    what: &str,
) {
    assert_eq!(basis.count(FieldFamily::Harmonic), harmonic, "{what}");
    let u = basis.fields();
    let fields: Vec<Vec<f64>> = (0..basis.len())
        .map(|j| (0..u.nrows()).map(|i| u[(i, j)]).collect())
        .collect();
    for (j, field) in fields.iter().enumerate() {
        let lambda = basis.eigenvalues()[j];
        let residual = eigen_residual(complex, lambda, field);
        assert!(
            residual <= 1e-8 * lambda.max(1.0),
            "{what}: field {j} λ = {lambda:e}: residual {residual:e}"
        );
    }
    let mut worst = 0.0f64;
    for i in 0..fields.len() {
        for j in 0..=i {
            let target = if i == j { 1.0 } else { 0.0 };
            worst = worst.max((complex.field_inner(&fields[i], &fields[j]) - target).abs());
        }
    }
    assert!(worst <= 1e-9, "{what}: orthonormality {worst:e}");
    let report = basis.report().unwrap();
    println!(
        "{what}: {} fields, harmonic {} (orthonormality {:.1e}, ‖LΓ‖ {:.1e}), {:.2} s",
        basis.len(),
        report.harmonic_dimension,
        report.harmonic_orthonormality_error,
        report.harmonic_kernel_residual,
        report.seconds
    );
}

#[test]
fn harmonic_fields_number_2g_on_the_real_meshes() {
    for (name, genus) in [("kitten", 1), ("eight", 2), ("3holes", 3)] {
        let Some(path) = shared_mesh(&format!("{name}.obj")) else {
            continue;
        };
        let mesh = load_mesh(&path).unwrap().mesh.into_triangles().unwrap();
        assert_eq!(mesh.genus(), genus);
        let request = BasisRequest::pairs(10).with_seed(11);
        let conforming = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
        let basis = compute_basis(&conforming, &request).unwrap();
        check(
            &conforming,
            &basis,
            2 * genus,
            &format!("{name} conforming"),
        );
        let nonconforming = Nonconforming::new(&mesh, MassLumping::Barycentric).unwrap();
        let basis = compute_basis(&nonconforming, &request).unwrap();
        check(
            &nonconforming,
            &basis,
            2 * genus,
            &format!("{name} nonconforming"),
        );
    }
}
