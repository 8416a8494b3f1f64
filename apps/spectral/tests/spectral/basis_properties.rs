//! The Fourier basis on generated meshes, both decompositions: eigenfield residuals,
//! orthonormality, harmonic dimension 2g, the complete basis, and the size requests.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::generate::{genus_surface, icosphere, torus};
use tvf_core::TriangleMesh;
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};
use tvf_spectral::{
    compute_basis, compute_eigenfunction_basis, eigen_residual, BasisRequest, FieldFamily,
    FourierAnalysis, SpectralBasis,
};

fn column(basis: &SpectralBasis, j: usize) -> Vec<f64> {
    let u = basis.fields();
    (0..u.nrows()).map(|i| u[(i, j)]).collect()
}

/// Every field an eigenfield to 1e-8·max(1, λ); `Uᵀ M_X U = I` to 1e-9; harmonic count = 2g.
fn check_basis<H: HodgeComplex + ?Sized>(
    complex: &H,
    basis: &SpectralBasis,
    genus: usize,
    what: &str,
) {
    assert_eq!(
        basis.count(FieldFamily::Harmonic),
        2 * genus,
        "{what}: harmonic count"
    );
    let fields: Vec<Vec<f64>> = (0..basis.len()).map(|j| column(basis, j)).collect();
    for (j, u) in fields.iter().enumerate() {
        let lambda = basis.eigenvalues()[j];
        let residual = eigen_residual(complex, lambda, u);
        assert!(
            residual <= 1e-8 * lambda.max(1.0),
            "{what}: field {j} ({:?}, λ = {lambda}) residual {residual:e}",
            basis.families()[j]
        );
        if basis.families()[j] == FieldFamily::Harmonic {
            assert_eq!(lambda, 0.0);
        } else {
            assert!(
                lambda > 1e-6,
                "{what}: non-harmonic field {j} with λ = {lambda}"
            );
        }
    }
    let mut worst = 0.0f64;
    for i in 0..fields.len() {
        for j in 0..=i {
            let target = if i == j { 1.0 } else { 0.0 };
            worst = worst.max((complex.field_inner(&fields[i], &fields[j]) - target).abs());
        }
    }
    assert!(worst <= 1e-9, "{what}: orthonormality error {worst:e}");
    let report = basis.report().expect("computed bases carry a report");
    assert_eq!(report.harmonic_dimension, 2 * genus);
    assert!(
        report.harmonic_orthonormality_error <= 1e-9,
        "{what}: {report:?}"
    );
    assert!(
        report.harmonic_kernel_residual <= 1e-8,
        "{what}: {report:?}"
    );
}

#[test]
fn generated_surfaces_of_genus_0_to_3_both_decompositions() {
    for genus in 0..=3 {
        let mesh = genus_surface(genus, 4);
        assert_eq!(mesh.genus(), genus);
        let request = BasisRequest::pairs(12).with_seed(genus as u64);
        let conforming = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
        let basis = compute_basis(&conforming, &request).unwrap();
        assert_eq!(basis.len(), 2 * genus + 24);
        check_basis(
            &conforming,
            &basis,
            genus,
            &format!("conforming genus {genus}"),
        );
        let nonconforming = Nonconforming::new(&mesh, MassLumping::Voronoi).unwrap();
        let basis = compute_basis(&nonconforming, &request).unwrap();
        check_basis(
            &nonconforming,
            &basis,
            genus,
            &format!("nonconforming genus {genus}"),
        );
    }
}

fn random_field(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| rng.random_range(-1.0..1.0)).collect()
}

fn check_complete<H: HodgeComplex + ?Sized>(complex: &H, mesh: &TriangleMesh, what: &str) {
    let basis = compute_basis(complex, &BasisRequest::complete()).unwrap();
    let faces = mesh.face_count();
    assert_eq!(basis.len(), 2 * faces, "{what}: complete basis size");
    assert_eq!(
        basis.count(FieldFamily::Integrable),
        complex.potentials_dimension() - 1
    );
    check_basis(complex, &basis, mesh.genus(), what);
    let v = random_field(2 * faces, 7);
    let analysis = FourierAnalysis::new(&basis, &v).unwrap();
    assert!(
        analysis.relative_rest_norm < 1e-12,
        "{what}: rest {}",
        analysis.relative_rest_norm
    );
    let back = basis.reconstruct(&analysis.coefficients).unwrap();
    let error: f64 = v
        .iter()
        .zip(&back)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(error < 1e-12, "{what}: reconstruction error {error:e}");
    // Parseval: Σ c² = ‖v‖²
    let energy: f64 = analysis.coefficients.iter().map(|c| c * c).sum();
    assert!((energy - analysis.norm * analysis.norm).abs() < 1e-10 * energy);
}

trait PotentialsDimension {
    fn potentials_dimension(&self) -> usize;
}

impl<H: HodgeComplex + ?Sized> PotentialsDimension for H {
    fn potentials_dimension(&self) -> usize {
        self.d0().cols()
    }
}

