//! Reduced tangential vector field splines: hard constraints, convergence to the full spline,
//! dependent constraints, editing.

use crate::common::{mixed_constraints, relative_difference, spectral_basis, truncated};
use tvf_core::discretization::HodgeComplex;
use tvf_core::generate::{genus_surface, icosphere, jitter};
use tvf_design::{
    reference_spline, Constraint, ConstraintAssembler, DesignError, Location, ReducedBasis,
    SplineSession, Target,
};
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};

const OMEGA: f64 = 0.1;

fn check_hard_constraints<H: HodgeComplex + ?Sized>(
    name: &str,
    complex: &H,
    mesh: &tvf_core::TriangleMesh,
    d: usize,
) {
    let basis = truncated(&spectral_basis(complex, None), d);
    let assembler = ConstraintAssembler::new(complex, mesh);
    let constraints = assembler
        .compile_all(&mixed_constraints(mesh, 8, 7))
        .expect("valid constraints");
    let mut session = SplineSession::new(&basis, OMEGA).expect("session");
    for c in constraints {
        session.add(c).expect("independent constraints");
    }
    let field = session.field();
    assert!(field.iter().all(|x| x.is_finite()));
    for r in session.residuals(&field) {
        println!(
            "{name}: constraint {} relative residual {:.2e}",
            r.id, r.relative
        );
        assert!(
            r.relative < 1e-9,
            "{name}: constraint {} has relative residual {:e}",
            r.id,
            r.relative
        );
    }
}

#[test]
fn reduced_splines_meet_every_hard_constraint_on_genus_0_to_3() {
    let sphere = jitter(&icosphere(2), 0.2, 3).expect("jittered sphere");
    let meshes = [
        ("genus 0", sphere),
        ("genus 1", genus_surface(1, 4)),
        ("genus 2", genus_surface(2, 4)),
        ("genus 3", genus_surface(3, 4)),
    ];
    for (name, mesh) in &meshes {
        assert_eq!(
            mesh.genus(),
            name.trim_start_matches("genus ").parse::<usize>().unwrap()
        );
        let complex = Conforming::new(mesh, MassLumping::Barycentric).expect("complex");
        check_hard_constraints(name, &complex, mesh, 120);
    }
    let (name, mesh) = &meshes[1];
    let complex = Nonconforming::new(mesh, MassLumping::Barycentric).expect("complex");
    // Nonconforming: divergence lives on edges, curl on vertices; the mixed set uses the other keys.
    let assembler = ConstraintAssembler::new(&complex, mesh);
    let error = assembler
        .compile_all(&mixed_constraints(mesh, 8, 7))
        .unwrap_err();
    assert!(error.to_string().contains("source"), "{error}");
    let swapped: Vec<Constraint> = mixed_constraints(mesh, 8, 7)
        .into_iter()
        .map(|c| match c.location {
            Location::Vertex(_) | Location::Edge(_) => {
                c.with_family(tvf_design::OperatorFamily::Other)
            }
            _ => c,
        })
        .collect();
    let basis = truncated(&spectral_basis(&complex, None), 120);
    let mut session = SplineSession::new(&basis, OMEGA).expect("session");
    for c in assembler
        .compile_all(&swapped)
        .expect("valid with the other family")
    {
        session.add(c).expect("independent");
    }
    let field = session.field();
    for r in session.residuals(&field) {
        assert!(
            r.relative < 1e-9,
            "nonconforming {name}: {} residual {:e}",
            r.id,
            r.relative
        );
    }
}

