//! Soft-constrained design (Fisher et al.): full vs reduced, symbolic reuse, residuals, and the
//! trade-off against hard constraints.

use crate::common::{mixed_constraints, relative_difference, spectral_basis, truncated};
use tvf_core::discretization::HodgeComplex;
use tvf_core::generate::{icosphere, jitter, torus};
use tvf_design::{
    default_regularization, CompiledConstraint, ConstraintAssembler, FullSoftDesign,
    ReducedSoftDesign, SoftOptions, SplineSession,
};
use tvf_discretizations::{Conforming, MassLumping};

fn options(complex: &Conforming, omega: f64) -> SoftOptions {
    SoftOptions {
        omega,
        regularization: default_regularization(complex),
    }
}

fn full_vs_reduced(mesh: &tvf_core::TriangleMesh, sizes: &[usize]) -> Vec<f64> {
    let complex = Conforming::new(mesh, MassLumping::Barycentric).expect("complex");
    let opts = options(&complex, 0.01);
    let assembler = ConstraintAssembler::new(&complex, mesh);
    let constraints = assembler
        .compile_all(&mixed_constraints(mesh, 6, 21))
        .expect("constraints");
    let full = FullSoftDesign::new(&complex, opts, constraints.clone()).expect("full design");
    let (x_full, report) = full.solve();
    assert!(
        report.final_residual() < 1e-8,
        "full residual {:?}",
        report.residuals
    );
    let complete = spectral_basis(&complex, None);
    let mut errors = Vec::new();
    for &d in sizes {
        let basis = truncated(&complete, d);
        let mut reduced = ReducedSoftDesign::new(&basis, opts).expect("reduced design");
        reduced.add_all(constraints.clone()).expect("updates");
        let error = relative_difference(
            &reduced.field(),
            &x_full,
            complex.m1().diagonal_values().unwrap(),
        );
        println!(
            "  genus {}  d = {d:4}  relative difference {error:.3e}",
            mesh.genus()
        );
        errors.push(error);
    }
    errors
}

#[test]
fn full_and_reduced_soft_design_agree_as_d_grows() {
    let sphere = jitter(&icosphere(2), 0.2, 4).expect("mesh");
    let errors = full_vs_reduced(&sphere, &[40, 160, 320, 640]);
    assert!(errors.windows(2).all(|w| w[1] <= w[0] * 1.05), "{errors:?}");
    assert!(*errors.last().unwrap() < 1e-8, "{errors:?}");
    // Genus 1: the harmonic fields are held by ε and the constraints in both systems alike.
    let ring = torus(1.0, 0.45, 16, 8).expect("torus");
    let errors = full_vs_reduced(&ring, &[64, 128, 256, 512]);
    assert!(errors.windows(2).all(|w| w[1] <= w[0] * 1.05), "{errors:?}");
    assert!(*errors.last().unwrap() < 1e-8, "{errors:?}");
}

#[test]
fn soft_constraints_trade_off_while_hard_ones_hold() {
    let mesh = jitter(&icosphere(2), 0.2, 8).expect("mesh");
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).expect("complex");
    let assembler = ConstraintAssembler::new(&complex, &mesh);
    let constraints = assembler
        .compile_all(&mixed_constraints(&mesh, 6, 2))
        .expect("constraints");
    let complete = spectral_basis(&complex, None);
    let basis = truncated(&complete, 640);

    let full = FullSoftDesign::new(&complex, options(&complex, 0.1), constraints.clone()).unwrap();
    let (soft, _) = full.solve();
    let soft_worst = constraints
        .iter()
        .map(|c| tvf_design::residual(c, &soft).relative)
        .fold(0.0, f64::max);

    let mut spline = SplineSession::new(&basis, 0.1).unwrap();
    for c in constraints.clone() {
        spline.add(c).unwrap();
    }
    let hard = spline.field();
    let hard_worst = spline
        .residuals(&hard)
        .iter()
        .map(|r| r.relative)
        .fold(0.0, f64::max);
    println!("worst relative residual: soft {soft_worst:.3e}, hard {hard_worst:.3e}");
    assert!(
        soft_worst > 1e-2,
        "soft design should not meet every constraint exactly: {soft_worst:e}"
    );
    assert!(hard_worst < 1e-9, "{hard_worst:e}");

    // Raising the weight of every constraint pulls the soft design towards the constraints.
    let heavy: Vec<CompiledConstraint> = constraints
        .iter()
        .cloned()
        .map(|c| CompiledConstraint { weight: 1e4, ..c })
        .collect();
    let heavy_design =
        FullSoftDesign::new(&complex, options(&complex, 0.1), heavy.clone()).unwrap();
    let (x, report) = heavy_design.solve();
    assert!(report.final_residual() < 1e-8);
    let heavy_worst = heavy
        .iter()
        .map(|c| tvf_design::residual(c, &x).relative)
        .fold(0.0, f64::max);
    assert!(
        heavy_worst < 0.1 * soft_worst,
        "heavy {heavy_worst:e} vs {soft_worst:e}"
    );
}

