//! Dense generalized symmetric eigensolver `A x = λ M x` with diagonal `M`: the reference
//! path (test oracle) and the fallback of [`crate::lowest_eigenpairs`] for small problems.

use crate::error::SolverError;
use faer::{Mat, MatRef, Side};

/// All eigenpairs of `A x = λ M x` for a dense symmetric `n × n` matrix `A` and a positive
/// diagonal mass `M = diag(mass_diagonal)`.
///
/// Computed with faer's self-adjoint eigensolver on `M^{-1/2} A M^{-1/2}` (symmetrised, so
/// only the symmetric part of `A` matters); eigenvectors are mapped back with `M^{-1/2}`.
/// Returns eigenvalues in ascending order and the `n × n` eigenvector matrix `X` (column `j`
/// belongs to eigenvalue `j`) with `Xᵀ M X = I`.
///
/// Errors: [`SolverError::NotSquare`], [`SolverError::DimensionMismatch`],
/// [`SolverError::MassNotPositive`], [`SolverError::NonFinite`],
/// [`SolverError::NoConvergence`] if faer's QR iteration fails.
pub fn dense_generalized_eigen(
    a: MatRef<'_, f64>,
    mass_diagonal: &[f64],
) -> Result<(Vec<f64>, Mat<f64>), SolverError> {
    let n = a.nrows();
    if a.ncols() != n {
        return Err(SolverError::NotSquare {
            rows: n,
            cols: a.ncols(),
        });
    }
    if mass_diagonal.len() != n {
        return Err(SolverError::DimensionMismatch {
            context: "mass diagonal length",
            expected: n,
            actual: mass_diagonal.len(),
        });
    }
    check_mass(mass_diagonal)?;
    for j in 0..n {
        for i in 0..n {
            let value = a[(i, j)];
            if !value.is_finite() {
                return Err(SolverError::NonFinite {
                    context: "dense matrix",
                    row: i,
                    col: j,
                    value,
                });
            }
        }
    }
    let inv_sqrt: Vec<f64> = mass_diagonal.iter().map(|m| 1.0 / m.sqrt()).collect();
    let scaled = Mat::from_fn(n, n, |i, j| {
        0.5 * (a[(i, j)] + a[(j, i)]) * inv_sqrt[i] * inv_sqrt[j]
    });
    let (values, vectors) = symmetric_eigen(scaled.as_ref())?;
    let x = Mat::from_fn(n, n, |i, j| vectors[(i, j)] * inv_sqrt[i]);
    Ok((values, x))
}

/// Eigen-decomposition of a dense symmetric matrix (lower triangle read): ascending values and
/// orthonormal eigenvectors.
pub(crate) fn symmetric_eigen(a: MatRef<'_, f64>) -> Result<(Vec<f64>, Mat<f64>), SolverError> {
    let n = a.nrows();
    if n == 0 {
        return Ok((Vec::new(), Mat::zeros(0, 0)));
    }
    let evd = a
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| SolverError::NoConvergence {
            reason: format!("dense self-adjoint eigensolver failed: {e:?}"),
        })?;
    let s = evd.S().column_vector();
    let values: Vec<f64> = (0..n).map(|i| s[i]).collect();
    Ok((values, evd.U().to_owned()))
}

/// Checks that every mass entry is finite and positive.
pub(crate) fn check_mass(mass_diagonal: &[f64]) -> Result<(), SolverError> {
    for (index, &value) in mass_diagonal.iter().enumerate() {
        if !value.is_finite() {
            return Err(SolverError::NonFinite {
                context: "mass diagonal",
                row: index,
                col: 0,
                value,
            });
        }
        if value <= 0.0 {
            return Err(SolverError::MassNotPositive { index, value });
        }
    }
    Ok(())
}
