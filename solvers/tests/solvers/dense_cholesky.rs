#![allow(clippy::needless_range_loop)] // index loops mirror the matrix formulas
use faer::Mat;
use tvf_solvers::{DenseCholesky, SolverError};

fn spd(n: usize, salt: f64) -> Mat<f64> {
    let b = Mat::from_fn(n, n, |i, j| ((i * 7 + j * 13) as f64 * 0.37 + salt).sin());
    let mut a = Mat::zeros(n, n);
    for i in 0..n {
        for j in 0..n {
            a[(i, j)] =
                (0..n).map(|k| b[(i, k)] * b[(j, k)]).sum::<f64>() + if i == j { 1.0 } else { 0.0 };
        }
    }
    a
}

fn assert_factor_matches(chol: &DenseCholesky, a: &Mat<f64>) {
    let fresh = DenseCholesky::new(a.as_ref()).unwrap();
    let (l, f) = (chol.factor(), fresh.factor());
    assert_eq!(l.nrows(), f.nrows());
    for i in 0..l.nrows() {
        for j in 0..=i {
            assert!(
                (l[(i, j)] - f[(i, j)]).abs() < 1e-10,
                "L[{i},{j}] {} vs {}",
                l[(i, j)],
                f[(i, j)]
            );
        }
    }
}

#[test]
fn update_and_downdate_match_refactorization() {
    let n = 30;
    let a = spd(n, 0.3);
    let mut chol = DenseCholesky::new(a.as_ref()).unwrap();
    let v: Vec<f64> = (0..n).map(|i| (i as f64 * 0.9).cos()).collect();
    chol.rank_one_update(&v).unwrap();
    let updated = Mat::from_fn(n, n, |i, j| a[(i, j)] + v[i] * v[j]);
    assert_factor_matches(&chol, &updated);
    chol.rank_one_downdate(&v).unwrap();
    assert_factor_matches(&chol, &a);
    let b: Vec<f64> = (0..n).map(|i| i as f64 - 3.0).collect();
    let x = chol.solve(&b).unwrap();
    for i in 0..n {
        let ax: f64 = (0..n).map(|j| a[(i, j)] * x[j]).sum();
        assert!((ax - b[i]).abs() < 1e-9);
    }
}

#[test]
fn downdate_to_indefinite_fails_and_leaves_factor_unchanged() {
    let a = Mat::<f64>::identity(4, 4);
    let mut chol = DenseCholesky::new(a.as_ref()).unwrap();
    let v = [0.0, 1.5, 0.0, 0.0];
    assert!(matches!(
        chol.rank_one_downdate(&v),
        Err(SolverError::NotPositiveDefinite { .. })
    ));
    assert_factor_matches(&chol, &a);
}

#[test]
fn bordered_append_and_remove_match_refactorization() {
    let n = 25;
    let big = spd(n + 1, 1.1);
    let small = Mat::from_fn(n, n, |i, j| big[(i, j)]);
    let mut chol = DenseCholesky::new(small.as_ref()).unwrap();
    let column: Vec<f64> = (0..=n).map(|i| big[(i, n)]).collect();
    chol.append(&column).unwrap();
    assert_factor_matches(&chol, &big);
    for index in [0usize, 7, n] {
        let mut c = DenseCholesky::new(big.as_ref()).unwrap();
        c.remove(index).unwrap();
        let keep: Vec<usize> = (0..=n).filter(|&i| i != index).collect();
        let reduced = Mat::from_fn(n, n, |i, j| big[(keep[i], keep[j])]);
        assert_factor_matches(&c, &reduced);
    }
    assert!(matches!(
        chol.remove(n + 1),
        Err(SolverError::DimensionMismatch { .. })
    ));
    // appending a column that makes the matrix indefinite is refused
    let mut bad: Vec<f64> = (0..=n).map(|i| big[(i, n)]).collect();
    bad.push(0.0);
    assert!(matches!(
        chol.append(&bad),
        Err(SolverError::NotPositiveDefinite { .. })
    ));
    assert_eq!(chol.dimension(), n + 1);
}

#[test]
fn invalid_input_is_reported() {
    let a = Mat::from_fn(3, 3, |i, j| if i == j { -1.0 } else { 0.0 });
    assert!(matches!(
        DenseCholesky::new(a.as_ref()),
        Err(SolverError::NotPositiveDefinite { pivot: 0, .. })
    ));
    let mut chol = DenseCholesky::new(Mat::<f64>::identity(3, 3).as_ref()).unwrap();
    assert!(matches!(
        chol.rank_one_update(&[1.0]),
        Err(SolverError::DimensionMismatch { .. })
    ));
    assert!(matches!(
        chol.solve(&[1.0, 2.0]),
        Err(SolverError::DimensionMismatch { .. })
    ));
}