#[test]
fn reduced_spline_approaches_the_full_spline_as_d_grows() {
    let mesh = jitter(&icosphere(2), 0.2, 11).expect("mesh");
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).expect("complex");
    let full_basis = spectral_basis(&complex, None);
    let assembler = ConstraintAssembler::new(&complex, &mesh);
    let constraints = assembler
        .compile_all(&mixed_constraints(&mesh, 6, 5))
        .expect("constraints");
    let reference = reference_spline(&complex, OMEGA, 0.0, &constraints).expect("full spline");
    for report in &reference.solve_reports {
        assert!(
            report.final_residual() < 1e-10,
            "reference solve residual {:e}",
            report.final_residual()
        );
    }
    let mut errors = Vec::new();
    println!("      d   relative M_X difference to the full spline");
    for d in [40, 80, 160, 320, 480, 640] {
        let basis = truncated(&full_basis, d);
        let mut session = SplineSession::new(&basis, OMEGA).expect("session");
        for c in constraints.clone() {
            session.add(c).expect("independent");
        }
        let error = relative_difference(
            &session.field(),
            &reference.field,
            complex.m1().diagonal_values().unwrap(),
        );
        println!("  {d:5}   {error:.3e}");
        errors.push(error);
    }
    assert!(
        errors.windows(2).all(|w| w[1] <= w[0] * 1.05),
        "not approaching: {errors:?}"
    );
    assert!(errors[2] < 0.5 * errors[0], "{errors:?}");
    // The complete basis spans X_h: the reduced spline is the full one.
    assert!(*errors.last().unwrap() < 1e-7, "{errors:?}");
}

fn sphere_session_setup() -> (tvf_core::TriangleMesh, Conforming, ReducedBasis) {
    let mesh = icosphere(1);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).expect("complex");
    let basis = ReducedBasis::from_spectral(&spectral_basis(&complex, None)).expect("basis");
    (mesh, complex, basis)
}

#[test]
fn the_same_vector_twice_is_reported_by_id() {
    let (mesh, complex, basis) = sphere_session_setup();
    let assembler = ConstraintAssembler::new(&complex, &mesh);
    let at = Location::Face {
        face: 3,
        barycentric: None,
    };
    let first = assembler
        .compile(&Constraint::new(
            "first",
            Target::Vector([1.0, 0.0, 0.0]),
            at.clone(),
        ))
        .unwrap();
    let clash = assembler
        .compile(&Constraint::new(
            "clash",
            Target::Vector([0.0, 1.0, 0.0]),
            at.clone(),
        ))
        .unwrap();
    let again = assembler
        .compile(&Constraint::new(
            "again",
            Target::Vector([1.0, 0.0, 0.0]),
            at,
        ))
        .unwrap();
    let mut session = SplineSession::new(&basis, OMEGA).unwrap();
    session.add(first).unwrap();
    let before = session.field();
    match session.add(clash) {
        Err(DesignError::Dependent {
            id,
            involved,
            conflicting,
            ..
        }) => {
            assert_eq!(id, "clash");
            assert_eq!(involved, vec!["first".to_string()]);
            assert!(conflicting);
        }
        other => panic!("expected a dependency error, got {other:?}"),
    }
    match session.add(again) {
        Err(DesignError::Dependent {
            id, conflicting, ..
        }) => {
            assert_eq!(id, "again");
            assert!(!conflicting, "same value: redundant, not conflicting");
        }
        other => panic!("expected a dependency error, got {other:?}"),
    }
    // The failed adds left the session unchanged.
    assert_eq!(session.ids(), vec!["first"]);
    assert_eq!(session.row_count(), 2);
    assert_eq!(session.field(), before);
}

#[test]
fn a_dependent_set_of_divergences_is_detected_and_never_gives_nan() {
    // Σ_i M_i (div x)_i = 0 on a closed surface: the divergence rows at all vertices are dependent.
    let (mesh, complex, basis) = sphere_session_setup();
    let assembler = ConstraintAssembler::new(&complex, &mesh);
    let mut session = SplineSession::new(&basis, OMEGA).unwrap();
    let mut rejected = Vec::new();
    for v in 0..mesh.vertex_count() {
        let c = Constraint::new(
            format!("div{v}"),
            Target::Divergence(1.0),
            Location::Vertex(v),
        );
        match session.add(assembler.compile(&c).unwrap()) {
            Ok(()) => {}
            Err(DesignError::Dependent {
                id,
                involved,
                conflicting,
                ..
            }) => {
                assert!(conflicting, "all values 1 cannot integrate to 0");
                assert!(involved.len() > 1);
                rejected.push(id);
            }
            Err(other) => panic!("unexpected error {other}"),
        }
    }
    assert_eq!(rejected, vec![format!("div{}", mesh.vertex_count() - 1)]);
    assert!(session.field().iter().all(|x| x.is_finite()));
}

