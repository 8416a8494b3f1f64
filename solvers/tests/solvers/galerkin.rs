//! The eigensolver on pencils with a sparse (consistent) mass and on mixed pencils
//! `d1 W⁻¹ d1ᵀ ψ = μ N ψ`, against the dense solver, on generated meshes (a jittered grid and
//! a closed "pillow" of two grids): the cotan stiffness with the consistent P1 mass, and the
//! Whitney 1-form mass `W` with the face–edge incidence `d1` and face masses `N`.
#![allow(clippy::needless_range_loop)] // index loops mirror the matrix formulas

#[path = "../../examples/mesh_matrices/mod.rs"]
#[allow(dead_code)]
mod mesh_matrices;

use faer::Mat;
use tvf_solvers::{
    dense_generalized_eigen, dense_generalized_eigen_with_mass, lowest_eigenpairs_of, EigenOptions,
    EigenRequest, Eigenpairs, MassMatrix, Pencil, SolverError,
};

fn dense(a: &sprs::CsMat<f64>) -> Mat<f64> {
    let mut d = Mat::zeros(a.rows(), a.cols());
    for (v, (i, j)) in a.iter() {
        d[(i, j)] += *v;
    }
    d
}

/// `d1 W⁻¹ d1ᵀ`, dense (the reference: the solver never forms it on its sparse path).
fn dense_mixed(w: &sprs::CsMat<f64>, d1: &sprs::CsMat<f64>) -> Mat<f64> {
    let d = dense(d1);
    let llt = dense(w).as_ref().llt(faer::Side::Lower).expect("W is SPD");
    let x = faer::linalg::solvers::Solve::solve(&llt, d.transpose().to_owned());
    let a = &d * &x;
    Mat::from_fn(a.nrows(), a.ncols(), |i, j| 0.5 * (a[(i, j)] + a[(j, i)]))
}

/// Options of the sparse Krylov path for problems of a few hundred to a few thousand
/// unknowns: several intervals per request.
fn krylov_options(interval_size: usize) -> EigenOptions<'static> {
    EigenOptions {
        dense_threshold: 50,
        interval_size,
        parallelism: faer::Par::Seq,
        threads: 2,
        ..EigenOptions::default()
    }
}

/// Largest relative error of the values against the reference (for the kernel, eigenvalues
/// below `10⁻⁸ λ_max`: the absolute error over `λ_max`), the largest `|Xᵀ M X − I|`, and the
/// largest reported residual.
fn errors(result: &Eigenpairs, reference: &[f64], mass: &Mat<f64>) -> (f64, f64, f64) {
    let k = result.values.len();
    let top = reference[reference.len() - 1];
    let value_error = (0..k)
        .map(|j| {
            let scale = if reference[j].abs() < 1e-8 * top {
                top
            } else {
                reference[j].abs()
            };
            (result.values[j] - reference[j]).abs() / scale
        })
        .fold(0.0, f64::max);
    let x = &result.vectors;
    let gram = x.transpose() * (mass * x);
    let mut orthonormality = 0.0f64;
    for i in 0..k {
        for j in 0..k {
            let target = if i == j { 1.0 } else { 0.0 };
            orthonormality = orthonormality.max((gram[(i, j)] - target).abs());
        }
    }
    let residual = result.residuals.iter().fold(0.0f64, |m, r| m.max(*r));
    (value_error, orthonormality, residual)
}

fn assert_accurate(name: &str, result: &Eigenpairs, reference: &[f64], mass: &Mat<f64>) {
    let (value_error, orthonormality, residual) = errors(result, reference, mass);
    println!(
        "{name}: k = {}, max relative eigenvalue error {value_error:.1e}, max |XᵀMX − I| \
         {orthonormality:.1e}, max residual {residual:.1e}",
        result.values.len()
    );
    assert!(
        value_error <= 1e-10,
        "{name}: eigenvalue error {value_error:e}"
    );
    assert!(
        orthonormality <= 1e-10,
        "{name}: |XᵀMX − I| = {orthonormality:e}"
    );
    assert!(residual <= 1e-9, "{name}: residual {residual:e}");
}

/// The counts of the pencil at midpoints between reference eigenvalues (and inside the
/// kernel's gap) equal the dense counts.
fn assert_counts(name: &str, pencil: &Pencil<'_>, reference: &[f64], at: &[usize]) {
    for &j in at {
        let t = 0.5 * (reference[j] + reference[j + 1]);
        let count = pencil.count_below(t).expect("counts");
        let expected = reference.iter().filter(|&&v| v < count.shift).count();
        assert_eq!(count.below, expected, "{name}: count below {t:e}");
    }
}

