//! [`LinearOperator`]: a derived operator of the seam — a sparse matrix where it is one, else a
//! sum of products of sparse matrices and masses applied factor by factor, never formed densely.

use super::mass::{sparse_times_block, Mass, MassForm, MassStorage};
use super::sparse::{mul_transpose_vec, mul_vec, product, to_csr, transpose};
use faer::{Mat, MatRef};
use sprs::CsMat;
use std::sync::Arc;

/// A linear map `ℝⁿ → ℝᵐ` derived from the five matrices of a complex.
///
/// Where every mass it involves is diagonal (or sparse and not inverted) the operator is a sparse
/// matrix ([`LinearOperator::Sparse`], e.g. every operator of a lumped complex). An inverse of a
/// sparse mass (`M0⁻¹` of a consistent P1 mass, the Whitney `M1⁻¹`) or a mass stored as its
/// inverse (a consistent co-potential mass's `M2`) is dense; operators containing one are kept as
/// [`LinearOperator::Composed`] and applied through sparse products and the mass's cached sparse
/// Cholesky factorization.
#[derive(Debug, Clone)]
pub enum LinearOperator {
    /// A sparse matrix (CSR).
    Sparse(CsMat<f64>),
    /// A sum of products applied factor by factor.
    Composed(Composition),
}

/// `Σ_t c_t · F_t,1 F_t,2 ⋯ F_t,k` (each product applied right to left).
#[derive(Debug, Clone)]
pub struct Composition {
    shape: (usize, usize),
    terms: Vec<(f64, Vec<Factor>)>,
}

/// One factor of a [`Composition`].
#[derive(Debug, Clone)]
pub enum Factor {
    /// A sparse matrix `A`.
    Matrix(Arc<CsMat<f64>>),
    /// The transpose `Aᵀ` of a sparse matrix (not formed).
    Transpose(Arc<CsMat<f64>>),
    /// A mass `M`.
    Mass(Mass),
    /// The inverse `M⁻¹` of a mass (on its free nodes, zero on the others).
    MassInverse(Mass),
    /// Another operator.
    Operator(Arc<LinearOperator>),
}

impl Factor {
    /// A sparse matrix factor.
    pub fn matrix(a: &CsMat<f64>) -> Self {
        Factor::Matrix(Arc::new(to_csr(a)))
    }

    /// A transposed sparse matrix factor.
    pub fn transpose(a: &CsMat<f64>) -> Self {
        Factor::Transpose(Arc::new(to_csr(a)))
    }

    /// `(rows, cols)`.
    fn shape(&self) -> (usize, usize) {
        match self {
            Factor::Matrix(a) => a.shape(),
            Factor::Transpose(a) => (a.cols(), a.rows()),
            Factor::Mass(m) | Factor::MassInverse(m) => (m.len(), m.len()),
            Factor::Operator(op) => op.shape(),
        }
    }

    /// The factor as a sparse matrix, if it is one.
    fn sparse(&self) -> Option<CsMat<f64>> {
        match self {
            Factor::Matrix(a) => Some((**a).clone()),
            Factor::Transpose(a) => Some(transpose(a)),
            Factor::Mass(m) => m.sparse_matrix(),
            Factor::MassInverse(m) => m.sparse_inverse_matrix(),
            Factor::Operator(op) => op.as_sparse().cloned(),
        }
    }

    fn apply(&self, x: &[f64]) -> Vec<f64> {
        match self {
            Factor::Matrix(a) => mul_vec(a, x),
            Factor::Transpose(a) => mul_transpose_vec(a, x),
            Factor::Mass(m) => m.apply(x),
            Factor::MassInverse(m) => m.solve(x),
            Factor::Operator(op) => op.apply(x),
        }
    }

    fn apply_transpose(&self, x: &[f64]) -> Vec<f64> {
        match self {
            Factor::Matrix(a) => mul_transpose_vec(a, x),
            Factor::Transpose(a) => mul_vec(a, x),
            Factor::Mass(m) => m.apply(x),
            Factor::MassInverse(m) => m.solve(x),
            Factor::Operator(op) => op.apply_transpose(x),
        }
    }

    fn apply_block(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        match self {
            Factor::Matrix(a) => sparse_times_block(a, x),
            Factor::Transpose(a) => sparse_times_block(&a.transpose_view().to_owned(), x),
            Factor::Mass(m) => m.apply_block(x),
            Factor::MassInverse(m) => m.solve_block(x),
            Factor::Operator(op) => op.apply_block(x),
        }
    }
}

impl LinearOperator {
    /// `coefficient · F_1 F_2 ⋯ F_k`: a sparse matrix if every factor is one, else composed.
    ///
    /// # Panics
    /// If `factors` is empty or the shapes do not chain (a programming error).
    pub fn product(coefficient: f64, factors: Vec<Factor>) -> Self {
        Self::sum(vec![(coefficient, factors)])
    }

