//! The mass matrix `M` of a pencil: a positive diagonal ([`MassMatrix::Diagonal`], lumped masses)
//! or a sparse symmetric positive-definite matrix ([`MassMatrix::Sparse`], consistent Galerkin
//! masses), and [`Mass`], the view of either that the eigensolver's kernels take: every `M x`,
//! `xᵀ M y` and M-norm dispatches on it once, at the top of a kernel, so a diagonal mass runs
//! the same instructions as before sparse masses existed.

use super::symmetric_products::{gather_times, Row};
use crate::convert::upper_triangle_csc;
use crate::error::SolverError;
use crate::sparse_ldlt::SparseLdlt;
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use faer::{Mat, MatMut, MatRef, Par};

/// The mass matrix of a pencil, as given by the caller.
#[derive(Debug, Clone, Copy)]
pub enum MassMatrix<'a> {
    /// The `n` positive entries of a diagonal mass (lumped masses; units of area).
    Diagonal(&'a [f64]),
    /// An `n × n` sparse symmetric positive-definite mass (e.g. the consistent P1 mass
    /// `(|T|/12)(1 + δ_ij)` per triangle), CSC or CSR, in full symmetric storage (both
    /// triangles) or upper-triangular storage: the strict lower triangle is ignored.
    Sparse(&'a sprs::CsMat<f64>),
}

/// A mass matrix as the kernels see it, rows in the order of the vectors it multiplies.
#[derive(Clone, Copy)]
pub(crate) enum Mass<'a> {
    /// The diagonal of `M`.
    Diagonal(&'a [f64]),
    /// `M` in full symmetric CSC storage (a column is also a row).
    Sparse(SparseColMatRef<'a, usize, f64>),
}

impl Mass<'_> {
    /// `M x` (`n × s`) for the `n × s` block `x`.
    pub(crate) fn times(self, x: MatRef<'_, f64>) -> Mat<f64> {
        let mut out = Mat::<f64>::zeros(x.nrows(), x.ncols());
        self.times_into(x, out.as_mut());
        out
    }

    /// `out ← M x` for the `n × s` blocks `x` and `out`.
    pub(crate) fn times_into(self, x: MatRef<'_, f64>, mut out: MatMut<'_, f64>) {
        match self {
            Mass::Diagonal(mass) => {
                for j in 0..x.ncols() {
                    for (i, m) in mass.iter().enumerate() {
                        out[(i, j)] = m * x[(i, j)];
                    }
                }
            }
            Mass::Sparse(m) => super::symmetric_products::symmetric_times(out, m, x, Par::Seq),
        }
    }

    /// `out ← M x` for a packed chunk `x` (`n` rows).
    pub(crate) fn times_rows(self, x: &[Row], out: &mut [Row]) {
        match self {
            Mass::Diagonal(mass) => {
                for ((target, row), m) in out.iter_mut().zip(x).zip(mass) {
                    *target = std::array::from_fn(|j| m * row[j]);
                }
            }
            Mass::Sparse(m) => gather_times(m, x, out),
        }
    }
}

/// `rows ← M⁻¹ rows` for packed rows in the input order, with the Cholesky factorization
/// `factor` of `M` (`work`: the rows in its elimination order, resized as needed).
pub(crate) fn solve_mass_rows(factor: &SparseLdlt, rows: &mut [Row], work: &mut Vec<Row>) {
    let Some(order) = factor.elimination_order() else {
        factor.solve_rows_in_elimination_order(rows);
        return;
    };
    work.clear();
    work.extend(order.iter().map(|&row| rows[row]));
    factor.solve_rows_in_elimination_order(work);
    for (solved, &row) in work.iter().zip(order) {
        rows[row] = *solved;
    }
}

/// Full symmetric storage of the sparse SPD mass given by the caller: its upper triangle and
/// the mirror image of it.
///
/// Errors: [`SolverError::NotSquare`], [`SolverError::NonFinite`],
/// [`SolverError::DimensionMismatch`] if it is not `n × n`.
pub(crate) fn full_symmetric_mass(
    mass: &sprs::CsMat<f64>,
    n: usize,
    context: &'static str,
) -> Result<SparseColMat<usize, f64>, SolverError> {
    let upper = upper_triangle_csc(mass)?;
    if upper.nrows() != n {
        return Err(SolverError::DimensionMismatch {
            context,
            expected: n,
            actual: upper.nrows(),
        });
    }
    symmetric_full(&upper)
}

/// Full symmetric storage of the matrix whose upper triangle is `upper`.
pub(crate) fn symmetric_full(
    upper: &SparseColMat<usize, f64>,
) -> Result<SparseColMat<usize, f64>, SolverError> {
    let n = upper.nrows();
    let mut triplets = Vec::with_capacity(2 * upper.val().len());
    let col_ptr = upper.symbolic().col_ptr();
    let row_idx = upper.symbolic().row_idx();
    for j in 0..n {
        for p in col_ptr[j]..col_ptr[j + 1] {
            let i = row_idx[p];
            triplets.push(Triplet::new(i, j, upper.val()[p]));
            if i != j {
                triplets.push(Triplet::new(j, i, upper.val()[p]));
            }
        }
    }
    SparseColMat::try_new_from_triplets(n, n, &triplets)
        .map_err(|e| SolverError::Factorization(format!("{e:?}")))
}

/// `P M Pᵀ` for the full symmetric `m` and the order `order` (row `i` of the result is row
/// `order[i]` of `m`): the mass in the order of the Krylov vectors, formed once per pencil.
pub(crate) fn permuted(
    m: SparseColMatRef<'_, usize, f64>,
    order: &[usize],
) -> Result<SparseColMat<usize, f64>, SolverError> {
    let n = m.nrows();
    let mut position = vec![0usize; n];
    for (i, &row) in order.iter().enumerate() {
        position[row] = i;
    }
    let col_ptr = m.symbolic().col_ptr();
    let row_idx = m.symbolic().row_idx();
    let mut triplets = Vec::with_capacity(m.val().len());
    for j in 0..n {
        for p in col_ptr[j]..col_ptr[j + 1] {
            triplets.push(Triplet::new(position[row_idx[p]], position[j], m.val()[p]));
        }
    }
    SparseColMat::try_new_from_triplets(n, n, &triplets)
        .map_err(|e| SolverError::Factorization(format!("{e:?}")))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The permuted mass times permuted vectors is the permuted product, and the packed and
    /// column products agree with the dense one.
    #[test]
    fn permuted_mass_products_are_the_permuted_products() {
        let n = 57;
        let mut t = sprs::TriMat::new((n, n));
        for i in 0..n {
            t.add_triplet(i, i, 2.0 + (i % 3) as f64);
            for offset in [1, 5] {
                if i + offset < n {
                    let v = 0.3 + ((i * 7) % 5) as f64 / 10.0;
                    t.add_triplet(i, i + offset, v);
                    t.add_triplet(i + offset, i, v);
                }
            }
        }
        let full = full_symmetric_mass(&t.to_csc(), n, "test mass").expect("valid");
        let dense = full.to_dense();
        let order: Vec<usize> = (0..n).map(|i| (i * 11) % n).collect();
        let p = permuted(full.as_ref(), &order).expect("valid");
        let x = Mat::from_fn(n, 3, |i, j| ((i * 13 + j * 7) % 17) as f64 - 8.0);
        let expected = &dense * &x;
        let product = Mass::Sparse(full.as_ref()).times(x.as_ref());
        assert!((&product - &expected).norm_max() <= 1e-12 * expected.norm_max());
        let px = Mat::from_fn(n, 3, |i, j| x[(order[i], j)]);
        let ppx = Mass::Sparse(p.as_ref()).times(px.as_ref());
        let rows: Vec<Row> = (0..n)
            .map(|i| std::array::from_fn(|j| if j < 3 { px[(i, j)] } else { 0.0 }))
            .collect();
        let mut packed = vec![[0.0; 8]; n];
        Mass::Sparse(p.as_ref()).times_rows(&rows, &mut packed);
        for i in 0..n {
            for j in 0..3 {
                let e = expected[(order[i], j)];
                assert!((ppx[(i, j)] - e).abs() <= 1e-12 * expected.norm_max());
                assert!((packed[i][j] - e).abs() <= 1e-12 * expected.norm_max());
            }
        }
    }
}
