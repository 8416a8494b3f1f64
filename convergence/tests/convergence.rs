//! The convergence study against exact spectra: the P1 and Crouzeix–Raviart families converge
//! at order 2 on the unit sphere and the hemisphere, and a candidate that cannot be built stops
//! the study with its name.

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
