//! The threading of the full soft-design factorization: sequential and parallel factors give the
//! same field to round-off, the automatic choice is sequential for small systems, and the choice
//! survives a change of constraints.

use crate::common::{max_relative_difference, FullDesignInputs};
use faer::Par;
use tvf_core::generate::{icosphere, jitter};
use tvf_design::{FactorParallelism, FillOrdering, FullSoftDesign, SEQUENTIAL_FLOP_LIMIT};

#[test]
fn the_policy_maps_flops_to_threads() {
    let automatic = FactorParallelism::default();
    assert_eq!(
        automatic,
        FactorParallelism::Auto {
            sequential_flop_limit: SEQUENTIAL_FLOP_LIMIT
        }
    );
    assert_eq!(automatic.choose(0.5 * SEQUENTIAL_FLOP_LIMIT), Par::Seq);
    assert_eq!(
        automatic.choose(2.0 * SEQUENTIAL_FLOP_LIMIT),
        faer::get_global_parallelism()
    );
    let lower = FactorParallelism::Auto {
        sequential_flop_limit: 1e3,
    };
    assert_eq!(lower.choose(1e4), faer::get_global_parallelism());
    assert_eq!(FactorParallelism::Sequential.choose(1e15), Par::Seq);
    assert_eq!(FactorParallelism::Parallel.choose(1.0), Par::rayon(0));
}

#[test]
fn sequential_and_parallel_factors_give_the_same_field() {
    let mesh = jitter(&icosphere(4), 0.2, 11).expect("sphere");
    let FullDesignInputs {
        dirichlet,
        mass,
        options,
        first,
        second,
    } = FullDesignInputs::new(&mesh, 10, (1, 2));
    let design = |parallelism| {
        FullSoftDesign::from_matrices_with(
            &dirichlet,
            &mass,
            options,
            first.clone(),
            FillOrdering::NestedDissection,
            parallelism,
        )
        .expect("full design")
    };
    let automatic = design(FactorParallelism::default());
    let mut sequential = design(FactorParallelism::Sequential);
    let mut parallel = design(FactorParallelism::Parallel);
    // Large enough that the factor's values are zeroed by several threads (≥ 2^20 values).
    assert!(sequential.factor_entries() >= 1 << 20);
    assert!(automatic.factor_flop_count() < SEQUENTIAL_FLOP_LIMIT);
    assert!(!automatic.is_parallel());
    assert!(!sequential.is_parallel());
    assert!(parallel.is_parallel());
    assert_eq!(
        sequential.factor_entries(),
        parallel.factor_entries(),
        "threading must not change the analysis"
    );

    let compare = |a: &FullSoftDesign, b: &FullSoftDesign| {
        let (x, report_a) = a.solve();
        let (y, report_b) = b.solve();
        for report in [&report_a, &report_b] {
            assert!(report.final_residual() < 1e-8, "{:?}", report.residuals);
        }
        // Round-off: both are refined to the same residual; the factors differ only in the
        // order of floating-point sums.
        let difference = max_relative_difference(&x, &y);
        assert!(
            difference <= 1e-10,
            "sequential and parallel fields differ by {difference:e} relative"
        );
    };
    compare(&sequential, &parallel);
    compare(&automatic, &sequential);

    // The choice is kept by refactorizations.
    sequential
        .set_constraints(second.clone())
        .expect("refactor");
    parallel.set_constraints(second).expect("refactor");
    assert!(!sequential.is_parallel());
    assert!(parallel.is_parallel());
    compare(&sequential, &parallel);
}
