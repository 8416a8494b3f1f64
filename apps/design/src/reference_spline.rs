//! [`reference_spline`]: the full-resolution tangential vector field spline, for checking the
//! reduced [`crate::SplineSession`] on small meshes.

use crate::augmented_system::{assemble, AugmentedFactor, ConstraintTerms, PatternUnion};
use crate::constraint::{CompiledConstraint, SparseRow};
use crate::error::DesignError;
use crate::galerkin_blocks::{EnergyWeights, GalerkinBlocks};
use crate::regularization::mean_eigenvalue;
use crate::soft_system::Factoring;
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use sprs::CsMat;
use tvf_core::discretization::sparse::{diagonal, linear_combination, mul_vec};
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_solvers::iterative_refinement::{
    accurate_residual, exact, refined_solve, DoubleDouble, SolveReport,
};
use tvf_solvers::{FactorParallelism, FillOrdering, SparseCholesky};

/// The full spline and how well its solves went.
#[derive(Debug, Clone)]
pub struct ReferenceSpline {
    /// The field `x` (`n1` values).
    pub field: Vec<f64>,
    /// Lagrange multipliers `μ`, one per constraint row.
    pub multipliers: Vec<f64>,
    /// Residual histories of the `n_c` solves with `A` (see [`SolveReport`]); the worst final one
    /// is the accuracy of `A⁻¹ C̃ᵀ`.
    pub solve_reports: Vec<SolveReport>,
}

/// Relative weight (of the mean eigenvalue of the Hodge–Laplacian) of the terms the factored
/// system of a complex with non-diagonal masses adds where `ε` or `ω` is zero: a screening
/// `τ M1` (`τ = 1e-10 λ̄`, as [`crate::default_regularization`]) and a Dirichlet term `α S`
/// (`α = 1e-8 λ̄`). The refinement removes them.
const SCREENING_SHIFT: f64 = 1e-10;
const DIRICHLET_SHIFT: f64 = 1e-8;

/// Minimises `xᵀ (B + ωS + εM1) x` subject to `C̃ x = c` at full resolution (`n1` unknowns).
///
/// Null-space-free Schur approach: `Z = A⁻¹ C̃ᵀ` for `A = B + ωS + εM1` (one refined solve per
/// constraint row), `(C̃ Z) μ = c` dense, `x = Z μ`. Where `S` is a sparse matrix and `M1`
/// diagonal, `A` is formed and factored by a sparse Cholesky. Otherwise `B = S M1⁻¹ S` (and
/// possibly `S`) is dense: the solves go through the augmented system of
/// [`crate::FullSoftDesign`] for `εM1 + ωS + S M1⁻¹ S` (auxiliary unknowns `y = M1⁻¹ S x` and the
/// nodal quantities of the non-diagonal masses), refined on `A` applied through mass solves; a
/// zero `ε` or `ω` is replaced in the factored system by a small multiple of the mean eigenvalue,
/// which the refinement removes. On a genus-0 mesh `ε = 0` gives exactly the spline of
/// Section 7; on genus > 0 `A` is singular on the harmonic fields and `ε > 0` is needed (the
/// reduced solver instead replaces the harmonic eigenvalues, so the two agree only
/// approximately there). `O(n_c)` sparse solves: small meshes.
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
    let rows: Vec<(&SparseRow, f64)> = constraints
        .iter()
        .flat_map(|c| c.rows.iter().zip(c.values.iter().copied()))
        .collect();
    let (z, solve_reports) = match (
        complex.dirichlet_energy().as_sparse(),
        complex.biharmonic_energy().as_sparse(),
        complex.m1().diagonal_values(),
    ) {
        (Some(dirichlet), Some(biharmonic), Some(m1)) => {
            sparse_columns(dirichlet, biharmonic, m1, omega, epsilon, &rows)?
        }
        _ => augmented_columns(complex, omega, epsilon, &rows)?,
    };
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
    let mut field = vec![0.0; complex.field_dimension()];
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

