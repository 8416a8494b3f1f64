//! The full soft-design system under both fill-reducing orderings: the same field, residuals
//! refined below 1e-8, symbolic reuse with nested dissection, and the default ordering.

use crate::common::{max_relative_difference, FullDesignInputs};
use tvf_core::generate::{icosphere, jitter, torus};
use tvf_design::{
    default_regularization, FillOrdering, FullSoftDesign, SoftOptions, DEFAULT_FULL_ORDERING,
};
use tvf_discretizations::{Conforming, MassLumping};

#[test]
fn amd_and_nested_dissection_give_the_same_field() {
    for mesh in [
        jitter(&icosphere(3), 0.25, 3).expect("sphere"),
        torus(1.0, 0.4, 40, 16).expect("torus"),
    ] {
        let FullDesignInputs {
            dirichlet,
            mass,
            options,
            first,
            second,
        } = FullDesignInputs::new(&mesh, 8, (5, 6));
        let design = |ordering| {
            FullSoftDesign::from_matrices_with_ordering(
                &dirichlet,
                &mass,
                options,
                first.clone(),
                ordering,
            )
            .expect("full design")
        };
        let amd = design(FillOrdering::Amd);
        let mut nd = design(FillOrdering::NestedDissection);
        assert_eq!(amd.ordering(), FillOrdering::Amd);
        assert_eq!(nd.ordering(), FillOrdering::NestedDissection);
        assert!(nd.timings().symbolic);
        let (x_amd, report_amd) = amd.solve();
        let (x_nd, report_nd) = nd.solve();
        for report in [&report_amd, &report_nd] {
            assert!(report.final_residual() < 1e-8, "{:?}", report.residuals);
        }
        let difference = max_relative_difference(&x_nd, &x_amd);
        assert!(
            difference < 1e-9,
            "AMD and ND fields differ by {difference:e}"
        );

        // Changing the constraints reuses the nested-dissection analysis when the pattern holds
        // them (vector constraints in faces: diagonal blocks of S), else analyses it anew; either
        // way the refactored system matches a fresh one.
        let reused = nd.set_constraints(second.clone()).expect("refactor");
        assert_eq!(nd.timings().symbolic, !reused);
        assert_eq!(nd.ordering(), FillOrdering::NestedDissection);
        let (x_changed, report) = nd.solve();
        assert!(report.final_residual() < 1e-8, "{:?}", report.residuals);
        let fresh = FullSoftDesign::from_matrices_with_ordering(
            &dirichlet,
            &mass,
            options,
            second.clone(),
            FillOrdering::NestedDissection,
        )
        .expect("fresh design");
        let difference = max_relative_difference(&x_changed, &fresh.solve().0);
        assert!(difference < 1e-9, "refactored vs fresh: {difference:e}");
    }
}

#[test]
fn default_ordering_is_used_by_new() {
    let mesh = icosphere(2);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).expect("complex");
    let options = SoftOptions {
        omega: 0.1,
        regularization: default_regularization(&complex),
    };
    let design = FullSoftDesign::new(&complex, options, Vec::new()).expect("full design");
    assert_eq!(design.ordering(), DEFAULT_FULL_ORDERING);
    assert!(design.factor_entries() > 0 && design.factor_flop_count() > 0.0);
}
