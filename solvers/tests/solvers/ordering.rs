//! Fill-reducing orderings: nested dissection (METIS) gives valid, deterministic permutations,
//! and factorizations ordered by it solve as accurately as AMD-ordered ones.

use crate::common::*;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Mat, Par};
use tvf_solvers::convert::upper_triangle_csc;
use tvf_solvers::ordering::{
    inverse_permutation, is_permutation, nested_dissection, nested_dissection_of_groups,
    AdjacencyGraph,
};
use tvf_solvers::{FillOrdering, SolverError, SparseCholesky, SparseLdlt};

fn relative_residual(a: &sprs::CsMat<f64>, x: &[f64], b: &[f64]) -> f64 {
    let ax = matvec(a, x);
    let r: f64 = ax.iter().zip(b).map(|(p, q)| (p - q) * (p - q)).sum();
    let nb: f64 = b.iter().map(|q| q * q).sum();
    (r / nb).sqrt()
}

fn grid_system(nx: usize, ny: usize) -> sprs::CsMat<f64> {
    let a = grid_laplacian(nx, ny, false);
    let mass = irregular_masses(a.rows(), 5);
    add_diagonal(&a, &mass, 0.05)
}

#[test]
fn nested_dissection_is_a_valid_deterministic_permutation() {
    let a = grid_system(40, 35);
    let upper = upper_triangle_csc(&a).unwrap();
    let perm = nested_dissection(upper.symbolic()).unwrap();
    assert!(is_permutation(&perm, a.rows()));
    let again = nested_dissection(upper.symbolic()).unwrap();
    assert_eq!(perm, again, "nested dissection must be deterministic");
    // Full storage describes the same graph, hence the same ordering.
    let full = faer_full(&a);
    assert_eq!(nested_dissection(full.symbolic()).unwrap(), perm);
    let inverse = inverse_permutation(&perm);
    for (k, &p) in perm.iter().enumerate() {
        assert_eq!(inverse[p], k);
    }
}

#[test]
fn nested_dissection_handles_disconnected_and_tiny_graphs() {
    // Two grids, a path and isolated unknowns (diagonal only).
    let blocks = [
        grid_system(9, 7),
        path_laplacian(13),
        grid_system(5, 5),
        add_diagonal(&graph_laplacian(4, &[]), &[1.0; 4], 1.0),
    ];
    let a = direct_sum(&blocks);
    let upper = upper_triangle_csc(&a).unwrap();
    let perm = nested_dissection(upper.symbolic()).unwrap();
    assert!(is_permutation(&perm, a.rows()));
    for n in [0, 1] {
        let tiny = add_diagonal(&graph_laplacian(n, &[]), &vec![1.0; n], 1.0);
        let upper = upper_triangle_csc(&tiny).unwrap();
        assert_eq!(
            nested_dissection(upper.symbolic()).unwrap(),
            (0..n).collect::<Vec<_>>()
        );
    }
}

#[test]
fn nested_dissection_factor_solves_accurately_with_comparable_fill() {
    let a = grid_system(60, 50);
    let n = a.rows();
    let x_true: Vec<f64> = (0..n).map(|i| (i as f64 * 0.21).cos()).collect();
    let b = matvec(&a, &x_true);
    let amd = SparseCholesky::new(&a).unwrap();
    let nd = SparseCholesky::with_ordering(&a, FillOrdering::NestedDissection).unwrap();
    assert_eq!(amd.ordering(), FillOrdering::Amd);
    assert_eq!(nd.ordering(), FillOrdering::NestedDissection);
    let x = nd.solve(&b);
    assert!(relative_residual(&a, &x, &b) < 1e-13);
    assert!(max_abs_diff(&x, &x_true) < 1e-9);
    assert!(max_abs_diff(&x, &amd.solve(&b)) < 1e-10);
    // A 2D grid: nested dissection fills in about as much as AMD, far less than the natural
    // (banded) ordering's n · nx.
    assert!(
        (nd.factor_len() as f64) < 1.3 * amd.factor_len() as f64,
        "ND fill {} vs AMD {}",
        nd.factor_len(),
        amd.factor_len()
    );
    assert!(nd.factor_len() < n * 60 / 2);
    // Many right-hand sides and refactorisation reuse the nested-dissection analysis.
    let rhs = Mat::from_fn(n, 3, |i, j| ((i + 7 * j) as f64 * 0.05).sin());
    let many = nd.solve_many(rhs.as_ref());
    for j in 0..3 {
        let col: Vec<f64> = (0..n).map(|i| rhs[(i, j)]).collect();
        let sol: Vec<f64> = (0..n).map(|i| many[(i, j)]).collect();
        assert!(relative_residual(&a, &sol, &col) < 1e-13);
    }
    let mut nd = nd;
    let stiffer = add_diagonal(&a, &irregular_masses(n, 9), 2.0);
    nd.refactor(&stiffer).unwrap();
    let y = nd.solve(&b);
    assert!(relative_residual(&stiffer, &y, &b) < 1e-13);
}

#[test]
fn nested_dissection_ldlt_of_indefinite_matrix_has_the_same_inertia_as_amd() {
    // A − σI for a grid Laplacian with σ inside the spectrum: indefinite, nonsingular.
    let a = grid_laplacian(30, 20, false);
    let shifted = add_diagonal(&a, &vec![1.0; a.rows()], -0.73);
    let upper = upper_triangle_csc(&shifted).unwrap();
    let amd = SparseLdlt::new(upper.as_ref()).unwrap();
    let nd = SparseLdlt::with_ordering(upper.as_ref(), FillOrdering::NestedDissection).unwrap();
    assert_eq!(nd.inertia(), amd.inertia());
    assert!(nd.inertia().negative > 0 && nd.inertia().positive > 0);
    assert!(nd.factor_flop_count() > 0.0);
    let b: Vec<f64> = (0..a.rows()).map(|i| 1.0 + (i % 7) as f64).collect();
    let mut x = Mat::from_fn(a.rows(), 1, |i, _| b[i]);
    nd.solve_in_place(x.as_mut());
    let x: Vec<f64> = (0..a.rows()).map(|i| x[(i, 0)]).collect();
    assert!(relative_residual(&shifted, &x, &b) < 1e-11);
}

