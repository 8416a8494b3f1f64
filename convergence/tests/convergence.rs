//! The convergence study against exact spectra: the P1 and Crouzeix–Raviart families converge
//! at order 2 on the unit sphere and the hemisphere, polygon-dec converges on the quad sphere
//! and hemisphere, and a candidate that cannot be built stops the study with its name.

use tvf_convergence::study::{run_convergence, Candidate, ConvergenceConfig, Surface};
use tvf_core::discretization::BoundaryCondition;
use tvf_core::TriangleMesh;
use tvf_discretizations::Catalog;
use tvf_spectral::FieldFamily;

#[test]
fn p1_and_crouzeix_raviart_converge_at_order_two() {
    let catalog = Catalog::builtin();
    let candidates = ["conforming-barycentric", "nonconforming-barycentric"]
        .map(|id| Candidate::from_entry(catalog.get(id).unwrap()));
    let config = ConvergenceConfig {
        surfaces: Surface::all(),
        levels: vec![2, 3, 4],
        eigenvalues: 8,
    };
    let report = run_convergence(&candidates, &config, &|_, _, _| {}).unwrap();
    assert_eq!(report.rows.len(), 2 * 3 * 3);
    assert_eq!(report.orders.len(), 2 * 3 * 2);
    for order in &report.orders {
        assert!((order.order - 2.0).abs() <= 0.2, "{order:?}");
    }
    // The finest sphere level is within 1 % for both families.
    let finest = report
        .rows
        .iter()
        .find(|r| r.surface == Surface::Sphere && r.level == 4)
        .unwrap();
    assert!(finest.error(FieldFamily::Integrable) < 1e-2, "{finest:?}");
    assert!(finest.error(FieldFamily::Cointegrable) < 1e-2, "{finest:?}");
}

#[test]
fn a_candidate_that_cannot_be_built_is_named() {
    let candidates = [Candidate::new(
        "draft",
        |_: &TriangleMesh, _: BoundaryCondition| Err("no assembly yet".to_string()),
    )];
    let error = run_convergence(&candidates, &ConvergenceConfig::default(), &|_, _, _| {})
        .err()
        .unwrap()
        .to_string();
    assert!(
        error.contains("draft") && error.contains("no assembly yet"),
        "{error}"
    );
}

#[test]
fn polygon_dec_converges_on_the_quad_sphere_and_hemisphere() {
    let catalog = Catalog::builtin();
    let candidates = [Candidate::from_entry(catalog.get("polygon-dec").unwrap())];
    let config = ConvergenceConfig {
        surfaces: Surface::all_quads(),
        levels: vec![1, 2, 3, 4],
        eigenvalues: 8,
    };
    let report = run_convergence(&candidates, &config, &|_, _, _| {}).unwrap();
    for row in &report.rows {
        eprintln!("{}", row.summary());
    }
    for order in &report.orders {
        eprintln!("{order:?}");
    }
    assert_eq!(report.rows.len(), 3 * 4);
    assert_eq!(report.orders.len(), 3 * 2);
    assert!(report.rows.iter().all(|r| r.surface.has_quads()));
    for order in &report.orders {
        assert!((order.order - 2.0).abs() <= 0.2, "{order:?}");
    }
}

#[test]
fn a_triangle_entry_is_refused_on_the_quad_sphere_with_its_name() {
    let catalog = Catalog::builtin();
    let candidates = [Candidate::from_entry(
        catalog.get("conforming-barycentric").unwrap(),
    )];
    let config = ConvergenceConfig {
        surfaces: vec![Surface::QuadSphere],
        levels: vec![1],
        eigenvalues: 4,
    };
    let error = run_convergence(&candidates, &config, &|_, _, _| {})
        .err()
        .unwrap()
        .to_string();
    assert!(
        error.contains("conforming-barycentric") && error.contains("quad-sphere"),
        "{error}"
    );
}