fn solve(requests: &[EigenRequest<'_, '_>], options: &EigenOptions<'_>) -> Vec<Eigenpairs> {
    lowest_eigenpairs_of(requests, options)
        .expect("the eigensolver converges")
        .pairs
}

/// Cotan stiffness with the consistent P1 mass of a jittered 40 × 35 grid (n = 1476): the 120
/// lowest pairs in five intervals agree with the dense generalized solver, are M-orthonormal,
/// the counts agree, and one and two concurrent intervals give the same result.
#[test]
fn consistent_mass_pencil_matches_the_dense_solver() {
    let (positions, faces) = mesh_matrices::grid(40, 35, 0.3);
    let stiffness = mesh_matrices::cotan(&positions, &faces).stiffness;
    let mass = mesh_matrices::consistent_mass(&positions, &faces);
    let (reference, _) =
        dense_generalized_eigen_with_mass(dense(&stiffness).as_ref(), dense(&mass).as_ref())
            .expect("dense reference");
    let k = 120;
    let mut results = Vec::new();
    for threads in [2, 1] {
        let pencil = Pencil::with_mass(&stiffness, MassMatrix::Sparse(&mass)).expect("valid");
        let options = EigenOptions {
            threads,
            ..krylov_options(30)
        };
        let request = EigenRequest {
            pencil: &pencil,
            count: k,
            top: None,
            seed: 7,
        };
        let result = solve(&[request], &options).remove(0);
        assert!(
            result.statistics.solving.factorizations >= 4,
            "several intervals"
        );
        assert_accurate("consistent mass", &result, &reference, &dense(&mass));
        if threads == 2 {
            assert_counts(
                "consistent mass",
                &pencil,
                &reference,
                &[0, 17, 60, 119, 200],
            );
        }
        results.push(result);
    }
    let difference = results[0]
        .values
        .iter()
        .zip(&results[1].values)
        .map(|(a, b)| (a - b).abs() / b.abs().max(1e-12))
        .fold(0.0, f64::max);
    assert!(
        difference <= 1e-13,
        "threads change the values by {difference:e}"
    );
}

/// One interval `(−∞, 2λ*)` whose midpoint, the shift, is the eigenvalue `λ*` to rounding (see
/// the diagonal-mass test of the same name): it is split and solved, with a sparse mass and with
/// a mixed pencil as with a diagonal mass.
#[test]
fn an_interval_whose_shift_sits_on_an_eigenvalue_is_split_and_solved() {
    let (positions, faces) = mesh_matrices::pillow(12, 10, 0.3, 3.0);
    let cotan = mesh_matrices::cotan(&positions, &faces);
    let consistent = mesh_matrices::consistent_mass(&positions, &faces);
    let whitney = mesh_matrices::whitney(&positions, &faces);
    let (exact_reference, _) = dense_generalized_eigen_with_mass(
        dense(&cotan.stiffness).as_ref(),
        dense(&consistent).as_ref(),
    )
    .expect("dense");
    let (coexact_reference, _) = dense_generalized_eigen(
        dense_mixed(&whitney.mass, &whitney.d1).as_ref(),
        &whitney.face_areas,
    )
    .expect("dense");
    let exact =
        Pencil::with_mass(&cotan.stiffness, MassMatrix::Sparse(&consistent)).expect("valid");
    let coexact = Pencil::mixed(
        &whitney.mass,
        &whitney.d1,
        MassMatrix::Diagonal(&whitney.face_areas),
    )
    .expect("valid");
    let n_mass = Mat::from_fn(faces.len(), faces.len(), |i, j| {
        if i == j {
            whitney.face_areas[i]
        } else {
            0.0
        }
    });
    let cases = [
        (
            "split, consistent mass",
            &exact,
            &exact_reference,
            dense(&consistent),
        ),
        ("split, mixed", &coexact, &coexact_reference, n_mass),
    ];
    for (name, pencil, reference, mass) in cases {
        let star = reference[41];
        let top = pencil.count_below(2.0 * star).expect("counts");
        let k = top.below;
        assert!(3 * k < pencil.dimension(), "{name}: {k}");
        let options = EigenOptions {
            interval_size: 10 * k,
            ..krylov_options(10 * k)
        };
        let request = EigenRequest {
            pencil,
            count: k,
            top: Some(top),
            seed: 5,
        };
        let result = solve(&[request], &options).remove(0);
        let statistics = result.statistics;
        assert!(
            statistics.solving.factorizations >= 3,
            "{name}: {statistics:?}"
        );
        assert_accurate(name, &result, reference, &mass);
    }
}