#[test]
fn editing_matches_a_fresh_session() {
    let (mesh, complex, basis) = sphere_session_setup();
    let assembler = ConstraintAssembler::new(&complex, &mesh);
    let all = assembler
        .compile_all(&mixed_constraints(&mesh, 5, 9))
        .unwrap();
    let mut session = SplineSession::new(&basis, OMEGA).unwrap();
    for c in all.clone() {
        session.add(c).unwrap();
    }
    session.remove("v1").unwrap();
    session.remove("vortex").unwrap();
    let mut moved = all[3].clone();
    moved.values = vec![0.25, -0.75];
    session.modify(moved.clone()).unwrap();
    assert!(matches!(
        session.remove("v1"),
        Err(DesignError::UnknownId { .. })
    ));
    assert!(matches!(
        session.add(all[0].clone()),
        Err(DesignError::DuplicateId { .. })
    ));

    let mut fresh = SplineSession::new(&basis, OMEGA).unwrap();
    for c in &all {
        if c.id == "v1" || c.id == "vortex" {
            continue;
        }
        fresh
            .add(if c.id == moved.id {
                moved.clone()
            } else {
                c.clone()
            })
            .unwrap();
    }
    let (a, b) = (session.field(), fresh.field());
    let difference = relative_difference(&a, &b, complex.m1().diagonal_values().unwrap());
    assert!(difference < 1e-10, "edited vs fresh: {difference:e}");
    for r in session.residuals(&a) {
        assert!(r.relative < 1e-9, "{} {:e}", r.id, r.relative);
    }
}

#[test]
fn single_precision_map_agrees_with_double() {
    let (mesh, complex, basis) = sphere_session_setup();
    let assembler = ConstraintAssembler::new(&complex, &mesh);
    let mut session = SplineSession::new(&basis, OMEGA).unwrap();
    for c in assembler
        .compile_all(&mixed_constraints(&mesh, 4, 1))
        .unwrap()
    {
        session.add(c).unwrap();
    }
    let v = session.solve();
    let x = session.field();
    let single = basis.to_f32().unwrap();
    let v32: Vec<f32> = v.iter().map(|&a| a as f32).collect();
    let mut x32 = vec![0.0f32; x.len()];
    single.map(&v32, &mut x32).unwrap();
    let x32: Vec<f64> = x32.iter().map(|&a| a as f64).collect();
    let difference = relative_difference(&x32, &x, complex.m1().diagonal_values().unwrap());
    assert!(difference < 1e-5, "f32 vs f64 map: {difference:e}");
    assert!(basis.map(&v[1..], &mut vec![0.0; x.len()]).is_err());
}