#[test]
fn changing_constraints_reuses_the_symbolic_factorization() {
    let mesh = icosphere(2);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).expect("complex");
    let assembler = ConstraintAssembler::new(&complex, &mesh);
    let first = assembler
        .compile_all(&mixed_constraints(&mesh, 5, 1))
        .unwrap();
    let second = assembler
        .compile_all(&mixed_constraints(&mesh, 7, 2))
        .unwrap();
    // ω > 0: B's pattern holds every constraint block.
    let mut design = FullSoftDesign::new(&complex, options(&complex, 0.1), first.clone()).unwrap();
    assert!(design.set_constraints(second.clone()).unwrap());
    assert_eq!(design.symbolic_analyses(), 1);
    let (x, report) = design.solve();
    let fresh = FullSoftDesign::new(&complex, options(&complex, 0.1), second.clone()).unwrap();
    let (y, _) = fresh.solve();
    assert!(report.final_residual() < 1e-8);
    assert!(relative_difference(&x, &y, complex.m1().diagonal_values().unwrap()) < 1e-10);
    // ω = 0: the pattern of S couples faces sharing a vertex, but a P1 divergence at a point mixes
    // three vertex one-rings, whose faces need not share a vertex; the pattern grows once, then is
    // reused.
    let point = tvf_design::Constraint::new(
        "div-point",
        tvf_design::Target::Divergence(1.0),
        tvf_design::Location::Face {
            face: 7,
            barycentric: Some(vec![0.3, 0.3, 0.4]),
        },
    );
    let first = vec![assembler.compile(&point).unwrap()];
    let mut dirichlet_only =
        FullSoftDesign::new(&complex, options(&complex, 0.0), Vec::new()).unwrap();
    assert!(!dirichlet_only.set_constraints(first.clone()).unwrap());
    assert_eq!(dirichlet_only.symbolic_analyses(), 2);
    assert!(dirichlet_only.set_constraints(Vec::new()).unwrap());
    assert!(dirichlet_only.set_constraints(first).unwrap());
    assert_eq!(dirichlet_only.symbolic_analyses(), 2);
}

#[test]
fn reduced_soft_design_updates_match_a_fresh_factorization() {
    let mesh = icosphere(1);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).expect("complex");
    let basis = truncated(&spectral_basis(&complex, None), 120);
    let assembler = ConstraintAssembler::new(&complex, &mesh);
    let all = assembler
        .compile_all(&mixed_constraints(&mesh, 6, 3))
        .unwrap();
    let opts = options(&complex, 0.1);
    let mut edited = ReducedSoftDesign::new(&basis, opts).unwrap();
    edited.add_all(all.clone()).unwrap();
    edited.remove("v2").unwrap();
    edited.remove("source").unwrap();
    edited.set_values("v0", &[0.5, 0.5]).unwrap();
    // Values that are not finite, or of the wrong count, are refused and change nothing.
    assert!(edited.set_values("v0", &[f64::NAN, 0.5]).is_err());
    assert!(edited.set_values("v0", &[0.5]).is_err());
    let mut fresh = ReducedSoftDesign::new(&basis, opts).unwrap();
    for c in all.iter().filter(|c| c.id != "v2" && c.id != "source") {
        let mut c = c.clone();
        if c.id == "v0" {
            c.values = vec![0.5, 0.5];
        }
        fresh.add(c).unwrap();
    }
    let (a, b) = (edited.solve(), fresh.solve());
    let difference = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
        / b.iter().map(|y| y * y).sum::<f64>().sqrt();
    assert!(difference < 1e-10, "{difference:e}");
}