#[test]
fn grouped_nested_dissection_orders_blocks_of_unknowns() {
    // Two unknowns per grid node (a 2 × 2 block per node and per edge): group = node.
    let grid = grid_system(25, 20);
    let nodes = grid.rows();
    let mut t = sprs::TriMat::new((2 * nodes, 2 * nodes));
    for (v, (i, j)) in grid.iter() {
        for (p, q) in [(0, 0), (1, 1), (0, 1), (1, 0)] {
            let scale = if p == q { 1.0 } else { 0.25 };
            t.add_triplet(2 * i + p, 2 * j + q, v * scale);
        }
    }
    let a: sprs::CsMat<f64> = t.to_csr();
    let upper = upper_triangle_csc(&a).unwrap();
    let node_of: Vec<usize> = (0..2 * nodes).map(|i| i / 2).collect();
    let order = nested_dissection_of_groups(upper.symbolic(), &node_of, nodes).unwrap();
    assert!(is_permutation(&order, nodes));
    assert_eq!(
        order,
        nested_dissection_of_groups(upper.symbolic(), &node_of, nodes).unwrap()
    );
    let perm: Vec<usize> = order.iter().flat_map(|&v| [2 * v, 2 * v + 1]).collect();
    let factor = SparseLdlt::with_permutation(upper.as_ref(), &perm).unwrap();
    let b: Vec<f64> = (0..2 * nodes).map(|i| (i as f64 * 0.3).sin()).collect();
    let mut x = Mat::from_fn(2 * nodes, 1, |i, _| b[i]);
    factor.solve_in_place(x.as_mut());
    let x: Vec<f64> = (0..2 * nodes).map(|i| x[(i, 0)]).collect();
    assert!(relative_residual(&a, &x, &b) < 1e-12);
    // The quotient graph is the grid's own graph.
    let quotient = AdjacencyGraph::quotient_of_pattern(upper.symbolic(), &node_of, nodes);
    let grid_graph =
        AdjacencyGraph::from_symmetric_pattern(upper_triangle_csc(&grid).unwrap().symbolic());
    assert_eq!(quotient, grid_graph);
    assert_eq!(quotient.neighbours_of(0), &[1, 25]);
}

#[test]
fn invalid_custom_permutation_is_an_error() {
    let a = grid_system(6, 5);
    let upper = upper_triangle_csc(&a).unwrap();
    let n = a.rows();
    let mut repeated: Vec<usize> = (0..n).collect();
    repeated[3] = 4;
    for bad in [repeated, (0..n - 1).collect(), (1..=n).collect()] {
        assert!(matches!(
            SparseLdlt::with_permutation(upper.as_ref(), &bad),
            Err(SolverError::Factorization(_))
        ));
    }
}

#[test]
fn ordering_names_round_trip() {
    for ordering in [FillOrdering::Amd, FillOrdering::NestedDissection] {
        assert_eq!(FillOrdering::from_name(ordering.name()), Some(ordering));
    }
    assert_eq!(
        FillOrdering::from_name("METIS"),
        Some(FillOrdering::NestedDissection)
    );
    assert_eq!(FillOrdering::from_name("colamd"), None);
    assert_eq!(FillOrdering::default(), FillOrdering::Amd);
}

/// Both triangles of a `sprs` matrix as a faer CSC matrix.
fn faer_full(a: &sprs::CsMat<f64>) -> SparseColMat<usize, f64> {
    let csc = a.to_csc();
    let n = a.rows();
    let symbolic = SymbolicSparseColMat::new_checked(
        n,
        n,
        csc.indptr().to_proper().to_vec(),
        None,
        csc.indices().to_vec(),
    );
    SparseColMat::new(symbolic, csc.data().to_vec())
}

#[test]
fn a_factor_pattern_factors_shifted_matrices_like_a_fresh_factorization() {
    let a = grid_system(12, 9);
    let n = a.rows();
    let upper = upper_triangle_csc(&a).unwrap();
    let pattern = SparseLdlt::new(upper.as_ref()).unwrap().pattern();
    // A − σI with σ inside the spectrum: indefinite, same pattern.
    let mut shifted = a.clone();
    for i in 0..n {
        *shifted.get_mut(i, i).unwrap() -= 2.5;
    }
    let shifted_upper = upper_triangle_csc(&shifted).unwrap();
    let reused = pattern.factor(shifted_upper.as_ref(), Par::Seq).unwrap();
    let fresh = SparseLdlt::new(shifted_upper.as_ref()).unwrap();
    assert_eq!(reused.inertia(), fresh.inertia());
    assert!(reused.inertia().negative > 0 && reused.inertia().positive > 0);
    let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).cos()).collect();
    let mut x = Mat::from_fn(n, 1, |i, _| b[i]);
    reused.solve_in_place(x.as_mut());
    let x: Vec<f64> = (0..n).map(|i| x[(i, 0)]).collect();
    assert!(relative_residual(&shifted, &x, &b) < 1e-11);
    // Another pattern is refused.
    let other = upper_triangle_csc(&grid_system(9, 12)).unwrap();
    assert!(matches!(
        pattern.factor(other.as_ref(), Par::Seq),
        Err(SolverError::PatternMismatch)
    ));
}
