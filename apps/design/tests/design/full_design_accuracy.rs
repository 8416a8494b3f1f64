//! The full soft design of the catalog's entries with non-diagonal masses reaches `tvf design
//! --full`'s target on meshes of a few thousand faces also for a smooth design (large `ω`),
//! where the refinement stalls unless the factored augmented system is an accurate solver:
//! polygon-dec on a quad torus (a diagonal `M0`, a sparse `M1`: the potential term of `S` stays
//! in the field block, so the direct solve is accurate by itself), and whitney-galerkin,
//! conforming-consistent and nonconforming-consistent on a triangle torus (a term of `S` through
//! auxiliary unknowns: factored with a larger screening, which the refinement removes). With the
//! field block singular up to `εM1` on the gradients, these solves stalled at relative residuals
//! of 1e-2 (polygon-dec) and 5e-2 (whitney-galerkin).

use crate::common::node_location;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::generate::{quad_torus, torus};
use tvf_core::mesh::Mesh;
use tvf_core::SurfaceMesh;
use tvf_design::{
    default_regularization, CompiledConstraint, Constraint, ConstraintAssembler, FullSoftDesign,
    Location, SoftOptions, SolveReport, Target, FULL_SOLVE_TARGET,
};
use tvf_discretizations::catalog_entry;

/// A vector at a point of the first face and one in a face halfway around, a divergence at a
/// potential node and a curl at a co-potential node, as `tvf design` reads them.
fn constraints<M: Mesh + ?Sized>(
    complex: &dyn HodgeComplex,
    mesh: &M,
    faces: usize,
    corners: usize,
) -> Vec<CompiledConstraint> {
    let mut weights = vec![0.5 / (corners - 1) as f64; corners];
    weights[0] = 0.5;
    let (potentials, co_potentials) = (complex.potential_nodes(), complex.co_potential_nodes());
    let list = [
        Constraint::new(
            "a",
            Target::Vector([1.0, 0.0, 0.0]),
            Location::Face {
                face: 0,
                barycentric: Some(weights),
            },
        ),
        Constraint::new(
            "b",
            Target::Vector([0.0, 1.0, 0.0]),
            Location::Face {
                face: faces / 2 + 7,
                barycentric: None,
            },
        ),
        Constraint::new(
            "source",
            Target::Divergence(2.0),
            node_location(potentials, potentials.len() / 3),
        ),
        Constraint::new(
            "vortex",
            Target::Curl(-1.5),
            node_location(co_potentials, co_potentials.len() / 4),
        ),
    ];
    ConstraintAssembler::new(complex, mesh)
        .compile_all(&list)
        .expect("valid constraints")
}

/// The refined full design of `complex` for `constraints` at smoothness `omega`: its report,
/// checked against the target of `tvf design --full`.
fn refined(
    name: &str,
    complex: &dyn HodgeComplex,
    constraints: &[CompiledConstraint],
    omega: f64,
) -> SolveReport {
    let options = SoftOptions {
        omega,
        regularization: default_regularization(complex),
    };
    let design = FullSoftDesign::new(complex, options, constraints.to_vec()).expect("design");
    let (x, report) = design.solve();
    println!(
        "{name}, ω = {omega}: {} unknowns, residuals {:?}, rounding floor {:.1e}, {:.2} Gflop",
        x.len(),
        report.residuals,
        report.rounding_floor,
        design.factor_flop_count() / 1e9
    );
    assert!(x.iter().all(|v| v.is_finite()), "{name}: non-finite field");
    assert_eq!(x.len(), complex.field_dimension());
    assert!(
        report.meets(FULL_SOLVE_TARGET),
        "{name}, ω = {omega}: residuals {:?}, floor {:e}",
        report.residuals,
        report.rounding_floor
    );
    report
}

#[test]
fn polygon_dec_full_design_is_accurate_from_the_factorization() {
    let mesh = SurfaceMesh::from(quad_torus(1.0, 0.4, 96, 32).expect("quad torus"));
    let complex = catalog_entry("polygon-dec")
        .expect("entry")
        .build(&mesh)
        .expect("polygon-dec");
    assert!(complex.m0().is_diagonal() && !complex.m1().is_diagonal());
    let compiled = constraints(complex.as_ref(), &mesh, mesh.face_count(), 4);
    for omega in [0.1, 100.0] {
        let report = refined("polygon-dec", complex.as_ref(), &compiled, omega);
        // The direct solve alone is within a few digits of the floor (1e-10 at ω = 100).
        assert!(
            report.residuals[0] < 1e-8 && report.residuals.len() <= 5,
            "ω = {omega}: residuals {:?}",
            report.residuals
        );
    }
}

#[test]
fn full_designs_through_auxiliary_unknowns_reach_the_target() {
    let mesh = SurfaceMesh::from(torus(1.0, 0.4, 96, 32).expect("torus"));
    for id in [
        "whitney-galerkin",
        "conforming-consistent",
        "nonconforming-consistent",
    ] {
        let complex = catalog_entry(id).expect("entry").build(&mesh).expect(id);
        let compiled = constraints(complex.as_ref(), &mesh, mesh.face_count(), 3);
        for omega in [0.1, 100.0] {
            let report = refined(id, complex.as_ref(), &compiled, omega);
            assert!(
                report.residuals.len() <= 12,
                "{id}, ω = {omega}: residuals {:?}",
                report.residuals
            );
        }
    }
}