#[test]
fn complete_basis_has_2f_fields_and_reconstructs_a_random_field() {
    let sphere = icosphere(1);
    check_complete(
        &Conforming::new(&sphere, MassLumping::Barycentric).unwrap(),
        &sphere,
        "sphere conforming",
    );
    check_complete(
        &Nonconforming::new(&sphere, MassLumping::Barycentric).unwrap(),
        &sphere,
        "sphere nonconforming",
    );
    let ring = torus(2.0, 0.7, 12, 8).unwrap();
    check_complete(
        &Conforming::new(&ring, MassLumping::Voronoi).unwrap(),
        &ring,
        "torus conforming",
    );
    check_complete(
        &Nonconforming::new(&ring, MassLumping::Barycentric).unwrap(),
        &ring,
        "torus nonconforming",
    );
}

#[test]
fn size_requests_select_the_lowest_eigenfields() {
    let mesh = genus_surface(1, 4);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let complete = compute_basis(&complex, &BasisRequest::complete()).unwrap();
    let all = complete.eigenvalues();
    for d in [1, 2, 3, 40, 101] {
        let basis = compute_basis(&complex, &BasisRequest::fields(d)).unwrap();
        assert_eq!(basis.len(), d);
        for (a, b) in basis.eigenvalues().iter().zip(all) {
            assert!((a - b).abs() <= 1e-9 * b.max(1.0), "d = {d}: {a} vs {b}");
        }
    }
    let bound = all[60];
    let basis = compute_basis(&complex, &BasisRequest::max_eigenvalue(bound)).unwrap();
    let expected = all.iter().filter(|&&l| l <= bound * (1.0 + 1e-9)).count();
    assert!(
        basis.len() == expected || basis.len() + 1 == expected,
        "{} vs {expected}",
        basis.len()
    );
    assert!(basis.eigenvalues().iter().all(|&l| l <= bound));
    let basis = compute_basis(&complex, &BasisRequest::max_frequency(0.0)).unwrap();
    assert_eq!(basis.len(), 2);
    assert!(compute_basis(&complex, &BasisRequest::fields(2 * mesh.face_count() + 1)).is_err());
    assert!(compute_basis(&complex, &BasisRequest::max_eigenvalue(-1.0)).is_err());
    let pairs = compute_basis(&complex, &BasisRequest::pairs(5)).unwrap();
    assert_eq!(pairs.count(FieldFamily::Integrable), 5);
    assert_eq!(pairs.count(FieldFamily::Cointegrable), 5);
}

#[test]
fn eigenfunction_form_matches_the_dense_fields() {
    let mesh = genus_surface(2, 4);
    let complex = Nonconforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let request = BasisRequest::pairs(20)
        .keeping_eigenfunctions()
        .with_single_precision_copy();
    let basis = compute_basis(&complex, &request).unwrap();
    let compact = basis.eigenfunctions().unwrap();
    let (same, _) = compute_eigenfunction_basis(&complex, &request).unwrap();
    assert_eq!(same.eigenvalues(), compact.eigenvalues());
    assert_eq!(compact.eigenvalues(), basis.eigenvalues());
    assert!(compact.memory_bytes() * 10 < basis.len() * basis.field_dimension() * 8 * 6);
    let v = random_field(complex.field_dimension(), 3);
    let dense = basis.coefficients(&v).unwrap();
    let sparse = compact.coefficients(&complex, &v).unwrap();
    for (a, b) in dense.iter().zip(&sparse) {
        assert!((a - b).abs() < 1e-11, "{a} vs {b}");
    }
    let from_dense = basis.reconstruct(&dense).unwrap();
    let from_sparse = compact.reconstruct(&complex, &dense).unwrap();
    let from_single = basis.reconstruct_f32(&dense).unwrap();
    let scale = from_dense.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for ((a, b), c) in from_dense.iter().zip(&from_sparse).zip(&from_single) {
        assert!((a - b).abs() < 1e-12 * scale);
        assert!((a - c).abs() < 1e-5 * scale);
    }
    let field = compact.field(&complex, 7);
    for (r, x) in field.iter().enumerate() {
        assert!((x - basis.fields()[(r, 7)]).abs() < 1e-13);
    }
}

#[test]
fn meshes_with_boundary_get_a_complete_orthonormal_basis() {
    let mesh = tvf_core::generate::perforated_plate(1, 4);
    for boundary in tvf_core::discretization::BoundaryCondition::ALL {
        let complex = Conforming::with_boundary(&mesh, MassLumping::Barycentric, boundary).unwrap();
        let basis = compute_basis(&complex, &BasisRequest::complete()).unwrap();
        // An annulus: one harmonic field; the basis spans all 2F fields.
        assert_eq!(basis.report().unwrap().harmonic_dimension, 1);
        assert_eq!(basis.len(), complex.field_dimension());
        let d = basis.len();
        let fields = basis.fields();
        let column = |j: usize| (0..d).map(|r| fields[(r, j)]).collect::<Vec<f64>>();
        for i in (0..d).step_by(7) {
            for j in (0..d).step_by(5) {
                let inner = basis.inner_product(&column(i), &column(j));
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((inner - expected).abs() < 1e-8, "({i},{j}) = {inner}");
            }
        }
    }
}
