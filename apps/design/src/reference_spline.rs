//! [`reference_spline`]: the full-resolution tangential vector field spline, for checking the
//! reduced [`crate::SplineSession`] on small meshes.

use crate::constraint::CompiledConstraint;
use crate::error::DesignError;
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use sprs::CsMat;
use tvf_core::discretization::sparse::{diagonal, linear_combination, mul_vec};
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_solvers::iterative_refinement::{accurate_residual, refined_solve, SolveReport};
use tvf_solvers::SparseCholesky;

/// The full spline and how well its solves went.
#[derive(Debug, Clone)]
pub struct ReferenceSpline {
    /// The field `x` (`2F` values).
    pub field: Vec<f64>,
    /// Lagrange multipliers `μ`, one per constraint row.
    pub multipliers: Vec<f64>,
    /// Residual histories of the `n_c` solves with `A` (see [`SolveReport`]); the worst final one
    /// is the accuracy of `A⁻¹ C̃ᵀ`.
    pub solve_reports: Vec<SolveReport>,
}

/// Minimises `xᵀ (B + ωS + εM_X) x` subject to `C̃ x = c` at full resolution (`2F` unknowns).
///
/// Null-space-free Schur approach: `Z = A⁻¹ C̃ᵀ` with the sparse Cholesky of
/// `A = B + ωS + εM_X` (one refined solve per constraint row), `(C̃ Z) μ = c` dense, `x = Z μ`.
/// On a genus-0 mesh `ε = 0` gives exactly the spline of Section 7; on genus > 0 `A` is singular
/// on the harmonic fields and `ε > 0` is needed (the reduced solver instead replaces the harmonic
/// eigenvalues, so the two agree only approximately there). `O(n_c)` sparse solves: small meshes.
pub fn reference_spline<H: HodgeComplex + ?Sized>(
    complex: &H,
    omega: f64,
    epsilon: f64,
    constraints: &[CompiledConstraint],
) -> Result<ReferenceSpline, DesignError> {
    for (what, value) in [("omega", omega), ("epsilon", epsilon)] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(DesignError::BadParameter { what, value });
        }
    }
    let (Some(dirichlet), Some(biharmonic), Some(m1)) = (
        complex.dirichlet_energy().as_sparse(),
        complex.biharmonic_energy().as_sparse(),
        complex.m1().diagonal_values(),
    ) else {
        return Err(DesignError::NotSparse {
            what: "the reference spline",
        });
    };
    let energy: CsMat<f64> = linear_combination(1.0, biharmonic, omega, dirichlet);
    let screened: Vec<f64> = m1.iter().map(|m| epsilon * m).collect();
    let matrix = linear_combination(1.0, &energy, 1.0, &diagonal(&screened));
    let factor = SparseCholesky::new(&matrix)?;
    let n = matrix.rows();
    let rows: Vec<(&Vec<(usize, f64)>, f64)> = constraints
        .iter()
        .flat_map(|c| c.rows.iter().zip(c.values.iter().copied()))
        .collect();
    let mut z: Vec<Vec<f64>> = Vec::with_capacity(rows.len());
    let mut solve_reports = Vec::with_capacity(rows.len());
    for (row, _) in &rows {
        let mut rhs = vec![0.0; n];
        for &(j, a) in row.iter() {
            if j >= n {
                return Err(DesignError::DimensionMismatch {
                    what: "constraint row column (must be < 2F)",
                    expected: n,
                    actual: j,
                });
            }
            rhs[j] += a;
        }
        let (column, report) = refined_solve(
            |x| mul_vec(&matrix, x),
            |x| accurate_residual(&matrix, x, &rhs),
            &rhs,
            |r| factor.solve(r),
        );
        z.push(column);
        solve_reports.push(report);
    }
    let nc = rows.len();
    let schur = Mat::from_fn(nc, nc, |i, j| {
        rows[i].0.iter().map(|&(k, a)| a * z[j][k]).sum::<f64>()
    });
    let schur = Mat::from_fn(nc, nc, |i, j| 0.5 * (schur[(i, j)] + schur[(j, i)]));
    let llt = schur.llt(Side::Lower).map_err(|_| {
        DesignError::NotPositiveDefinite(
            "the full-resolution Schur complement C̃ A⁻¹ C̃ᵀ (dependent constraints?)".into(),
        )
    })?;
    let c = Mat::from_fn(nc, 1, |i, _| rows[i].1);
    let mu = llt.solve(&c);
    let mut field = vec![0.0; n];
    for (k, column) in z.iter().enumerate() {
        for (x, zk) in field.iter_mut().zip(column) {
            *x += mu[(k, 0)] * zk;
        }
    }
    Ok(ReferenceSpline {
        field,
        multipliers: (0..nc).map(|k| mu[(k, 0)]).collect(),
        solve_reports,
    })
}