/// A spline and a reduced soft design in a basis file read in blocks (only the rows of `U` the
/// constraints touch held, [`ReducedBasis::from_field_basis`]) against the same file loaded
/// whole: the reduced coefficients bit for bit (the rows are the loaded basis's, summed in the
/// same order), the fields to round-off (`1e-13` of the largest coefficient: the synthesis
/// sums in another order); a lumped and a Galerkin (non-diagonal `M1`: co-integrable rows by
/// mass solves, to round-off, so the coefficients and fields to `1e-11` relative: the
/// constrained solve amplifies the rows' round-off) complex; a constraint touching a row that
/// was not read is refused.
#[test]
fn splines_and_reduced_designs_in_a_basis_file_read_in_blocks_equal_the_loaded_basis() {
    use std::sync::Arc;
    use tvf_core::discretization::HodgeOperators;
    use tvf_design::{timed_reduced_design, timed_spline, SoftOptions};
    use tvf_discretizations::{BoxedComplex, WhitneyGalerkin};
    use tvf_spectral::{load_basis, save_computed_basis, BasisFileBlocks, BasisFileKey};

    let dir = tempfile::tempdir().unwrap();
    let mesh = genus_surface(1, 4);
    let lumped: BoxedComplex = Box::new(Conforming::new(&mesh, MassLumping::Barycentric).unwrap());
    let galerkin: BoxedComplex = Box::new(WhitneyGalerkin::new(&mesh).unwrap());
    for (name, complex, exact) in [("lumped", lumped, true), ("galerkin", galerkin, false)] {
        let path = dir.path().join(format!("{name}.tvfb"));
        let key = BasisFileKey::new(&mesh, complex.as_ref());
        let request = tvf_spectral::BasisRequest::fields(80);
        save_computed_basis(&path, complex.as_ref(), &request, &key).unwrap();
        let loaded = load_basis(&path, &key, complex.as_ref()).unwrap();
        // The constraints the complex takes (Whitney forms have no curl at an edge).
        let compiled = |seed| -> Vec<_> {
            let assembler = ConstraintAssembler::new(complex.as_ref(), &mesh);
            let all = mixed_constraints(&mesh, 6, seed);
            all.iter()
                .filter_map(|c| assembler.compile(c).ok())
                .collect()
        };
        let constraints = compiled(11);
        assert!(constraints.len() >= 6);
        // A vector at a face no constraint touches (on this small mesh the Galerkin
        // divergence's row, through the Whitney mass, touches nearly every edge: lumped only).
        let assembler = ConstraintAssembler::new(complex.as_ref(), &mesh);
        let touched = ReducedBasis::touched_rows(&constraints);
        let faces = if exact { 0..mesh.face_count() } else { 0..0 };
        let untouched = faces
            .map(|face| {
                let location = Location::Face {
                    face,
                    barycentric: None,
                };
                let far = Constraint::new("far", Target::Vector([1.0, 0.0, 0.0]), location);
                assembler.compile(&far).unwrap()
            })
            .find(|c| c.rows.iter().flatten().all(|(j, _)| !touched.contains(j)));
        let whole = ReducedBasis::from_spectral(&loaded).unwrap();
        let n1 = complex.field_dimension();
        let blocks = BasisFileBlocks::open(&path, &key, complex)
            .unwrap()
            .unwrap();
        let blocks = ReducedBasis::from_field_basis(Arc::new(blocks), &constraints).unwrap();
        assert_eq!(blocks.eigenvalues(), whole.eigenvalues());
        assert_eq!(blocks.harmonic(), whole.harmonic());

        let solve = |basis: &ReducedBasis| {
            let mut session = SplineSession::new(basis, OMEGA).unwrap();
            for c in constraints.iter().cloned() {
                session.add(c).unwrap();
            }
            session.solve()
        };
        let (expected, found) = (solve(&whole), solve(&blocks));
        if exact {
            assert_eq!(found, expected, "{name}: reduced spline coefficients");
        } else {
            let scale = expected.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let worst = found
                .iter()
                .zip(&expected)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(
                worst <= 1e-11 * scale,
                "{name}: coefficients differ by {worst:e}"
            );
        }
        // The synthesis's round-off alone (1e-13), or with the coefficients' (1e-11).
        let tolerance = if exact { 1e-13 } else { 1e-11 };
        let close = |a: &[f64], b: &[f64]| {
            let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let worst = a
                .iter()
                .zip(b)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            println!(
                "{name}: fields differ by {:.1e} of the largest",
                worst / scale
            );
            worst <= tolerance * scale
        };
        let spline = timed_spline(&blocks, OMEGA, &constraints).unwrap();
        let spline_whole = timed_spline(&whole, OMEGA, &constraints).unwrap();
        assert!(
            close(&spline.field, &spline_whole.field),
            "{name}: spline field"
        );
        let options = SoftOptions {
            omega: OMEGA,
            regularization: 1e-3,
        };
        let design = timed_reduced_design(&blocks, options, &constraints).unwrap();
        let design_whole = timed_reduced_design(&whole, options, &constraints).unwrap();
        assert!(
            close(&design.field, &design_whole.field),
            "{name}: design field"
        );
        assert_eq!(spline.field.len(), n1);

        if exact {
            let untouched = untouched.expect("a face whose rows no constraint touches");
            let mut session = SplineSession::new(&blocks, OMEGA).unwrap();
            let error = session.add(untouched).unwrap_err();
            assert!(error.to_string().contains("not read"), "{error}");
        }
    }
}
