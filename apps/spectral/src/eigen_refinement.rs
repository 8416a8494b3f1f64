//! One refinement step for eigenpairs from an iterative solver: a block inverse iteration below
//! the spectrum followed by a Rayleigh–Ritz projection.
//!
//! Why: Lemma 1 maps an eigenfunction error `r = Aφ − λMφ` to the field residual
//! `‖L Φ − λ Φ‖ ≈ ‖d0 M⁻¹ r‖ / √λ`, which amplifies the high-frequency part of `r` by the
//! gradient (≈ 1/h). A Krylov solver that has converged to `1e-12` in the shift-inverted metric
//! leaves such components at a level that shows up as `1e-8` in the fields. One step of
//! `Z = (A − σM)⁻¹ M X` with `σ < 0` damps every component of eigenvalue `λ_m` by
//! `(λ − σ)/(λ_m − σ)` (tiny for high frequencies), and Rayleigh–Ritz on `span Z` then restores
//! `A`- and `M`-orthogonality inside clusters of close eigenvalues.

use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::{Accum, Mat};
use rayon::prelude::*;
use sprs::CsMat;
use tvf_core::discretization::sparse::{diagonal, linear_combination, mul_vec};
use tvf_solvers::{dense_generalized_eigen, SolverError, SparseCholesky};

/// Refines the lowest eigenpairs `(values, vectors)` (`n × t`, `M`-orthonormal, ascending; may
/// include kernel vectors) of `A x = λ M x`. Returns new ascending values and `M`-orthonormal
/// vectors spanning the inverse-iterated subspace. `first_nonzero` sets the shift
/// `σ = −first_nonzero / 10`.
pub(crate) fn refine_eigenpairs(
    stiffness: &CsMat<f64>,
    mass: &[f64],
    values: &[f64],
    vectors: &Mat<f64>,
    first_nonzero: f64,
) -> Result<(Vec<f64>, Mat<f64>), SolverError> {
    let (n, t) = (vectors.nrows(), vectors.ncols());
    if t == 0 {
        return Ok((Vec::new(), Mat::zeros(n, 0)));
    }
    let shift = 0.1
        * if first_nonzero > 0.0 {
            first_nonzero
        } else {
            1.0
        };
    let shifted = linear_combination(1.0, stiffness, shift, &diagonal(mass));
    let cholesky = SparseCholesky::new(&shifted)?;
    // Z = (A + s M)⁻¹ M X, column j scaled by (λ_j + s) so that Z ≈ X.
    let mx = Mat::from_fn(n, t, |i, j| mass[i] * vectors[(i, j)]);
    let mut z = cholesky.solve_many(mx.as_ref());
    for (j, &value) in values.iter().enumerate().take(t) {
        let scale = value.max(0.0) + shift;
        z.col_mut(j).iter_mut().for_each(|x| *x *= scale);
    }
    // Projected pencil (Zᵀ A Z, Zᵀ M Z), both t × t.
    let az = sparse_times(stiffness, &z);
    let mz = Mat::from_fn(n, t, |i, j| mass[i] * z[(i, j)]);
    let a_small = symmetric_inner(&z, &az);
    let m_small = symmetric_inner(&z, &mz);
    // M-orthonormalise: Zᵀ M Z = V D Vᵀ, W = V D^{-1/2} (Z W is M-orthonormal).
    let ones = vec![1.0; t];
    let (d, v) = dense_generalized_eigen(m_small.as_ref(), &ones)?;
    if d.iter().any(|&x| x.is_nan() || x <= 1e-12 * d[t - 1]) {
        return Err(SolverError::NoConvergence {
            reason: "refinement subspace lost rank".into(),
        });
    }
    let w = Mat::from_fn(t, t, |i, j| v[(i, j)] / d[j].sqrt());
    let h = w.transpose() * &a_small * &w;
    let (theta, y) = dense_generalized_eigen(h.as_ref(), &ones)?;
    let combination = &w * &y;
    let refined = &z * &combination;
    Ok((theta, refined))
}

/// `Zᵀ Y` (`t × t`) for `Z, Y: n × t` when it is symmetric (`Y = S Z` with symmetric `S`): only
/// the lower triangle is multiplied (half the flops of a full product), then mirrored.
fn symmetric_inner(z: &Mat<f64>, y: &Mat<f64>) -> Mat<f64> {
    let t = z.ncols();
    let mut product = Mat::<f64>::zeros(t, t);
    triangular::matmul(
        product.as_mut(),
        BlockStructure::TriangularLower,
        Accum::Replace,
        z.transpose(),
        BlockStructure::Rectangular,
        y.as_ref(),
        BlockStructure::Rectangular,
        1.0,
        faer::get_global_parallelism(),
    );
    for j in 0..t {
        for i in 0..j {
            product[(i, j)] = product[(j, i)];
        }
    }
    product
}

/// `A X` for a sparse CSR/CSC `A` and dense `X`, column by column in parallel.
fn sparse_times(a: &CsMat<f64>, x: &Mat<f64>) -> Mat<f64> {
    let (n, t) = (x.nrows(), x.ncols());
    let columns: Vec<Vec<f64>> = (0..t)
        .into_par_iter()
        .map(|j| {
            let column: Vec<f64> = (0..n).map(|i| x[(i, j)]).collect();
            mul_vec(a, &column)
        })
        .collect();
    Mat::from_fn(a.rows(), t, |i, j| columns[j][i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symmetric_inner_matches_the_full_product() {
        let (n, t) = (300, 41);
        let z = Mat::from_fn(n, t, |i, j| ((i * 7 + j * 13) % 29) as f64 / 14.0 - 1.0);
        // Y = S Z with S = diag(1..n) + (shift by one, both ways): symmetric.
        let y = Mat::from_fn(n, t, |i, j| {
            let mut v = (1 + i) as f64 * z[(i, j)];
            if i > 0 {
                v += 0.5 * z[(i - 1, j)];
            }
            if i + 1 < n {
                v += 0.5 * z[(i + 1, j)];
            }
            v
        });
        let full = z.transpose() * &y;
        let half = symmetric_inner(&z, &y);
        let scale = full.norm_max();
        assert!((&full - &half).norm_max() <= 1e-12 * scale);
        assert_eq!(half, half.transpose().to_owned());
    }
}