/// The co-exact pencil of a closed pillow (Whitney `W` on 1008 edges, `d1`, face areas `N`,
/// n2 = 672 faces), whose kernel is the constant 2-form: values, N-orthonormality, counts, one
/// and two threads.
#[test]
fn mixed_pencil_with_a_kernel_matches_the_dense_solver() {
    let (positions, faces) = mesh_matrices::pillow(12, 14, 0.3, 3.0);
    let whitney = mesh_matrices::whitney(&positions, &faces);
    let a = dense_mixed(&whitney.mass, &whitney.d1);
    let (reference, _) = dense_generalized_eigen(a.as_ref(), &whitney.face_areas).expect("dense");
    assert!(reference[0].abs() <= 1e-10 * reference[reference.len() - 1]);
    assert!(
        reference[1] > 1e-6 * reference[reference.len() - 1],
        "one kernel vector"
    );
    let n_mass = Mat::from_fn(faces.len(), faces.len(), |i, j| {
        if i == j {
            whitney.face_areas[i]
        } else {
            0.0
        }
    });
    let k = 150;
    let mut results = Vec::new();
    for threads in [2, 1] {
        let pencil = Pencil::mixed(
            &whitney.mass,
            &whitney.d1,
            MassMatrix::Diagonal(&whitney.face_areas),
        )
        .expect("valid");
        assert_eq!(pencil.dimension(), faces.len());
        let options = EigenOptions {
            threads,
            ..krylov_options(40)
        };
        let request = EigenRequest {
            pencil: &pencil,
            count: k,
            top: None,
            seed: 11,
        };
        let result = solve(&[request], &options).remove(0);
        assert_accurate("mixed, closed", &result, &reference, &n_mass);
        assert!(result.values[0].abs() <= 1e-10 * reference[reference.len() - 1]);
        if threads == 2 {
            assert_counts("mixed, closed", &pencil, &reference, &[0, 1, 30, 149, 300]);
            let bound = pencil.spectrum_upper_bound();
            let top = reference[reference.len() - 1];
            assert!(
                bound >= top && bound <= 1.5 * top,
                "bound {bound:e}, λ_max {top:e}"
            );
        }
        results.push(result);
    }
    let difference = results[0]
        .values
        .iter()
        .zip(&results[1].values)
        .skip(1)
        .map(|(a, b)| (a - b).abs() / b.abs())
        .fold(0.0, f64::max);
    assert!(
        difference <= 1e-13,
        "threads change the values by {difference:e}"
    );
}

/// A sparse SPD face mass: `diag(areas)` plus a positive coupling of the faces across each
/// interior edge (`c [[1, 1], [1, 1]]` blocks, `c` a tenth of the smaller area).
fn coupled_face_mass(whitney: &mesh_matrices::Whitney) -> sprs::CsMat<f64> {
    let nf = whitney.face_areas.len();
    let mut t = sprs::TriMat::new((nf, nf));
    for (f, &area) in whitney.face_areas.iter().enumerate() {
        t.add_triplet(f, f, area);
    }
    let by_edge = whitney.d1.to_csc();
    for column in by_edge.outer_iterator() {
        let faces: Vec<usize> = column.iter().map(|(f, _)| f).collect();
        if let [f, g] = faces[..] {
            let c = 0.1 * whitney.face_areas[f].min(whitney.face_areas[g]);
            for (a, b) in [(f, f), (f, g), (g, f), (g, g)] {
                t.add_triplet(a, b, c);
            }
        }
    }
    t.to_csc()
}

