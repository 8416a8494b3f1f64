//! Dense generalized symmetric eigensolver `A x = λ M x` with a diagonal `M`
//! ([`dense_generalized_eigen`]) or a dense SPD `M` ([`dense_generalized_eigen_with_mass`]):
//! the reference path (test oracle) and the fallback of [`crate::lowest_eigenpairs`] for small
//! problems.

use crate::error::SolverError;
use crate::symmetric_eigen::symmetric_eigen;
use faer::{Mat, MatRef, Par, Side};

/// All eigenpairs of `A x = λ M x` for a dense symmetric `n × n` matrix `A` and a positive
/// diagonal mass `M = diag(mass_diagonal)`.
///
/// Computed with [`symmetric_eigen`] on `M^{-1/2} A M^{-1/2}` (symmetrised, so
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

/// All eigenpairs of `A x = λ M x` for dense symmetric `n × n` matrices `A` and `M`, `M`
/// positive definite (e.g. a consistent mass, or the dense form of a sparse one).
///
/// With the Cholesky factorization `M = L Lᵀ`, the eigenpairs of the symmetric
/// `C = L⁻¹ A L⁻ᵀ` (symmetrised: only the symmetric parts of `A` and `M` matter, `M` read from
/// its lower triangle) are mapped back by `X = L⁻ᵀ Y`. Returns ascending eigenvalues and the
/// `n × n` eigenvectors `X` (column `j` for eigenvalue `j`) with `Xᵀ M X = I`.
///
/// Errors: [`SolverError::NotSquare`], [`SolverError::DimensionMismatch`],
/// [`SolverError::NonFinite`], [`SolverError::MatrixNotPositiveDefinite`] naming the mass
/// matrix, [`SolverError::NoConvergence`] if faer's QR iteration fails.
pub fn dense_generalized_eigen_with_mass(
    a: MatRef<'_, f64>,
    mass: MatRef<'_, f64>,
) -> Result<(Vec<f64>, Mat<f64>), SolverError> {
    let n = a.nrows();
    for (context, m) in [("dense matrix", a), ("dense mass matrix", mass)] {
        if m.ncols() != m.nrows() {
            return Err(SolverError::NotSquare {
                rows: m.nrows(),
                cols: m.ncols(),
            });
        }
        if m.nrows() != n {
            return Err(SolverError::DimensionMismatch {
                context: "mass matrix dimension",
                expected: n,
                actual: m.nrows(),
            });
        }
        for j in 0..n {
            for i in 0..n {
                let value = m[(i, j)];
                if !value.is_finite() {
                    return Err(SolverError::NonFinite {
                        context,
                        row: i,
                        col: j,
                        value,
                    });
                }
            }
        }
    }
    let symmetric = Mat::from_fn(n, n, |i, j| 0.5 * (mass[(i, j)] + mass[(j, i)]));
    let llt = symmetric.as_ref().llt(Side::Lower).map_err(|_| {
        SolverError::MatrixNotPositiveDefinite {
            matrix: "mass matrix",
            pivot: first_non_positive_pivot(symmetric.as_ref()),
            value: 0.0,
        }
    })?;
    let l = llt.L();
    // C = L⁻¹ A L⁻ᵀ: two triangular solves (Y = L⁻¹ A, C = L⁻¹ Yᵀ).
    let mut y = Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]));
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, y.as_mut(), Par::Seq);
    let mut c = y.transpose().to_owned();
    faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, c.as_mut(), Par::Seq);
    let c = Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]));
    let (values, mut vectors) = symmetric_eigen(c.as_ref())?;
    faer::linalg::triangular_solve::solve_upper_triangular_in_place(
        l.transpose(),
        vectors.as_mut(),
        Par::Seq,
    );
    Ok((values, vectors))
}

/// The first row/column where the Cholesky factorization of the symmetric `m` (lower triangle
/// read) meets a pivot that is not positive (`n` if none): one right-looking elimination.
fn first_non_positive_pivot(m: MatRef<'_, f64>) -> usize {
    let n = m.nrows();
    let mut l = Mat::from_fn(n, n, |i, j| if i >= j { m[(i, j)] } else { 0.0 });
    for k in 0..n {
        let pivot = l[(k, k)];
        if !(pivot > 0.0 && pivot.is_finite()) {
            return k;
        }
        let root = pivot.sqrt();
        for i in k..n {
            l[(i, k)] /= root;
        }
        for j in k + 1..n {
            for i in j..n {
                l[(i, j)] -= l[(i, k)] * l[(j, k)];
            }
        }
    }
    n
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
