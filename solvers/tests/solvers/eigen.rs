#![allow(clippy::needless_range_loop)] // index loops mirror the matrix formulas

use crate::common::*;
use faer::Mat;
use std::cell::Cell;
use tvf_solvers::convert::shifted_upper_triangle;
use tvf_solvers::{
    default_slice_memory, dense_generalized_eigen, lowest_eigenpairs, lowest_eigenpairs_of,
    streamed_eigenvectors_in_memory, EigenOptions, EigenRequest, Eigenpairs, Pencil, SolverError,
    SparseLdlt,
};

fn dense(a: &sprs::CsMat<f64>) -> Mat<f64> {
    let mut d = Mat::zeros(a.rows(), a.cols());
    for (v, (i, j)) in a.iter() {
        d[(i, j)] += *v;
    }
    d
}

/// Checks `result` against the dense oracle: values, residuals, M-orthonormality, inertia.
fn check_against_oracle(a: &sprs::CsMat<f64>, mass: &[f64], k: usize, result: &Eigenpairs) {
    let n = a.rows();
    let ad = dense(a);
    let (reference, _) = dense_generalized_eigen(ad.as_ref(), mass).unwrap();
    let ones = vec![1.0; n];
    let (a_spectrum, _) = dense_generalized_eigen(ad.as_ref(), &ones).unwrap();
    let norm_a = a_spectrum.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let top = reference[n - 1];
    assert_eq!(result.values.len(), k);
    assert_eq!(result.vectors.nrows(), n);
    assert_eq!(result.vectors.ncols(), k);
    for j in 0..k {
        let tol = 1e-10 * reference[j].abs() + 1e-12 * top;
        assert!(
            (result.values[j] - reference[j]).abs() <= tol,
            "eigenvalue {j}: got {} expected {} (diff {:e})",
            result.values[j],
            reference[j],
            (result.values[j] - reference[j]).abs()
        );
        if j > 0 {
            assert!(result.values[j] >= result.values[j - 1]);
        }
    }
    // residuals ‖Ax − λMx‖ ≤ 1e-9 ‖A‖₂ ‖x‖
    for j in 0..k {
        let x: Vec<f64> = (0..n).map(|i| result.vectors[(i, j)]).collect();
        let ax = matvec(a, &x);
        let r: f64 = (0..n)
            .map(|i| (ax[i] - result.values[j] * mass[i] * x[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        let xn: f64 = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!(
            r <= 1e-9 * norm_a * xn,
            "residual {j}: {:e}",
            r / (norm_a * xn)
        );
        assert!(
            result.residuals[j] <= 1e-9,
            "reported residual {j}: {:e}",
            result.residuals[j]
        );
    }
    // XᵀMX = I
    let mut worst = 0.0f64;
    for p in 0..k {
        for q in 0..=p {
            let dot: f64 = (0..n)
                .map(|i| result.vectors[(i, p)] * mass[i] * result.vectors[(i, q)])
                .sum();
            let expected = if p == q { 1.0 } else { 0.0 };
            worst = worst.max((dot - expected).abs());
        }
    }
    assert!(worst <= 1e-10, "XᵀMX deviates from I by {worst:e}");
    // Sylvester inertia just above the top returned eigenvalue (tests pick k at a gap)
    assert!(
        reference[k] - reference[k - 1] > 1e-8 * top,
        "test must choose k at a spectral gap"
    );
    let sigma = 0.5 * (reference[k - 1] + reference[k]);
    let upper = shifted_upper_triangle(a, mass, sigma).unwrap();
    let inertia = SparseLdlt::new(upper.as_ref()).unwrap().inertia();
    assert_eq!(inertia.negative, k, "inertia below sigma");
    assert!(result.values.iter().all(|&v| v < sigma));
}

#[test]
fn grid_laplacian_with_irregular_masses() {
    let a = grid_laplacian(40, 38, false);
    let mass = irregular_masses(a.rows(), 11);
    let options = EigenOptions {
        interval_size: 40,
        ..Default::default()
    };
    let result = lowest_eigenpairs(&a, &mass, 100, &options).unwrap();
    check_against_oracle(&a, &mass, 100, &result);
    let statistics = result.statistics;
    assert!(
        statistics.solving.factorizations >= 3,
        "several intervals expected, got {statistics:?}"
    );
    assert!(result.residuals.iter().all(|r| r.is_finite()));
}

#[test]
fn three_components_give_three_zero_eigenvalues() {
    let a = direct_sum(&[
        grid_laplacian(20, 20, false),
        grid_laplacian(15, 25, false),
        path_laplacian(300),
    ]);
    let mass = irregular_masses(a.rows(), 5);
    let result = lowest_eigenpairs(&a, &mass, 41, &EigenOptions::default()).unwrap();
    check_against_oracle(&a, &mass, 41, &result);
    let zeros = result.values.iter().filter(|v| v.abs() < 1e-10).count();
    assert_eq!(zeros, 3);
    assert!(result.values[3] > 1e-5);
}

#[test]
fn periodic_grid_multiplicities_are_complete() {
    // torus grid with unit mass: eigenvalues 4 sin²(πa/n) + 4 sin²(πb/n), multiplicities 1, 2, 4, 8
    let a = grid_laplacian(30, 30, true);
    let mass = vec![1.0; a.rows()];
    let options = |threads| EigenOptions {
        interval_size: 48,
        block_size: 8,
        threads,
        ..Default::default()
    };
    // k = 137 ends a multiplet: count of eigenvalues below the 138th distinct level
    let ad = dense(&a);
    let (reference, _) = dense_generalized_eigen(ad.as_ref(), &mass).unwrap();
    let k = (120..200)
        .find(|&k| reference[k] - reference[k - 1] > 1e-6)
        .unwrap();
    for threads in [2, 1] {
        let result = lowest_eigenpairs(&a, &mass, k, &options(threads)).unwrap();
        check_against_oracle(&a, &mass, k, &result);
    }
}

#[test]
fn multiplicity_larger_than_block_size_is_found() {
    // five identical components: every eigenvalue has multiplicity ≥ 5, blocks of 2 vectors
    let block = grid_laplacian(12, 11, false);
    let copies: Vec<_> = (0..5).map(|_| block.clone()).collect();
    let a = direct_sum(&copies);
    let base = irregular_masses(block.rows(), 9);
    let mass: Vec<f64> = (0..5).flat_map(|_| base.iter().copied()).collect();
    for threads in [2, 1] {
        let options = EigenOptions {
            block_size: 2,
            interval_size: 20,
            threads,
            ..Default::default()
        };
        let result = lowest_eigenpairs(&a, &mass, 50, &options).unwrap();
        check_against_oracle(&a, &mass, 50, &result);
        let zeros = result.values.iter().filter(|v| v.abs() < 1e-10).count();
        assert_eq!(zeros, 5);
    }
}

#[test]
fn interval_results_do_not_depend_on_the_thread_count() {
    let a = grid_laplacian(40, 38, false);
    let mass = irregular_masses(a.rows(), 7);
    let run = |threads| {
        let options = EigenOptions {
            interval_size: 30,
            threads,
            ..Default::default()
        };
        lowest_eigenpairs(&a, &mass, 120, &options).unwrap()
    };
    let one = run(1);
    check_against_oracle(&a, &mass, 120, &one);
    assert!(
        one.statistics.factorizations() >= 5,
        "several intervals expected, got {:?}",
        one.statistics
    );
    let three = run(3);
    assert_eq!(one.values, three.values);
    assert_eq!(one.statistics.solves(), three.statistics.solves());
    assert_eq!(one.vectors, three.vectors);
}

/// A slice memory budget with room for one slice but not two runs the intervals one at a time
/// and gives the same pairs bit for bit; one too small for a slice of the target size makes
/// the intervals smaller (more factorizations), and the pairs still match the oracle.
#[test]
fn a_slice_memory_budget_changes_the_schedule_or_the_intervals_not_the_pairs() {
    let a = grid_laplacian(40, 38, false);
    let mass = irregular_masses(a.rows(), 7);
    let run = |slice_memory| {
        let options = EigenOptions {
            interval_size: 30,
            threads: 2,
            slice_memory: Some(slice_memory),
            ..Default::default()
        };
        lowest_eigenpairs(&a, &mass, 120, &options).unwrap()
    };
    let free = run(usize::MAX);
    let two_slices = free.statistics.peak_slice_memory;
    assert!(two_slices > 0, "{:?}", free.statistics);
    let one_at_a_time = run(two_slices / 2);
    assert_eq!(one_at_a_time.statistics.peak_slice_memory, two_slices / 2);
    assert_eq!(free.values, one_at_a_time.values);
    assert_eq!(free.vectors, one_at_a_time.vectors);
    assert_eq!(
        free.statistics.factorizations(),
        one_at_a_time.statistics.factorizations()
    );
    let smaller = run(two_slices / 4);
    check_against_oracle(&a, &mass, 120, &smaller);
    // At least two blocks per interval: here more than the budget, so each slice runs alone.
    assert!(smaller.statistics.peak_slice_memory < two_slices / 2);
    assert!(
        smaller.statistics.factorizations() > free.statistics.factorizations(),
        "{:?} against {:?}",
        smaller.statistics,
        free.statistics
    );
}

#[test]
fn seeded_runs_are_deterministic_and_report_progress() {
    let a = grid_laplacian(30, 20, false);
    let mass = irregular_masses(a.rows(), 3);
    let calls = Cell::new(0usize);
    let callback = |p: &tvf_solvers::EigenProgress| {
        assert_eq!(p.wanted, 30);
        calls.set(calls.get() + 1);
    };
    let options = EigenOptions {
        seed: 42,
        progress: Some(&callback),
        ..Default::default()
    };
    let first = lowest_eigenpairs(&a, &mass, 30, &options).unwrap();
    let second = lowest_eigenpairs(&a, &mass, 30, &options).unwrap();
    assert_eq!(first.values, second.values);
    assert_eq!(first.statistics.solves(), second.statistics.solves());
    assert!(calls.get() >= 2);
    assert!(first.statistics.solves() > 0);
}

#[test]
fn small_problems_use_the_dense_path() {
    let a = grid_laplacian(8, 7, false);
    let mass = irregular_masses(a.rows(), 8);
    let result = lowest_eigenpairs(&a, &mass, 50, &EigenOptions::default()).unwrap();
    assert_eq!(result.statistics.factorizations(), 0);
    let ad = dense(&a);
    let (reference, _) = dense_generalized_eigen(ad.as_ref(), &mass).unwrap();
    for j in 0..50 {
        assert!((result.values[j] - reference[j]).abs() < 1e-12 * reference[55].max(1.0));
    }
    assert!(result.residuals.iter().all(|&r| r < 1e-12));
}

#[test]
fn invalid_requests_are_errors() {
    let a = path_laplacian(10);
    let mass = vec![1.0; 10];
    assert_eq!(
        lowest_eigenpairs(&a, &mass, 11, &EigenOptions::default()).unwrap_err(),
        SolverError::TooManyEigenpairs {
            requested: 11,
            dimension: 10
        }
    );
    let mut bad = mass.clone();
    bad[3] = 0.0;
    assert!(matches!(
        lowest_eigenpairs(&a, &bad, 2, &EigenOptions::default()),
        Err(SolverError::MassNotPositive { index: 3, .. })
    ));
    assert!(matches!(
        lowest_eigenpairs(&a, &mass[..9], 2, &EigenOptions::default()),
        Err(SolverError::DimensionMismatch { .. })
    ));
    let empty = lowest_eigenpairs(&a, &mass, 0, &EigenOptions::default()).unwrap();
    assert!(empty.values.is_empty());
}

#[test]
fn an_interval_whose_shift_sits_on_an_eigenvalue_is_split_and_solved() {
    // One interval (−∞, 2λ*) whose midpoint, the shift, is the eigenvalue λ* to rounding: the
    // shift-inverted operator has |θ| ≈ 1e14/λ* there, so the pairs at the far end of the
    // interval cannot reach the tolerance relative to their |θ| ≈ 1/λ* (the rounding floor is
    // ε·max|θ|). The interval must be split at its shift instead of restarting forever.
    let a = grid_laplacian(30, 30, true);
    let mass = vec![1.0; a.rows()];
    let (reference, _) = dense_generalized_eigen(dense(&a).as_ref(), &mass).unwrap();
    let star = reference[61];
    let pencil = Pencil::new(&a, &mass).unwrap();
    let top = pencil.count_below(2.0 * star).unwrap();
    let k = top.below;
    assert!(k > 100 && 3 * k < a.rows(), "{k}");
    let options = EigenOptions {
        interval_size: 10 * k,
        ..Default::default()
    };
    let request = EigenRequest {
        pencil: &pencil,
        count: k,
        top: Some(top),
        seed: 5,
    };
    let solution = lowest_eigenpairs_of(&[request], &options).unwrap();
    let statistics = solution.statistics;
    // One split: one more count, and the two halves' shifts.
    assert_eq!(statistics.counting.factorizations, 2, "{statistics:?}");
    assert_eq!(statistics.solving.factorizations, 3, "{statistics:?}");
    check_against_oracle(&a, &mass, k, &solution.pairs[0]);
}

#[test]
fn every_shift_is_factored_once_and_counted_shifts_are_reused() {
    let a = grid_laplacian(40, 38, false);
    let mass = irregular_masses(a.rows(), 13);
    let pencil = Pencil::new(&a, &mass).unwrap();
    // A caller's count (as a basis split does) serves as the top shift and as a boundary.
    let (reference, _) = dense_generalized_eigen(dense(&a).as_ref(), &mass).unwrap();
    let t = 0.5 * (reference[119] + reference[120]);
    let top = pencil.count_below(t).unwrap();
    assert_eq!(top.below, 120);
    let middle = pencil.count_below(0.5 * t).unwrap();
    assert_eq!(pencil.count_below(0.5 * t).unwrap(), middle);
    assert_eq!(pencil.statistics().counting.factorizations, 2);
    let options = EigenOptions {
        interval_size: 30,
        ..Default::default()
    };
    let request = EigenRequest {
        pencil: &pencil,
        count: 120,
        top: Some(top),
        seed: 1,
    };
    let solution = lowest_eigenpairs_of(&[request], &options).unwrap();
    let statistics = solution.statistics;
    // Four intervals: boundaries t/4 and 3t/4 are new, t/2 was counted already.
    assert_eq!(statistics.counting.factorizations, 4, "{statistics:?}");
    assert_eq!(statistics.solving.factorizations, 4, "{statistics:?}");
    assert_eq!(statistics.refinement.factorizations, 0, "{statistics:?}");
    let mut shifts: Vec<f64> = pencil.counted().iter().map(|c| c.shift).collect();
    shifts.dedup();
    assert_eq!(shifts.len(), statistics.factorizations());
    check_against_oracle(&a, &mass, 120, &solution.pairs[0]);
    assert!(solution.pairs[0].field_residuals.iter().all(|r| *r <= 1e-9));
}

/// A progress callback that unwinds (the Python package stops a computation on Ctrl+C this way)
/// stops the solve: its payload reaches the caller as it was, after the interval jobs running
/// on other threads have stopped at their next report, and no further report is made.
#[test]
fn a_progress_callback_that_unwinds_stops_the_solve() {
    struct Stop;
    let a = grid_laplacian(40, 38, false);
    let mass = irregular_masses(a.rows(), 7);
    let calls = Cell::new(0usize);
    let callback = |_: &tvf_solvers::EigenProgress| {
        calls.set(calls.get() + 1);
        std::panic::resume_unwind(Box::new(Stop));
    };
    let options = EigenOptions {
        interval_size: 30,
        threads: 3,
        progress: Some(&callback),
        ..Default::default()
    };
    let run = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        lowest_eigenpairs(&a, &mass, 120, &options)
    }));
    let Err(payload) = run else {
        panic!("the callback did not stop the solve")
    };
    assert!(
        payload.is::<Stop>(),
        "the caller gets the callback's payload"
    );
    assert_eq!(calls.get(), 1);
    // The solver is usable again afterwards (no poisoned state).
    let options = EigenOptions {
        interval_size: 30,
        threads: 3,
        ..Default::default()
    };
    check_against_oracle(
        &a,
        &mass,
        120,
        &lowest_eigenpairs(&a, &mass, 120, &options).unwrap(),
    );
}