/// The three kinds in one call, as a Whitney basis computation does: the exact problem (cotan
/// stiffness, consistent mass) and the co-exact problem (mixed, sparse face mass) of the pillow,
/// and a diagonal-mass pencil; each against its dense reference.
#[test]
fn three_kinds_of_pencils_are_solved_together() {
    let (positions, faces) = mesh_matrices::pillow(12, 10, 0.3, 3.0);
    let cotan = mesh_matrices::cotan(&positions, &faces);
    let consistent = mesh_matrices::consistent_mass(&positions, &faces);
    let whitney = mesh_matrices::whitney(&positions, &faces);
    let face_mass = coupled_face_mass(&whitney);
    let exact =
        Pencil::with_mass(&cotan.stiffness, MassMatrix::Sparse(&consistent)).expect("valid");
    let coexact =
        Pencil::mixed(&whitney.mass, &whitney.d1, MassMatrix::Sparse(&face_mass)).expect("valid");
    let lumped = Pencil::new(&cotan.stiffness, &cotan.mass).expect("valid");
    let requests: Vec<EigenRequest<'_, '_>> = [&exact, &coexact, &lumped]
        .iter()
        .enumerate()
        .map(|(i, pencil)| EigenRequest {
            pencil,
            count: 70,
            top: None,
            seed: 5 + i as u64,
        })
        .collect();
    let results = solve(&requests, &krylov_options(30));
    let stiffness = dense(&cotan.stiffness);
    let (exact_reference, _) =
        dense_generalized_eigen_with_mass(stiffness.as_ref(), dense(&consistent).as_ref())
            .expect("dense");
    assert_accurate("exact", &results[0], &exact_reference, &dense(&consistent));
    let a = dense_mixed(&whitney.mass, &whitney.d1);
    let (coexact_reference, _) =
        dense_generalized_eigen_with_mass(a.as_ref(), dense(&face_mass).as_ref()).expect("dense");
    assert_accurate(
        "co-exact",
        &results[1],
        &coexact_reference,
        &dense(&face_mass),
    );
    assert_counts("co-exact", &coexact, &coexact_reference, &[0, 10, 69]);
    let (lumped_reference, _) =
        dense_generalized_eigen(stiffness.as_ref(), &cotan.mass).expect("dense");
    let lumped_mass = Mat::from_fn(cotan.mass.len(), cotan.mass.len(), |i, j| {
        if i == j {
            cotan.mass[i]
        } else {
            0.0
        }
    });
    assert_accurate("lumped", &results[2], &lumped_reference, &lumped_mass);
    for (pencil, reference) in [(&exact, &exact_reference), (&lumped, &lumped_reference)] {
        let top = reference[reference.len() - 1];
        let bound = pencil.spectrum_upper_bound();
        assert!(bound >= top, "bound {bound:e} below λ_max {top:e}");
    }
}

/// Small problems take the dense path with a sparse or mixed pencil too.
#[test]
fn small_sparse_and_mixed_pencils_use_the_dense_path() {
    let (positions, faces) = mesh_matrices::pillow(4, 4, 0.2, 1.0);
    let cotan = mesh_matrices::cotan(&positions, &faces);
    let consistent = mesh_matrices::consistent_mass(&positions, &faces);
    let whitney = mesh_matrices::whitney(&positions, &faces);
    let exact =
        Pencil::with_mass(&cotan.stiffness, MassMatrix::Sparse(&consistent)).expect("valid");
    let coexact = Pencil::mixed(
        &whitney.mass,
        &whitney.d1,
        MassMatrix::Diagonal(&whitney.face_areas),
    )
    .expect("valid");
    let requests = [
        EigenRequest {
            pencil: &exact,
            count: 10,
            top: None,
            seed: 1,
        },
        EigenRequest {
            pencil: &coexact,
            count: 10,
            top: None,
            seed: 2,
        },
    ];
    let results = solve(&requests, &EigenOptions::default());
    for result in &results {
        assert_eq!(result.statistics.factorizations(), 0, "dense path");
    }
    let (exact_reference, _) = dense_generalized_eigen_with_mass(
        dense(&cotan.stiffness).as_ref(),
        dense(&consistent).as_ref(),
    )
    .expect("dense");
    assert_accurate(
        "dense exact",
        &results[0],
        &exact_reference,
        &dense(&consistent),
    );
    let (coexact_reference, _) = dense_generalized_eigen(
        dense_mixed(&whitney.mass, &whitney.d1).as_ref(),
        &whitney.face_areas,
    )
    .expect("dense");
    let n_mass = Mat::from_fn(faces.len(), faces.len(), |i, j| {
        if i == j {
            whitney.face_areas[i]
        } else {
            0.0
        }
    });
    assert_accurate("dense co-exact", &results[1], &coexact_reference, &n_mass);
}

