//! `Fields(d)` and `MaxEigenvalue(bound)` requests, whose split between the potential and the
//! co-potential family is counted by inertia: the result must be the complete (dense) basis's
//! lowest fields, on meshes of genus 0, 1 and 2, with several components, and with uneven splits.

use tvf_core::discretization::HodgeComplex;
use tvf_core::generate::{genus_surface, icosphere, torus};
use tvf_core::TriangleMesh;
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};
use tvf_spectral::{compute_basis, BasisRequest, FieldFamily, SpectralBasis};

/// The eigenfields a request for `d` fields must return: the lowest `d` of the complete basis.
fn check_fields<H: HodgeComplex + ?Sized>(
    complex: &H,
    complete: &SpectralBasis,
    d: usize,
    what: &str,
) {
    let basis = compute_basis(complex, &BasisRequest::fields(d)).unwrap();
    assert_eq!(basis.len(), d, "{what}, d = {d}");
    for (j, (a, b)) in basis
        .eigenvalues()
        .iter()
        .zip(complete.eigenvalues())
        .enumerate()
    {
        assert!(
            (a - b).abs() <= 1e-10 * b.max(1.0),
            "{what}, d = {d}: eigenvalue {j} is {a}, the complete basis has {b}"
        );
    }
    let expected = |family| {
        complete.families()[..d]
            .iter()
            .filter(|&&f| f == family)
            .count()
    };
    for family in [
        FieldFamily::Harmonic,
        FieldFamily::Integrable,
        FieldFamily::Cointegrable,
    ] {
        assert_eq!(
            basis.count(family),
            expected(family),
            "{what}, d = {d}: {family:?} count"
        );
    }
    let report = basis.report().unwrap();
    assert_eq!(report.eigensolver_calls, 2, "{what}, d = {d}: {report:?}");
    assert!(report.integrable_computed >= report.integrable_count);
    assert!(report.cointegrable_computed >= report.cointegrable_count);
    if let Some(t) = report.split_threshold {
        // Exactly the eigenvalues below the threshold were computed, and the last field kept
        // lies below it.
        assert!(report.counting_factorizations >= 2, "{what}: {report:?}");
        assert!(
            basis.eigenvalues()[d - 1] < t,
            "{what}, d = {d}: {report:?}"
        );
        let below = complete.eigenvalues().iter().filter(|&&l| l > 0.0 && l < t);
        assert_eq!(
            below.count(),
            report.integrable_computed + report.cointegrable_computed,
            "{what}, d = {d}: {report:?}"
        );
    }
}

/// Bounds halfway between consecutive well separated eigenvalues give exactly the fields up to
/// them; a bound above the spectrum gives all fields, a zero bound the harmonic ones.
fn check_bounds<H: HodgeComplex + ?Sized>(complex: &H, complete: &SpectralBasis, what: &str) {
    let all = complete.eigenvalues();
    let harmonic = complete.count(FieldFamily::Harmonic);
    for fraction in [0.05, 0.3, 0.8] {
        let mut j = (fraction * all.len() as f64) as usize;
        while all[j + 1] - all[j] < 1e-6 * all[j + 1] {
            j += 1;
        }
        let bound = 0.5 * (all[j] + all[j + 1]);
        let basis = compute_basis(complex, &BasisRequest::max_eigenvalue(bound)).unwrap();
        assert_eq!(basis.len(), j + 1, "{what}: bound {bound}");
        for (a, b) in basis.eigenvalues().iter().zip(all) {
            assert!((a - b).abs() <= 1e-10 * b.max(1.0), "{what}: {a} vs {b}");
        }
        let report = basis.report().unwrap();
        assert_eq!(
            report.counting_factorizations, 2,
            "{what}: one count of both families: {report:?}"
        );
        assert_eq!(
            report.integrable_computed + report.cointegrable_computed + harmonic,
            j + 1,
            "{what}: nothing above the bound is computed: {report:?}"
        );
    }
    let top = all[all.len() - 1];
    let everything = compute_basis(complex, &BasisRequest::max_eigenvalue(2.0 * top)).unwrap();
    assert_eq!(everything.len(), all.len(), "{what}");
    let none = compute_basis(complex, &BasisRequest::max_eigenvalue(0.0)).unwrap();
    assert_eq!(none.len(), harmonic, "{what}");
}

/// Field counts to check: small, odd, a few hundred, and close to the top of the spectrum where
/// the potential family (`V − c` eigenvalues) runs out and the split is very uneven.
fn sizes(complete: &SpectralBasis) -> Vec<usize> {
    let total = complete.len();
    let h = complete.count(FieldFamily::Harmonic);
    vec![h + 1, h + 37, total / 3, total - total / 20, total - 1]
}