/// Eigenvectors handed to a sink as their intervals finish ([`EigenOptions::finished`]) are,
/// column by column and bit for bit, those of the same call without one; two pencils of
/// different sizes and a dense-sized one in one call, intervals small enough for several per
/// pencil (neighbours orthogonalised across the hand-over). Each column comes exactly once, in
/// ascending order per request, and the result then holds no vectors but the same values and
/// residuals; so with the eigenvectors waiting in memory (small next to the slice budget) and
/// in a temporary file (a budget too small for that). A sink that fails stops the computation
/// with its message.
#[test]
fn eigenvectors_handed_on_as_they_finish_are_those_of_the_whole_result() {
    let big = grid_laplacian(40, 38, false);
    let big_mass = irregular_masses(big.rows(), 21);
    let small = grid_laplacian(24, 22, true);
    let small_mass = irregular_masses(small.rows(), 22);
    let tiny = path_laplacian(60);
    let tiny_mass = irregular_masses(tiny.rows(), 23);
    // (count, seed) of each request; the third is small enough for the dense solver.
    let wanted = [(150, 1), (90, 2), (12, 3)];
    let pencils = || {
        [
            Pencil::new(&big, &big_mass).unwrap(),
            Pencil::new(&small, &small_mass).unwrap(),
            Pencil::new(&tiny, &tiny_mass).unwrap(),
        ]
    };
    let options = EigenOptions {
        interval_size: 32,
        ..Default::default()
    };
    let solve = |pencils: &[Pencil<'_>; 3], options: &EigenOptions<'_>| {
        let requests: Vec<EigenRequest<'_, '_>> = pencils
            .iter()
            .zip(wanted)
            .map(|(pencil, (count, seed))| EigenRequest {
                pencil,
                count,
                top: None,
                seed,
            })
            .collect();
        lowest_eigenpairs_of(&requests, options)
    };
    let whole = solve(&pencils(), &options).unwrap();

    // The (column, bits of the vector) handed over, per request.
    type Handed = Vec<Vec<(usize, Vec<u64>)>>;
    let handed = std::cell::RefCell::new(Handed::from(vec![Vec::new(); 3]));
    let sink = |finished: &tvf_solvers::FinishedEigenvectors<'_>| {
        let mut handed = handed.borrow_mut();
        for j in 0..finished.vectors.ncols() {
            let bits = finished
                .vectors
                .col(j)
                .iter()
                .map(|x| x.to_bits())
                .collect();
            handed[finished.request].push((finished.first + j, bits));
        }
        Ok(())
    };
    // The eigenvectors of the two sliced requests wait in memory under the default budget, and
    // in a temporary file under one that holds the whole call's slices but less than four times
    // those eigenvectors.
    let sliced_bytes = (big.rows() * wanted[0].0 + small.rows() * wanted[1].0) * 8;
    let in_file = whole.statistics.peak_slice_memory;
    assert!(streamed_eigenvectors_in_memory(
        sliced_bytes,
        default_slice_memory()
    ));
    assert!(!streamed_eigenvectors_in_memory(sliced_bytes, in_file));
    for slice_memory in [None, Some(in_file)] {
        let streamed = solve(
            &pencils(),
            &EigenOptions {
                finished: Some(&sink),
                slice_memory,
                ..options
            },
        )
        .unwrap();
        let received = handed.replace(Handed::from(vec![Vec::new(); 3]));
        for (r, (pairs, streamed)) in whole.pairs.iter().zip(&streamed.pairs).enumerate() {
            let case = format!("request {r}, budget {slice_memory:?}");
            assert_eq!(streamed.vectors.ncols(), 0, "{case}");
            assert_eq!(streamed.values, pairs.values, "{case}");
            assert_eq!(streamed.field_residuals, pairs.field_residuals, "{case}");
            let columns: Vec<usize> = received[r].iter().map(|(j, _)| *j).collect();
            assert_eq!(
                columns,
                (0..pairs.values.len()).collect::<Vec<_>>(),
                "{case}"
            );
            for (j, bits) in &received[r] {
                let expected: Vec<u64> =
                    pairs.vectors.col(*j).iter().map(|x| x.to_bits()).collect();
                assert!(bits == &expected, "{case}, column {j} differs");
            }
        }
    }
    assert!(
        whole.statistics.solving.factorizations >= 6,
        "{:?}",
        whole.statistics
    );

    let failing = |_: &tvf_solvers::FinishedEigenvectors<'_>| Err("disk full".to_string());
    let error = solve(
        &pencils(),
        &EigenOptions {
            finished: Some(&failing),
            ..options
        },
    )
    .unwrap_err();
    assert!(
        matches!(&error.source, SolverError::Stopped { reason } if reason == "disk full"),
        "{error}"
    );
}