/// A mass or a `W` that is not positive definite is an error that names the matrix.
#[test]
fn indefinite_mass_and_w_are_named_errors() {
    let (positions, faces) = mesh_matrices::grid(3, 3, 0.0);
    let cotan = mesh_matrices::cotan(&positions, &faces);
    let whitney = mesh_matrices::whitney(&positions, &faces);
    let mut bad = sprs::TriMat::new((cotan.mass.len(), cotan.mass.len()));
    for i in 0..cotan.mass.len() {
        bad.add_triplet(i, i, if i == 5 { -1.0 } else { 1.0 });
    }
    let bad = bad.to_csc();
    match Pencil::with_mass(&cotan.stiffness, MassMatrix::Sparse(&bad)) {
        Err(SolverError::MatrixNotPositiveDefinite {
            matrix: "mass matrix",
            ..
        }) => {}
        other => panic!("expected the mass to be rejected, got {:?}", other.err()),
    }
    let negated = whitney.mass.map(|v| -v);
    match Pencil::mixed(
        &negated,
        &whitney.d1,
        MassMatrix::Diagonal(&whitney.face_areas),
    ) {
        Err(SolverError::MatrixNotPositiveDefinite { matrix: "W", .. }) => {}
        other => panic!("expected W to be rejected, got {:?}", other.err()),
    }
    let short = vec![1.0; 3];
    assert!(matches!(
        Pencil::mixed(&whitney.mass, &whitney.d1, MassMatrix::Diagonal(&short)),
        Err(SolverError::DimensionMismatch { .. })
    ));
}

/// The dense solver with a dense mass agrees with the diagonal one on a diagonal mass, and
/// rejects a mass that is not positive definite by name.
#[test]
fn dense_solver_with_a_mass_matrix() {
    let n = 30;
    let a = Mat::from_fn(n, n, |i, j| match i.abs_diff(j) {
        0 => 2.0 + (i % 4) as f64,
        1 => -1.0,
        _ => 0.0,
    });
    let diagonal: Vec<f64> = (0..n).map(|i| 0.5 + (i % 3) as f64).collect();
    let mass = Mat::from_fn(n, n, |i, j| if i == j { diagonal[i] } else { 0.0 });
    let (expected, _) = dense_generalized_eigen(a.as_ref(), &diagonal).expect("dense");
    let (values, vectors) =
        dense_generalized_eigen_with_mass(a.as_ref(), mass.as_ref()).expect("dense with a mass");
    for (v, e) in values.iter().zip(&expected) {
        assert!((v - e).abs() <= 1e-13 * e.abs().max(1.0));
    }
    let gram = vectors.transpose() * &mass * &vectors;
    assert!((&gram - Mat::<f64>::identity(n, n)).norm_max() <= 1e-13);
    let mut indefinite = mass.clone();
    indefinite[(7, 7)] = -1.0;
    assert!(matches!(
        dense_generalized_eigen_with_mass(a.as_ref(), indefinite.as_ref()),
        Err(SolverError::MatrixNotPositiveDefinite {
            matrix: "mass matrix",
            pivot: 7,
            ..
        })
    ));
}

/// `A − σM` on the union pattern of `A`, `M` and the diagonal equals the dense difference.
#[test]
fn shifted_matrix_with_a_sparse_mass_is_the_difference_on_the_union_pattern() {
    let (positions, faces) = mesh_matrices::grid(4, 3, 0.2);
    let stiffness = mesh_matrices::cotan(&positions, &faces).stiffness;
    let mass = mesh_matrices::consistent_mass(&positions, &faces);
    let sigma = 0.37;
    let upper = tvf_solvers::convert::shifted_upper_triangle_with_mass(&stiffness, &mass, sigma)
        .expect("valid");
    let expected = &dense(&stiffness) - &dense(&mass) * faer::Scale(sigma);
    let got = upper.to_dense();
    for j in 0..expected.ncols() {
        for i in 0..expected.nrows() {
            let e = if i <= j { expected[(i, j)] } else { 0.0 };
            assert!((got[(i, j)] - e).abs() <= 1e-14, "({i}, {j})");
        }
        let col = upper.symbolic().col_ptr()[j]..upper.symbolic().col_ptr()[j + 1];
        assert!(
            upper.symbolic().row_idx()[col].contains(&j),
            "diagonal of column {j}"
        );
    }
}