#[test]
fn fields_on_sphere_torus_and_genus_two_match_the_complete_basis() {
    let meshes = [
        ("sphere", icosphere(2)),
        ("torus", torus(1.0, 0.4, 24, 12).unwrap()),
        ("genus 2", genus_surface(2, 4)),
    ];
    for (name, mesh) in &meshes {
        let complex = Conforming::new(mesh, MassLumping::Barycentric).unwrap();
        let complete = compute_basis(&complex, &BasisRequest::complete()).unwrap();
        assert_eq!(complete.len(), 2 * mesh.face_count());
        assert_eq!(complete.count(FieldFamily::Harmonic), 2 * mesh.genus());
        for d in sizes(&complete) {
            check_fields(&complex, &complete, d, name);
        }
    }
    let mesh = torus(1.0, 0.35, 20, 10).unwrap();
    let complex = Nonconforming::new(&mesh, MassLumping::Voronoi).unwrap();
    let complete = compute_basis(&complex, &BasisRequest::complete()).unwrap();
    for d in sizes(&complete) {
        check_fields(&complex, &complete, d, "nonconforming torus");
    }
}

#[test]
fn uneven_splits_are_counted_exactly() {
    // Near the top of the sphere's spectrum nearly all fields are co-integrable (the
    // Crouzeix–Raviart problem has three times the unknowns of the cotan one).
    let mesh = icosphere(2);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let complete = compute_basis(&complex, &BasisRequest::complete()).unwrap();
    let d = 560;
    let basis = compute_basis(&complex, &BasisRequest::fields(d)).unwrap();
    let report = basis.report().unwrap();
    assert!(report.split_threshold.is_some(), "{report:?}");
    assert!(
        report.cointegrable_count > 2 * report.integrable_count,
        "{report:?}"
    );
    check_fields(&complex, &complete, d, "sphere, uneven");
}

#[test]
fn bounds_on_sphere_and_torus_keep_exactly_the_eigenvalues_below_them() {
    for (name, mesh) in [
        ("sphere", icosphere(2)),
        ("torus", torus(1.0, 0.4, 24, 12).unwrap()),
    ] {
        let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
        let complete = compute_basis(&complex, &BasisRequest::complete()).unwrap();
        check_bounds(&complex, &complete, name);
    }
}

/// Two spheres of different sizes and a torus as one mesh.
fn three_components() -> TriangleMesh {
    let parts = [
        (icosphere(2), 1.0, [0.0, 0.0, 0.0]),
        (icosphere(1), 0.6, [3.0, 0.0, 0.0]),
        (torus(1.0, 0.3, 12, 6).unwrap(), 1.0, [0.0, 4.0, 0.0]),
    ];
    let (mut positions, mut faces) = (Vec::new(), Vec::new());
    for (mesh, scale, offset) in &parts {
        let base = positions.len();
        positions.extend(
            mesh.positions()
                .iter()
                .map(|p| [0, 1, 2].map(|i| scale * p[i] + offset[i])),
        );
        faces.extend(mesh.faces().iter().map(|f| f.map(|v| v + base)));
    }
    TriangleMesh::new(positions, faces).unwrap()
}

#[test]
fn several_components_drop_one_kernel_eigenvalue_each() {
    let mesh = three_components();
    assert_eq!(mesh.component_count(), 3);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let complete = compute_basis(&complex, &BasisRequest::complete()).unwrap();
    assert_eq!(complete.count(FieldFamily::Harmonic), 2);
    for d in sizes(&complete) {
        check_fields(&complex, &complete, d, "three components");
    }
    let basis = compute_basis(&complex, &BasisRequest::fields(100)).unwrap();
    let report = basis.report().unwrap();
    assert_eq!(report.potential_kernel_eigenvalues.len(), 3);
    assert_eq!(report.co_potential_kernel_eigenvalues.len(), 3);
    check_bounds(&complex, &complete, "three components");
}

#[test]
fn tiny_meshes_are_solved_completely_without_counting() {
    let mesh = icosphere(1);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let complete = compute_basis(&complex, &BasisRequest::complete()).unwrap();
    for d in [1, 20, 159] {
        check_fields(&complex, &complete, d, "icosphere(1)");
        let basis = compute_basis(&complex, &BasisRequest::fields(d)).unwrap();
        let report = basis.report().unwrap();
        assert_eq!(report.split_threshold, None);
        assert_eq!(report.counting_factorizations, 0);
    }
    assert!(compute_basis(&complex, &BasisRequest::fields(161)).is_err());
}

/// A basis of 300 fields on a mesh large enough for the sparse solver (2562 vertices, 7680
/// edges): every shift is factored once, shared by counting, solving and refinement (the
/// solver's statistics say how many shifts and how many factorizations), refinement factors
/// nothing, and the eigensolver factors neither the threshold again nor any other counted shift.
#[test]
fn a_basis_factors_every_shift_once() {
    let mesh = icosphere(4);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let basis = compute_basis(&complex, &BasisRequest::fields(300)).unwrap();
    let report = basis.report().unwrap();
    let solver = report.solver;
    assert!(report.split_threshold.is_some(), "{report:?}");
    assert!(
        solver.solving.factorizations >= 4,
        "several intervals: {solver:?}"
    );
    assert_eq!(solver.refinement.factorizations, 0, "{solver:?}");
    assert_eq!(report.factorizations, solver.factorizations());
    assert_eq!(
        report.factorizations, report.distinct_shifts,
        "a shift was factored twice: {report:?}"
    );
    // The threshold search's counts are part of the counting phase; the boundaries add the rest.
    assert!(solver.counting.factorizations >= report.counting_factorizations);
    assert!(
        solver.solves() > 0 && report.max_field_residual <= 1e-8,
        "{report:?}"
    );
}