    /// `Σ_t c_t · F_t,1 ⋯ F_t,k`: each term formed as a sparse matrix where all its factors are
    /// sparse, and the sum a sparse matrix if every term is.
    ///
    /// # Panics
    /// If there is no term, a term has no factor, or the shapes do not fit (programming errors).
    pub fn sum(terms: Vec<(f64, Vec<Factor>)>) -> Self {
        assert!(!terms.is_empty(), "a sum of no terms");
        let shape = term_shape(&terms[0].1);
        let mut sparse_total: Option<CsMat<f64>> = None;
        let mut composed = Vec::new();
        for (coefficient, factors) in terms {
            assert_eq!(term_shape(&factors), shape, "terms of different shapes");
            match sparse_product(&factors) {
                Some(matrix) => {
                    let scaled = matrix.map(|x| coefficient * x);
                    sparse_total = Some(match sparse_total {
                        Some(total) => &total + &scaled,
                        None => scaled,
                    });
                }
                None => composed.push((coefficient, factors)),
            }
        }
        if composed.is_empty() {
            return LinearOperator::Sparse(sparse_total.expect("at least one term"));
        }
        if let Some(total) = sparse_total {
            composed.push((1.0, vec![Factor::Matrix(Arc::new(total))]));
        }
        LinearOperator::Composed(Composition {
            shape,
            terms: composed,
        })
    }

    /// `(rows, cols)`.
    pub fn shape(&self) -> (usize, usize) {
        match self {
            LinearOperator::Sparse(a) => a.shape(),
            LinearOperator::Composed(c) => c.shape,
        }
    }

    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.shape().0
    }

    /// Number of columns.
    pub fn cols(&self) -> usize {
        self.shape().1
    }

    /// The sparse matrix, if the operator is one.
    pub fn as_sparse(&self) -> Option<&CsMat<f64>> {
        match self {
            LinearOperator::Sparse(a) => Some(a),
            LinearOperator::Composed(_) => None,
        }
    }

    /// Whether the operator is a sparse matrix.
    pub fn is_sparse(&self) -> bool {
        self.as_sparse().is_some()
    }

    /// `A x` (`cols` entries in, `rows` out).
    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        match self {
            LinearOperator::Sparse(a) => mul_vec(a, x),
            LinearOperator::Composed(c) => {
                let mut y = vec![0.0; c.shape.0];
                for (coefficient, factors) in &c.terms {
                    let mut v = x.to_vec();
                    for factor in factors.iter().rev() {
                        v = factor.apply(&v);
                    }
                    for (yi, vi) in y.iter_mut().zip(&v) {
                        *yi += coefficient * vi;
                    }
                }
                y
            }
        }
    }

    /// `Aᵀ x` (`rows` entries in, `cols` out); masses are symmetric.
    pub fn apply_transpose(&self, x: &[f64]) -> Vec<f64> {
        match self {
            LinearOperator::Sparse(a) => mul_transpose_vec(a, x),
            LinearOperator::Composed(c) => {
                let mut y = vec![0.0; c.shape.1];
                for (coefficient, factors) in &c.terms {
                    let mut v = x.to_vec();
                    for factor in factors {
                        v = factor.apply_transpose(&v);
                    }
                    for (yi, vi) in y.iter_mut().zip(&v) {
                        *yi += coefficient * vi;
                    }
                }
                y
            }
        }
    }

    /// `A X` for a `cols × r` block.
    pub fn apply_block(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        match self {
            LinearOperator::Sparse(a) => sparse_times_block(a, x),
            LinearOperator::Composed(c) => {
                let mut y = Mat::zeros(c.shape.0, x.ncols());
                for (coefficient, factors) in &c.terms {
                    let mut v = x.to_owned();
                    for factor in factors.iter().rev() {
                        v = factor.apply_block(v.as_ref());
                    }
                    for j in 0..y.ncols() {
                        for i in 0..y.nrows() {
                            y[(i, j)] += coefficient * v[(i, j)];
                        }
                    }
                }
                y
            }
        }
    }

    /// Row `i` as a dense vector (`cols` entries): `Aᵀ eᵢ`.
    pub fn row(&self, i: usize) -> Vec<f64> {
        match self {
            LinearOperator::Sparse(a) => {
                let mut row = vec![0.0; a.cols()];
                let csr = to_csr(a);
                if let Some(r) = csr.outer_view(i) {
                    for (j, &v) in r.iter() {
                        row[j] = v;
                    }
                }
                row
            }
            LinearOperator::Composed(_) => {
                let mut unit = vec![0.0; self.rows()];
                unit[i] = 1.0;
                self.apply_transpose(&unit)
            }
        }
    }

    /// The operator as a dense matrix (small operators only: tests and dense references).
    pub fn to_dense(&self) -> Mat<f64> {
        let (rows, cols) = self.shape();
        match self {
            LinearOperator::Sparse(a) => {
                let mut dense = Mat::zeros(rows, cols);
                for (&v, (i, j)) in a.iter() {
                    dense[(i, j)] += v;
                }
                dense
            }
            LinearOperator::Composed(_) => {
                let identity = Mat::<f64>::identity(cols, cols);
                self.apply_block(identity.as_ref())
            }
        }
    }
}