/// `Z = A⁻¹ C̃ᵀ` (one column per row) with the sparse Cholesky factorization of
/// `A = B + ωS + εM1` (`S`, `B` sparse, `M1` diagonal).
fn sparse_columns(
    dirichlet: &CsMat<f64>,
    biharmonic: &CsMat<f64>,
    m1: &[f64],
    omega: f64,
    epsilon: f64,
    rows: &[(&SparseRow, f64)],
) -> Result<(Vec<Vec<f64>>, Vec<SolveReport>), DesignError> {
    let energy: CsMat<f64> = linear_combination(1.0, biharmonic, omega, dirichlet);
    let screened: Vec<f64> = m1.iter().map(|m| epsilon * m).collect();
    let matrix = linear_combination(1.0, &energy, 1.0, &diagonal(&screened));
    let factor = SparseCholesky::new(&matrix)?;
    let n = matrix.rows();
    let mut z: Vec<Vec<f64>> = Vec::with_capacity(rows.len());
    let mut solve_reports = Vec::with_capacity(rows.len());
    for (row, _) in rows {
        let rhs = dense_row(row, n)?;
        let (column, report) = refined_solve(
            |x| mul_vec(&matrix, x),
            |x| accurate_residual(&matrix, x, &rhs),
            &rhs,
            |r| factor.solve(r),
        );
        z.push(column);
        solve_reports.push(report);
    }
    Ok((z, solve_reports))
}

/// `Z = A⁻¹ C̃ᵀ` (one column per row) for `A = εM1 + ωS + S M1⁻¹ S` of a complex with
/// non-diagonal masses: solves with the augmented system (energy weights `τ = ε`, `α = ω`,
/// `β = 1`, zeros replaced by [`SCREENING_SHIFT`] and [`DIRICHLET_SHIFT`]) refined on `A`.
fn augmented_columns<H: HodgeComplex + ?Sized>(
    complex: &H,
    omega: f64,
    epsilon: f64,
    rows: &[(&SparseRow, f64)],
) -> Result<(Vec<Vec<f64>>, Vec<SolveReport>), DesignError> {
    if epsilon == 0.0 && complex.topology().harmonic_dimension > 0 {
        return Err(DesignError::NotPositiveDefinite(format!(
            "B + ωS on a surface with {} harmonic fields (use a positive epsilon)",
            complex.topology().harmonic_dimension
        )));
    }
    let blocks = GalerkinBlocks::new(complex);
    let energy = EnergyWeights {
        screening: epsilon,
        dirichlet: omega,
        biharmonic: 1.0,
    };
    let scale = mean_eigenvalue(complex);
    let factored = EnergyWeights {
        screening: if epsilon > 0.0 {
            epsilon
        } else {
            SCREENING_SHIFT * scale
        },
        dirichlet: if omega > 0.0 {
            omega
        } else {
            DIRICHLET_SHIFT * scale
        },
        biharmonic: 1.0,
    };
    let (upper, layout) = assemble(
        &blocks,
        factored,
        &ConstraintTerms::default(),
        &PatternUnion::default(),
    )?;
    let factor = AugmentedFactor::new(
        &upper,
        layout,
        &blocks,
        Factoring {
            ordering: FillOrdering::NestedDissection,
            parallelism: FactorParallelism::default(),
        },
    )?;
    let n = blocks.field.space_len();
    let mut z: Vec<Vec<f64>> = Vec::with_capacity(rows.len());
    let mut solve_reports = Vec::with_capacity(rows.len());
    for (row, _) in rows {
        let rhs = blocks.field.gather(&dense_row(row, n)?);
        let (column, report) = refined_solve(
            |x| blocks.energy(energy, x),
            |x| {
                blocks
                    .accurate_energy(energy, &exact(x))
                    .into_iter()
                    .zip(&rhs)
                    .map(|(ax, &b)| {
                        let r = DoubleDouble::difference(b, ax);
                        r.hi + r.lo
                    })
                    .collect()
            },
            &rhs,
            |r| factor.solve_field(r),
        );
        z.push(blocks.field.scatter(&column));
        solve_reports.push(report);
    }
    Ok((z, solve_reports))
}

/// A constraint row as a dense vector of `n` field coefficients.
fn dense_row(row: &SparseRow, n: usize) -> Result<Vec<f64>, DesignError> {
    let mut dense = vec![0.0; n];
    for &(j, a) in row {
        if j >= n {
            return Err(DesignError::DimensionMismatch {
                what: "constraint row column (must be < n1)",
                expected: n,
                actual: j,
            });
        }
        dense[j] += a;
    }
    Ok(dense)
}
