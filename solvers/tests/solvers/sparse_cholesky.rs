#![allow(clippy::needless_range_loop)] // index loops mirror the matrix formulas

use crate::common::*;
use faer::Mat;
use tvf_solvers::{SolverError, SparseCholesky, SparseLdlt};

#[test]
fn solves_shifted_grid_laplacian_full_and_upper_storage() {
    let a = grid_laplacian(30, 25, false);
    let mass = irregular_masses(a.rows(), 1);
    let shifted = add_diagonal(&a, &mass, 0.1);
    let x_true: Vec<f64> = (0..a.rows()).map(|i| (i as f64 * 0.37).sin()).collect();
    let b = matvec(&shifted, &x_true);

    let chol = SparseCholesky::new(&shifted).unwrap();
    assert_eq!(chol.dimension(), 750);
    let x = chol.solve(&b);
    assert!(
        max_abs_diff(&x, &x_true) < 1e-10,
        "full storage error {}",
        max_abs_diff(&x, &x_true)
    );

    // upper-triangular storage, CSR
    let mut t = sprs::TriMat::new(shifted.shape());
    for (v, (i, j)) in shifted.iter() {
        if i <= j {
            t.add_triplet(i, j, *v);
        }
    }
    let upper_csr: sprs::CsMat<f64> = t.to_csr();
    let x2 = SparseCholesky::new(&upper_csr).unwrap().solve(&b);
    assert!(max_abs_diff(&x2, &x_true) < 1e-10);
}

#[test]
fn solve_many_matches_single_solves() {
    let a = grid_laplacian(20, 20, true);
    let mass = irregular_masses(a.rows(), 2);
    let shifted = add_diagonal(&a, &mass, 0.5);
    let chol = SparseCholesky::new(&shifted).unwrap();
    let rhs = Mat::from_fn(a.rows(), 7, |i, j| ((i * (j + 3)) as f64 * 0.11).cos());
    let x = chol.solve_many(rhs.as_ref());
    for j in 0..7 {
        let col: Vec<f64> = (0..a.rows()).map(|i| rhs[(i, j)]).collect();
        let single = chol.solve(&col);
        let many: Vec<f64> = (0..a.rows()).map(|i| x[(i, j)]).collect();
        assert!(max_abs_diff(&single, &many) < 1e-12);
        let back = matvec(&shifted, &many);
        assert!(max_abs_diff(&back, &col) < 1e-10);
    }
}

#[test]
fn refactor_reuses_pattern_and_rejects_other_patterns() {
    let a = grid_laplacian(15, 12, false);
    let mass = irregular_masses(a.rows(), 3);
    let mut chol = SparseCholesky::new(&add_diagonal(&a, &mass, 0.2)).unwrap();
    let shifted2 = add_diagonal(&a, &mass, 3.0);
    chol.refactor(&shifted2).unwrap();
    let b: Vec<f64> = (0..a.rows()).map(|i| i as f64).collect();
    let x = chol.solve(&b);
    assert!(max_abs_diff(&matvec(&shifted2, &x), &b) < 1e-9);
    let fresh = SparseCholesky::new(&shifted2).unwrap().solve(&b);
    assert!(max_abs_diff(&x, &fresh) < 1e-12);

    let other = add_diagonal(&grid_laplacian(15, 12, true), &mass, 0.2);
    assert_eq!(chol.refactor(&other), Err(SolverError::PatternMismatch));
}

#[test]
fn semidefinite_laplacian_is_not_positive_definite() {
    let a = grid_laplacian(10, 10, false);
    match SparseCholesky::new(&a) {
        Err(SolverError::NotPositiveDefinite { pivot, .. }) => assert!(pivot < 100),
        other => panic!("expected NotPositiveDefinite, got {other:?}"),
    }
    // a negative shift of the mass makes it definite
    let mass = irregular_masses(100, 4);
    assert!(SparseCholesky::new(&add_diagonal(&a, &mass, 1e-6)).is_ok());
    // an indefinite matrix is rejected
    assert!(matches!(
        SparseCholesky::new(&add_diagonal(&a, &mass, -1.0)),
        Err(SolverError::NotPositiveDefinite { .. })
    ));
}

#[test]
fn bad_input_is_reported() {
    let rect: sprs::CsMat<f64> = sprs::TriMat::<f64>::new((3, 4)).to_csc();
    assert_eq!(
        SparseCholesky::new(&rect).unwrap_err(),
        SolverError::NotSquare { rows: 3, cols: 4 }
    );
    let mut t = sprs::TriMat::new((2, 2));
    t.add_triplet(0, 0, 1.0);
    t.add_triplet(1, 1, f64::NAN);
    assert!(matches!(
        SparseCholesky::new(&t.to_csc()),
        Err(SolverError::NonFinite { row: 1, col: 1, .. })
    ));
}

#[test]
fn inertia_counts_eigenvalues_below_shift() {
    // path Laplacian with unit mass: eigenvalues 2 - 2 cos(pi k / n), k = 0..n-1
    let n = 200;
    let a = path_laplacian(n);
    let ones = vec![1.0; n];
    for &sigma in &[0.5, 1.3, 2.7, 3.9] {
        let upper = tvf_solvers::convert::shifted_upper_triangle(&a, &ones, sigma).unwrap();
        let ldlt = SparseLdlt::new(upper.as_ref()).unwrap();
        let expected = (0..n)
            .filter(|&k| 2.0 - 2.0 * (std::f64::consts::PI * k as f64 / n as f64).cos() < sigma)
            .count();
        let inertia = ldlt.inertia();
        assert_eq!(inertia.negative, expected, "sigma = {sigma}");
        assert_eq!(inertia.negative + inertia.positive, n);
    }
}

#[test]
fn diagonal_matrices_factor() {
    // faer factors a diagonal pattern with its simplicial (not supernodal) representation; the
    // positivity check must read the pivots from it too.
    let diagonal = diagonal_matrix(&[1.0, 3.0, 2.0]);
    let cholesky = SparseCholesky::new(&diagonal).expect("a positive diagonal is SPD");
    let x = cholesky.solve(&[1.0, 1.0, 1.0]);
    assert!((x[1] - 1.0 / 3.0).abs() < 1e-15 && (x[2] - 0.5).abs() < 1e-15);
    let singular = diagonal_matrix(&[1.0, 0.0, 2.0]);
    assert!(SparseCholesky::new(&singular).is_err());
}

fn diagonal_matrix(d: &[f64]) -> sprs::CsMat<f64> {
    let n = d.len();
    sprs::CsMat::new((n, n), (0..=n).collect(), (0..n).collect(), d.to_vec())
}