/// The shape of a product of factors.
fn term_shape(factors: &[Factor]) -> (usize, usize) {
    assert!(!factors.is_empty(), "a product of no factors");
    for pair in factors.windows(2) {
        assert_eq!(
            pair[0].shape().1,
            pair[1].shape().0,
            "factors of a product do not chain"
        );
    }
    (factors[0].shape().0, factors[factors.len() - 1].shape().1)
}

/// The product of `factors` as a sparse matrix, if every factor is sparse.
fn sparse_product(factors: &[Factor]) -> Option<CsMat<f64>> {
    let mut matrices = Vec::with_capacity(factors.len());
    for factor in factors {
        matrices.push(factor.sparse()?);
    }
    let mut iter = matrices.into_iter();
    let first = to_csr(&iter.next()?);
    Some(iter.fold(first, |acc, m| product(&acc, &m)))
}

/// Whether a mass's inverse, as a factor, is a sparse matrix.
pub(crate) fn has_sparse_inverse(mass: &Mass) -> bool {
    matches!(
        (mass.storage(), mass.form()),
        (MassStorage::Diagonal(_), _) | (MassStorage::Sparse(_), MassForm::Inverse)
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretization::{NodeKind, NodeSpace};
    use faer::linalg::solvers::Solve;
    use sprs::TriMat;

    fn mass(n: usize) -> Mass {
        let mut t = TriMat::new((n, n));
        for i in 0..n {
            t.add_triplet(i, i, 3.0 + i as f64);
            if i + 1 < n {
                t.add_triplet(i, i + 1, 1.0);
                t.add_triplet(i + 1, i, 1.0);
            }
        }
        let nodes =
            NodeSpace::with_constant_kernel(NodeKind::Vertices, vec![[0.0; 3]; n], vec![0; n], 1);
        Mass::sparse("M", t.to_csr())
            .unwrap()
            .restricted_to(&nodes)
            .unwrap()
    }

    fn incidence(rows: usize, cols: usize) -> CsMat<f64> {
        let mut t = TriMat::new((rows, cols));
        for i in 0..rows {
            t.add_triplet(i, i % cols, 1.0);
            t.add_triplet(i, (i + 1) % cols, -1.0);
        }
        t.to_csr()
    }

    #[test]
    fn composed_products_agree_with_dense_algebra() {
        let d = incidence(5, 4);
        let m = mass(5);
        // dᵀ M⁻¹ d: composed (M is sparse and inverted).
        let op = LinearOperator::product(
            2.0,
            vec![
                Factor::transpose(&d),
                Factor::MassInverse(m.clone()),
                Factor::matrix(&d),
            ],
        );
        assert!(!op.is_sparse());
        let dense_m = m.sparse_matrix().unwrap();
        let mut mm = Mat::zeros(5, 5);
        for (&v, (i, j)) in dense_m.iter() {
            mm[(i, j)] = v;
        }
        let inverse = mm
            .as_ref()
            .llt(faer::Side::Lower)
            .unwrap()
            .solve(Mat::<f64>::identity(5, 5));
        let dd = LinearOperator::Sparse(d.clone()).to_dense();
        let expected = dd.transpose() * &inverse * &dd * faer::Scale(2.0);
        let got = op.to_dense();
        for i in 0..4 {
            for j in 0..4 {
                assert!((got[(i, j)] - expected[(i, j)]).abs() < 1e-13);
            }
        }
        // Transpose application and rows agree with the dense matrix.
        let x = [1.0, -2.0, 0.5, 3.0];
        let at = op.apply_transpose(&x);
        for j in 0..4 {
            let e: f64 = (0..4).map(|i| expected[(i, j)] * x[i]).sum();
            assert!((at[j] - e).abs() < 1e-13);
        }
        assert_eq!(op.row(2).len(), 4);
        // With M sparse but not inverted the product is a sparse matrix.
        let sparse = LinearOperator::product(
            1.0,
            vec![Factor::transpose(&d), Factor::Mass(m), Factor::matrix(&d)],
        );
        assert!(sparse.is_sparse());
    }

    #[test]
    fn sums_keep_sparse_terms_together() {
        let d = incidence(4, 4);
        let m = mass(4);
        let op = LinearOperator::sum(vec![
            (1.0, vec![Factor::matrix(&d)]),
            (-1.0, vec![Factor::MassInverse(m.clone())]),
            (0.5, vec![Factor::Mass(m.clone())]),
        ]);
        let x = [0.3, 1.0, -1.0, 2.0];
        let y = op.apply(&x);
        let expected: Vec<f64> = mul_vec(&d, &x)
            .iter()
            .zip(m.solve(&x))
            .zip(m.apply(&x))
            .map(|((a, b), c)| a - b + 0.5 * c)
            .collect();
        for (a, b) in y.iter().zip(&expected) {
            assert!((a - b).abs() < 1e-14);
        }
    }
}