/// The residuals a mixed pencil reports are those of the pairs it returns, measured after the
/// M-orthogonalisation across interval boundaries: with a loose tolerance (residuals far above
/// rounding, 1e-11 to 1e-7) each field residual equals, to 1 % (plus its rounding floor), the
/// residual `√(sᵀ A s / μ) / μ`, `s = N⁻¹ (A ψ − μ N ψ)`, formed densely from the returned
/// pair, and so does the relative residual `‖A ψ − μ N ψ‖ / (‖A‖ ‖ψ‖)` up to the estimate of
/// `‖A‖`. (Reporting the residuals the intervals' refinement measured before that step, to save
/// the final pass of two solves with `W` per pair, failed this: the step raised the relative
/// residual of a pair next to a boundary from 2.7e-12 to 2.3e-11.)
#[test]
fn reported_residuals_of_a_mixed_pencil_are_those_of_the_returned_pairs() {
    let (positions, faces) = mesh_matrices::pillow(12, 14, 0.3, 3.0);
    let whitney = mesh_matrices::whitney(&positions, &faces);
    let a = dense_mixed(&whitney.mass, &whitney.d1);
    let pencil = Pencil::mixed(
        &whitney.mass,
        &whitney.d1,
        MassMatrix::Diagonal(&whitney.face_areas),
    )
    .expect("valid");
    let request = EigenRequest {
        pencil: &pencil,
        count: 150,
        top: None,
        seed: 11,
    };
    let options = EigenOptions {
        tolerance: 1e-5,
        ..krylov_options(40)
    };
    let result = solve(&[request], &options).remove(0);
    let n = faces.len();
    let norm_a = (0..n)
        .map(|j| (0..n).map(|i| a[(i, j)].abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let mut compared = 0;
    for (j, &mu) in result.values.iter().enumerate() {
        let x = result.vectors.col(j);
        let ax = &a * x;
        let r: Vec<f64> = (0..n)
            .map(|i| ax[i] - mu * whitney.face_areas[i] * x[i])
            .collect();
        let r_norm = r.iter().map(|v| v * v).sum::<f64>().sqrt();
        let x_norm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        let relative = r_norm / (norm_a * x_norm);
        let reported = result.residuals[j];
        assert!(
            reported <= 3.0 * relative + 1e-15 && relative <= 3.0 * reported + 1e-15,
            "pair {j}: relative residual reported {reported:e}, of the returned pair {relative:e}"
        );
        if mu <= 1e-8 * result.values[result.values.len() - 1] {
            continue;
        }
        let s = Mat::from_fn(n, 1, |i, _| r[i] / whitney.face_areas[i]);
        let energy = (s.transpose() * (&a * &s))[(0, 0)];
        let field = (energy.max(0.0) / mu).sqrt() / mu;
        let reported = result.field_residuals[j];
        let floor = result.field_residual_floors[j];
        assert!(
            (reported - field).abs() <= 0.01 * field + floor,
            "pair {j} (μ = {mu:e}): field residual reported {reported:e}, of the returned pair \
             {field:e} (floor {floor:e})"
        );
        compared += 1;
    }
    assert!(compared >= 140, "{compared} field residuals compared");
}

/// The co-exact Whitney pencil counts right at shifts below its smallest nonzero eigenvalue
/// `λ₁` down to `1e-10 λ₁` and below 0: what lies below is the kernel of `A` alone. (Further
/// down, about `1e-16` of the top of the spectrum, the pivots on the kernel of `d1` are
/// rounding noise, in `C(σ)` as in the saddle matrix; see `pencil.rs`.)
#[test]
fn the_mixed_pencil_counts_right_below_its_smallest_nonzero_eigenvalue() {
    let (positions, faces) = mesh_matrices::pillow(12, 10, 0.3, 3.0);
    let whitney = mesh_matrices::whitney(&positions, &faces);
    let (reference, _) = dense_generalized_eigen(
        dense_mixed(&whitney.mass, &whitney.d1).as_ref(),
        &whitney.face_areas,
    )
    .expect("dense");
    let lambda1 = reference
        .iter()
        .copied()
        .find(|&v| v > 1e-8 * reference[reference.len() - 1])
        .expect("a nonzero eigenvalue");
    let pencil = Pencil::mixed(
        &whitney.mass,
        &whitney.d1,
        MassMatrix::Diagonal(&whitney.face_areas),
    )
    .expect("valid");
    let shifts = (0..=10)
        .map(|k| 0.5 * lambda1 * 10f64.powi(-k))
        .chain([-lambda1]);
    for t in shifts {
        let count = pencil.count_below(t).expect("counts");
        let expected = reference.iter().filter(|&&v| v < count.shift).count();
        assert_eq!(
            count.below, expected,
            "count below {t:e} (at {:e})",
            count.shift
        );
    }
}
