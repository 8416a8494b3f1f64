//! [`Mass`]: a mass matrix of the seam, a symmetric positive definite operator — a positive
//! diagonal (lumped masses, DEC's Hodge stars) or a sparse matrix (consistent P1 masses, the
//! Whitney 1-form mass) — stored in the form in which it is sparse.

use super::{DiscretizationError, NodeSpace, NO_COMPONENT};
use faer::{Mat, MatRef};
use sprs::{CsMat, TriMat};
use std::sync::{Arc, OnceLock};
use tvf_solvers::{SolverError, SparseCholesky};

/// Which matrix a [`Mass`] stores: the mass `M` itself, or its inverse `M⁻¹`.
///
/// A mass is stored in the form in which it is sparse. The seam's `M2` acts on `d1`'s
/// integrated values and is the inverse of the co-potential inner product: with a consistent
/// (Galerkin) co-potential mass it is `M2⁻¹` that is sparse, and `M2` is stored as
/// [`MassForm::Inverse`]. Every other mass of tvf's catalog is stored as [`MassForm::Direct`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MassForm {
    /// The stored matrix is `M`.
    Direct,
    /// The stored matrix is `M⁻¹`.
    Inverse,
}

impl MassForm {
    /// Lower-case name for files and reports: `direct`, `inverse`.
    pub fn name(self) -> &'static str {
        match self {
            MassForm::Direct => "direct",
            MassForm::Inverse => "inverse",
        }
    }

    /// The other form.
    pub fn flipped(self) -> Self {
        match self {
            MassForm::Direct => MassForm::Inverse,
            MassForm::Inverse => MassForm::Direct,
        }
    }
}

/// The stored matrix of a [`Mass`].
#[derive(Debug, Clone, PartialEq)]
pub enum MassStorage {
    /// A diagonal: one finite, non-negative weight per node (zero only on nodes no face uses).
    Diagonal(Vec<f64>),
    /// A sparse symmetric matrix (CSR, both triangles stored), positive definite on the free
    /// nodes.
    Sparse(CsMat<f64>),
}

/// A mass matrix `M` (`n × n`) of a [`super::HodgeComplex`]: symmetric positive definite on the
/// **free** nodes of its space (used by a face and not fixed by the boundary condition,
/// [`NodeSpace::is_free`]).
///
/// - [`Mass::apply`] is `M x`; [`Mass::solve`] is `M⁻¹ b` on the free nodes and zero on the
///   others (the mass restricted to the free nodes is what is inverted, so nothing leaks into a
///   fixed node); [`Mass::inner`] is `xᵀ M y`.
/// - A diagonal mass applies and inverts entry by entry (the fast path: `M⁻¹` is the reciprocal
///   of each free entry). A sparse mass applies by a sparse product and inverts with a sparse
///   Cholesky factorization of its free block, computed once and shared by every clone. A mass
///   stored as its inverse ([`MassForm::Inverse`]) does the opposite: `solve` is the product
///   and `apply` the factorization. No dense inverse is ever formed.
///
/// A mass fresh from a constructor treats every node as free; [`super::ComplexParts::new`]
/// restricts it to the free nodes of its space and, for a sparse mass, factors it there (an
/// error naming the mass if it is not positive definite).
#[derive(Debug, Clone)]
pub struct Mass {
    what: &'static str,
    storage: MassStorage,
    form: MassForm,
    free: Option<Arc<Vec<bool>>>,
    factor: Arc<OnceLock<Result<Arc<FreeCholesky>, DiscretizationError>>>,
}

impl PartialEq for Mass {
    /// Masses are equal when they store the same matrix in the same form on the same free nodes.
    fn eq(&self, other: &Self) -> bool {
        self.storage == other.storage && self.form == other.form && self.free == other.free
    }
}

/// The sparse Cholesky factorization of a stored matrix restricted to its free nodes.
#[derive(Debug)]
struct FreeCholesky {
    /// Full index of each free node, ascending.
    free_nodes: Vec<usize>,
    cholesky: SparseCholesky,
}

impl Mass {
    /// A diagonal mass: every entry finite and non-negative. `what` names the mass in errors
    /// (e.g. `"M1 (⋆1, the edge Hodge star)"`).
    pub fn diagonal(what: &'static str, values: Vec<f64>) -> Result<Self, DiscretizationError> {
        if let Some(index) = values.iter().position(|x| !x.is_finite()) {
            return Err(DiscretizationError::NonFinite { what, index });
        }
        let negative: Vec<usize> = (0..values.len()).filter(|&i| values[i] < 0.0).collect();
        if let Some(&first) = negative.first() {
            return Err(DiscretizationError::NotPositive {
                what,
                count: negative.len(),
                first,
                value: values[first],
            });
        }
        Ok(Self::from_storage(
            what,
            MassStorage::Diagonal(values),
            MassForm::Direct,
        ))
    }

    /// Like [`Mass::diagonal`], and also positive on every node whose component (in
    /// `components`, one per node) is not [`NO_COMPONENT`].
    pub fn diagonal_positive_on_used_nodes(
        what: &'static str,
        values: Vec<f64>,
        components: &[usize],
    ) -> Result<Self, DiscretizationError> {
        let zero: Vec<usize> = (0..values.len())
            .filter(|&i| values[i] <= 0.0 && components.get(i) != Some(&NO_COMPONENT))
            .collect();
        let mass = Self::diagonal(what, values)?;
        match zero.first() {
            Some(&first) => Err(DiscretizationError::NotPositive {
                what,
                count: zero.len(),
                first,
                value: mass.diagonal_values().map_or(0.0, |v| v[first]),
            }),
            None => Ok(mass),
        }
    }

    /// A sparse mass `M` (`n × n`): square, finite and symmetric to round-off (it is stored as
    /// `(M + Mᵀ)/2`). Positive definiteness is checked on the free nodes by
    /// [`super::ComplexParts::new`].
    pub fn sparse(what: &'static str, matrix: CsMat<f64>) -> Result<Self, DiscretizationError> {
        Ok(Self::from_storage(
            what,
            MassStorage::Sparse(checked_symmetric(what, matrix)?),
            MassForm::Direct,
        ))
    }

    /// A mass given by its sparse inverse `M⁻¹` (`n × n`; checked as in [`Mass::sparse`]): the
    /// form of a consistent co-potential mass's `M2`.
    pub fn sparse_inverse(
        what: &'static str,
        inverse: CsMat<f64>,
    ) -> Result<Self, DiscretizationError> {
        Ok(Self::from_storage(
            what,
            MassStorage::Sparse(checked_symmetric(what, inverse)?),
            MassForm::Inverse,
        ))
    }

    fn from_storage(what: &'static str, storage: MassStorage, form: MassForm) -> Self {
        Self {
            what,
            storage,
            form,
            free: None,
            factor: Arc::new(OnceLock::new()),
        }
    }

    /// The same mass restricted to the free nodes of `nodes` (same length), factored there if
    /// it is sparse. Errors: [`DiscretizationError::NotPositiveDefinite`] naming the mass,
    /// [`DiscretizationError::NotPositive`] for a diagonal with a zero on a used node.
    pub fn restricted_to(&self, nodes: &NodeSpace) -> Result<Self, DiscretizationError> {
        let free: Vec<bool> = (0..nodes.len()).map(|i| nodes.is_free(i)).collect();
        let mut mass = Self {
            free: if free.iter().all(|&f| f) {
                None
            } else {
                Some(Arc::new(free))
            },
            factor: Arc::new(OnceLock::new()),
            ..self.clone()
        };
        if let MassStorage::Sparse(_) = mass.storage {
            mass.factorization()?;
        } else if let Some(values) = mass.diagonal_values() {
            let zero: Vec<usize> = (0..values.len())
                .filter(|&i| mass.is_free(i) && values[i] <= 0.0)
                .collect();
            if let Some(&first) = zero.first() {
                return Err(DiscretizationError::NotPositive {
                    what: mass.what,
                    count: zero.len(),
                    first,
                    value: values[first],
                });
            }
        }
        // Keep the name the mass was built with.
        mass.what = self.what;
        Ok(mass)
    }

    /// The name errors use.
    pub fn what(&self) -> &'static str {
        self.what
    }

    /// Number of nodes `n`.
    pub fn len(&self) -> usize {
        match &self.storage {
            MassStorage::Diagonal(values) => values.len(),
            MassStorage::Sparse(matrix) => matrix.rows(),
        }
    }

    /// Whether the mass has no node.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The stored matrix.
    pub fn storage(&self) -> &MassStorage {
        &self.storage
    }

    /// Whether the stored matrix is `M` or `M⁻¹`.
    pub fn form(&self) -> MassForm {
        self.form
    }

    /// Whether `M` is diagonal.
    pub fn is_diagonal(&self) -> bool {
        matches!(self.storage, MassStorage::Diagonal(_))
    }

    /// The diagonal of `M` if `M` is diagonal (`n` entries), else `None`.
    pub fn diagonal_values(&self) -> Option<&[f64]> {
        match &self.storage {
            MassStorage::Diagonal(values) => Some(values),
            MassStorage::Sparse(_) => None,
        }
    }

    /// Whether node `i` is free (see [`Mass`]).
    pub fn is_free(&self, i: usize) -> bool {
        self.free.as_ref().is_none_or(|free| free[i])
    }

    /// The stored matrix as it was given (CSR, `n × n`; a diagonal as a diagonal matrix): `M`,
    /// or `M⁻¹` for [`MassForm::Inverse`] (see [`Mass::form`]).
    pub fn stored_matrix(&self) -> CsMat<f64> {
        match &self.storage {
            MassStorage::Diagonal(values) => super::sparse::diagonal(values),
            MassStorage::Sparse(matrix) => matrix.clone(),
        }
    }

    /// `M` as a sparse matrix (CSR, `n × n`) when it is sparse: a diagonal, or a sparse matrix
    /// stored directly. `None` for a mass stored as its inverse (`M` is dense).
    pub fn sparse_matrix(&self) -> Option<CsMat<f64>> {
        match (&self.storage, self.form) {
            (MassStorage::Diagonal(values), _) => Some(super::sparse::diagonal(values)),
            (MassStorage::Sparse(matrix), MassForm::Direct) => Some(matrix.clone()),
            (MassStorage::Sparse(_), MassForm::Inverse) => None,
        }
    }

    /// `M⁻¹` as a sparse matrix when it is sparse: the reciprocal of a diagonal on the free
    /// nodes (zero on the others), or a matrix stored as the inverse restricted to the free
    /// nodes. `None` for a sparse mass stored directly (`M⁻¹` is dense).
    pub fn sparse_inverse_matrix(&self) -> Option<CsMat<f64>> {
        match (&self.storage, self.form) {
            (MassStorage::Diagonal(_), _) => {
                Some(super::sparse::diagonal(&self.inverse_diagonal()?))
            }
            (MassStorage::Sparse(matrix), MassForm::Inverse) => {
                Some(self.restricted_matrix(matrix))
            }
            (MassStorage::Sparse(_), MassForm::Direct) => None,
        }
    }

    /// The reciprocal diagonal `1/m` on the free nodes and 0 on the others, if `M` is diagonal.
    pub fn inverse_diagonal(&self) -> Option<Vec<f64>> {
        let values = self.diagonal_values()?;
        Some(
            values
                .iter()
                .enumerate()
                .map(|(i, &m)| {
                    if m > 0.0 && self.is_free(i) {
                        1.0 / m
                    } else {
                        0.0
                    }
                })
                .collect(),
        )
    }

    /// The inverse mass `M⁻¹` as a [`Mass`] on the same nodes: a diagonal's reciprocal (on the
    /// free nodes), or the same stored matrix in the other form.
    pub fn inverse(&self) -> Mass {
        match &self.storage {
            MassStorage::Diagonal(_) => Self {
                storage: MassStorage::Diagonal(self.inverse_diagonal().unwrap_or_default()),
                ..self.clone()
            },
            MassStorage::Sparse(_) => Self {
                form: self.form.flipped(),
                ..self.clone()
            },
        }
    }

    /// The mass `c · M` (`c > 0`) on the same nodes, named `what`: the stored matrix scaled by
    /// `c`, or by `1/c` if it is stored as the inverse.
    pub fn scaled(&self, what: &'static str, c: f64) -> Mass {
        let factor = match self.form {
            MassForm::Direct => c,
            MassForm::Inverse => 1.0 / c,
        };
        let storage = match &self.storage {
            MassStorage::Diagonal(values) => {
                MassStorage::Diagonal(values.iter().map(|m| m * factor).collect())
            }
            MassStorage::Sparse(matrix) => MassStorage::Sparse(matrix.map(|m| m * factor)),
        };
        Self {
            what,
            storage,
            factor: Arc::new(OnceLock::new()),
            ..self.clone()
        }
    }

    /// `M x` (`n` entries in, `n` out).
    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        match (&self.storage, self.form) {
            (MassStorage::Diagonal(values), _) => {
                x.iter().zip(values).map(|(a, m)| a * m).collect()
            }
            (MassStorage::Sparse(matrix), MassForm::Direct) => super::sparse::mul_vec(matrix, x),
            (MassStorage::Sparse(_), MassForm::Inverse) => self.factored_solve(x),
        }
    }

    /// `M⁻¹ b` on the free nodes, zero on the others (`n` entries in, `n` out).
    pub fn solve(&self, b: &[f64]) -> Vec<f64> {
        match (&self.storage, self.form) {
            (MassStorage::Diagonal(values), _) => b
                .iter()
                .zip(values)
                .enumerate()
                .map(|(i, (x, &m))| {
                    if m > 0.0 && self.is_free(i) {
                        x / m
                    } else {
                        0.0
                    }
                })
                .collect(),
            (MassStorage::Sparse(_), MassForm::Direct) => self.factored_solve(b),
            (MassStorage::Sparse(matrix), MassForm::Inverse) => {
                let mut y = super::sparse::mul_vec(matrix, &self.zero_fixed(b));
                self.zero_fixed_in_place(&mut y);
                y
            }
        }
    }

    /// `xᵀ M y`.
    pub fn inner(&self, x: &[f64], y: &[f64]) -> f64 {
        match &self.storage {
            MassStorage::Diagonal(values) => x
                .iter()
                .zip(y)
                .zip(values)
                .map(|((a, b), m)| a * b * m)
                .sum(),
            MassStorage::Sparse(_) => x.iter().zip(self.apply(y)).map(|(a, b)| a * b).sum(),
        }
    }

    /// `M X` for an `n × r` block.
    pub fn apply_block(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        match (&self.storage, self.form) {
            (MassStorage::Diagonal(values), _) => {
                Mat::from_fn(x.nrows(), x.ncols(), |i, j| x[(i, j)] * values[i])
            }
            (MassStorage::Sparse(matrix), MassForm::Direct) => sparse_times_block(matrix, x),
            (MassStorage::Sparse(_), MassForm::Inverse) => self.factored_solve_block(x),
        }
    }

    /// `M⁻¹ B` for an `n × r` block (on the free nodes, zero rows elsewhere).
    pub fn solve_block(&self, b: MatRef<'_, f64>) -> Mat<f64> {
        match (&self.storage, self.form) {
            (MassStorage::Diagonal(_), _) => {
                let inverse = self.inverse_diagonal().unwrap_or_default();
                Mat::from_fn(b.nrows(), b.ncols(), |i, j| b[(i, j)] * inverse[i])
            }
            (MassStorage::Sparse(_), MassForm::Direct) => self.factored_solve_block(b),
            (MassStorage::Sparse(matrix), MassForm::Inverse) => {
                let masked = Mat::from_fn(b.nrows(), b.ncols(), |i, j| {
                    if self.is_free(i) {
                        b[(i, j)]
                    } else {
                        0.0
                    }
                });
                let mut y = sparse_times_block(matrix, masked.as_ref());
                for i in (0..y.nrows()).filter(|&i| !self.is_free(i)) {
                    for j in 0..y.ncols() {
                        y[(i, j)] = 0.0;
                    }
                }
                y
            }
        }
    }

    /// `1ᵀ M 1`: the total weight (for a potential mass, the area of the surface).
    pub fn total(&self) -> f64 {
        match (&self.storage, self.form) {
            (MassStorage::Diagonal(values), _) => values.iter().sum(),
            (MassStorage::Sparse(matrix), MassForm::Direct) => matrix.data().iter().sum(),
            (MassStorage::Sparse(_), MassForm::Inverse) => {
                let ones: Vec<f64> = (0..self.len())
                    .map(|i| if self.is_free(i) { 1.0 } else { 0.0 })
                    .collect();
                self.inner(&ones, &ones)
            }
        }
    }

    /// The stored matrix restricted to the free nodes (fixed rows and columns dropped to zero),
    /// CSR.
    fn restricted_matrix(&self, matrix: &CsMat<f64>) -> CsMat<f64> {
        if self.free.is_none() {
            return matrix.clone();
        }
        let mut triplets = TriMat::new(matrix.shape());
        for (&value, (i, j)) in matrix.iter() {
            if self.is_free(i) && self.is_free(j) {
                triplets.add_triplet(i, j, value);
            }
        }
        triplets.to_csr()
    }

    fn zero_fixed(&self, x: &[f64]) -> Vec<f64> {
        let mut y = x.to_vec();
        self.zero_fixed_in_place(&mut y);
        y
    }

    fn zero_fixed_in_place(&self, y: &mut [f64]) {
        if self.free.is_some() {
            for (i, v) in y.iter_mut().enumerate() {
                if !self.is_free(i) {
                    *v = 0.0;
                }
            }
        }
    }

    /// The Cholesky factorization of the stored sparse matrix on the free nodes (computed on
    /// first use, shared by clones).
    fn factorization(&self) -> Result<Arc<FreeCholesky>, DiscretizationError> {
        self.factor
            .get_or_init(|| {
                let MassStorage::Sparse(matrix) = &self.storage else {
                    return Err(DiscretizationError::Inconsistent(format!(
                        "{}: a diagonal mass has no factorization",
                        self.what
                    )));
                };
                let free_nodes: Vec<usize> =
                    (0..matrix.rows()).filter(|&i| self.is_free(i)).collect();
                let mut position = vec![usize::MAX; matrix.rows()];
                for (k, &i) in free_nodes.iter().enumerate() {
                    position[i] = k;
                }
                let n = free_nodes.len();
                let mut block = TriMat::new((n, n));
                for (&value, (i, j)) in matrix.iter() {
                    if position[i] != usize::MAX && position[j] != usize::MAX {
                        block.add_triplet(position[i], position[j], value);
                    }
                }
                let block: CsMat<f64> = block.to_csc();
                let cholesky = SparseCholesky::new(&block).map_err(|error| {
                    not_positive_definite(self.what, self.form, &free_nodes, error)
                })?;
                Ok(Arc::new(FreeCholesky {
                    free_nodes,
                    cholesky,
                }))
            })
            .clone()
    }

    /// Solves with the stored matrix on the free nodes.
    fn factored_solve(&self, b: &[f64]) -> Vec<f64> {
        let block = Mat::from_fn(b.len(), 1, |i, _| b[i]);
        let x = self.factored_solve_block(block.as_ref());
        (0..b.len()).map(|i| x[(i, 0)]).collect()
    }

    fn factored_solve_block(&self, b: MatRef<'_, f64>) -> Mat<f64> {
        let factor = self
            .factorization()
            .expect("a sparse mass of a complex is factored when the complex is built");
        let free = &factor.free_nodes;
        let mut gathered = Mat::from_fn(free.len(), b.ncols(), |k, j| b[(free[k], j)]);
        factor.cholesky.solve_in_place(gathered.as_mut());
        let mut x = Mat::zeros(b.nrows(), b.ncols());
        for (k, &i) in free.iter().enumerate() {
            for j in 0..b.ncols() {
                x[(i, j)] = gathered[(k, j)];
            }
        }
        x
    }
}

/// `A X` for a sparse `A` (`m × n`) and a dense `n × r` block.
///
/// Column by column of `X`, so that the inner loops run down contiguous columns of faer's
/// column-major blocks (looping over the columns innermost strode across memory and made the
/// dense checks of the conformance suite on 1.5k-node meshes spend half their time here); every
/// entry is summed in the order of `A`'s stored entries, as before.
pub(crate) fn sparse_times_block(a: &CsMat<f64>, x: MatRef<'_, f64>) -> Mat<f64> {
    let mut y = Mat::zeros(a.rows(), x.ncols());
    for j in 0..x.ncols() {
        let x_j = x.col(j);
        let mut y_j = y.col_mut(j);
        if a.is_csr() {
            for (i, row) in a.outer_iterator().enumerate() {
                let mut sum = 0.0;
                for (k, &v) in row.iter() {
                    sum += v * x_j[k];
                }
                y_j[i] = sum;
            }
        } else {
            for (k, column) in a.outer_iterator().enumerate() {
                let x_kj = x_j[k];
                for (i, &v) in column.iter() {
                    y_j[i] += v * x_kj;
                }
            }
        }
    }
    y
}

/// `matrix` checked (square, finite, symmetric to round-off) and returned as `(M + Mᵀ)/2` in
/// CSR storage.
fn checked_symmetric(
    what: &'static str,
    matrix: CsMat<f64>,
) -> Result<CsMat<f64>, DiscretizationError> {
    let (rows, cols) = matrix.shape();
    if rows != cols {
        return Err(DiscretizationError::Inconsistent(format!(
            "{what} is {rows} × {cols}, not square"
        )));
    }
    if let Some(index) = matrix.data().iter().position(|x| !x.is_finite()) {
        return Err(DiscretizationError::NonFinite { what, index });
    }
    let matrix = super::sparse::to_csr(&matrix);
    let transpose = super::sparse::transpose(&matrix);
    let scale = matrix.data().iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let difference = &matrix - &transpose;
    let asymmetry = difference
        .data()
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    if asymmetry > 1e-12 * scale {
        return Err(DiscretizationError::NotSymmetric {
            what,
            asymmetry,
            scale,
        });
    }
    if asymmetry == 0.0 {
        return Ok(matrix);
    }
    Ok((&matrix + &transpose).map(|x| 0.5 * x))
}

fn not_positive_definite(
    what: &'static str,
    form: MassForm,
    free_nodes: &[usize],
    error: SolverError,
) -> DiscretizationError {
    let stored = match form {
        MassForm::Direct => "",
        MassForm::Inverse => " (stored as its inverse)",
    };
    match error {
        SolverError::NotPositiveDefinite { pivot, value } => {
            DiscretizationError::NotPositiveDefinite {
                what,
                detail: format!(
                    "{stored} the Cholesky factorization of its free block met the pivot {value:e} \
                     at node {}",
                    free_nodes.get(pivot).copied().unwrap_or(pivot)
                ),
            }
        }
        other => DiscretizationError::NotPositiveDefinite {
            what,
            detail: format!("{stored} its Cholesky factorization failed: {other}"),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretization::{NodeKind, NodeSpace};

    fn space(dirichlet: Vec<bool>, components: Vec<usize>) -> NodeSpace {
        let n = components.len();
        NodeSpace {
            kind: NodeKind::Vertices,
            positions: vec![[0.0; 3]; n],
            components,
            dirichlet,
            constant_kernel: vec![true],
        }
    }

    fn tridiagonal(n: usize) -> CsMat<f64> {
        let mut t = TriMat::new((n, n));
        for i in 0..n {
            t.add_triplet(i, i, 4.0);
            if i + 1 < n {
                t.add_triplet(i, i + 1, 1.0);
                t.add_triplet(i + 1, i, 1.0);
            }
        }
        t.to_csr()
    }

    #[test]
    fn refuses_negative_and_non_finite_entries() {
        let err = Mass::diagonal("M1", vec![1.0, -2.0, 3.0, -0.5]).unwrap_err();
        assert_eq!(
            err,
            DiscretizationError::NotPositive {
                what: "M1",
                count: 2,
                first: 1,
                value: -2.0
            }
        );
        assert!(Mass::diagonal("M1", vec![1.0, f64::NAN]).is_err());
    }

    #[test]
    fn diagonal_zero_only_on_unused_nodes() {
        let used = [0, NO_COMPONENT, 0];
        assert!(Mass::diagonal_positive_on_used_nodes("M0", vec![1.0, 0.0, 2.0], &used).is_ok());
        assert!(Mass::diagonal_positive_on_used_nodes("M0", vec![0.0, 1.0, 2.0], &used).is_err());
        let mass = Mass::diagonal("M0", vec![2.0, 0.0]).unwrap();
        assert_eq!(mass.solve(&[1.0, 5.0]), vec![0.5, 0.0]);
        assert_eq!(mass.inner(&[1.0, 5.0], &[3.0, 7.0]), 6.0);
    }

    #[test]
    fn sparse_mass_solves_on_free_nodes_only() {
        let n = 6;
        let mass = Mass::sparse("M", tridiagonal(n)).unwrap();
        let nodes = space(
            vec![false, false, true, false, false, false],
            vec![0, 0, 0, 0, NO_COMPONENT, 0],
        );
        let mass = mass.restricted_to(&nodes).unwrap();
        let b = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let x = mass.solve(&b);
        assert_eq!((x[2], x[4]), (0.0, 0.0));
        // M x = b on the free nodes: rows 0, 1, 3, 5 of the restricted matrix.
        let restricted = mass.restricted_matrix(&tridiagonal(n));
        let y = super::super::sparse::mul_vec(&restricted, &x);
        for i in [0, 1, 3, 5] {
            assert!((y[i] - b[i]).abs() < 1e-14, "row {i}: {} vs {}", y[i], b[i]);
        }
        // Stored as its inverse, the same matrix swaps apply and solve.
        let inverse = mass.inverse();
        assert_eq!(inverse.form(), MassForm::Inverse);
        assert_eq!(inverse.apply(&b), x);
    }

    #[test]
    fn indefinite_and_asymmetric_matrices_are_refused_by_name() {
        let mut t = TriMat::new((2, 2));
        t.add_triplet(0, 0, 1.0);
        t.add_triplet(1, 1, -1.0);
        let mass = Mass::sparse("M0 (consistent)", t.to_csr()).unwrap();
        let nodes = space(vec![false; 2], vec![0, 0]);
        let err = mass.restricted_to(&nodes).unwrap_err();
        assert!(err.to_string().contains("M0 (consistent)"), "{err}");
        let mut t = TriMat::new((2, 2));
        t.add_triplet(0, 0, 1.0);
        t.add_triplet(0, 1, 0.5);
        t.add_triplet(1, 1, 1.0);
        let err = Mass::sparse("M1", t.to_csr()).unwrap_err();
        assert!(
            matches!(err, DiscretizationError::NotSymmetric { .. }),
            "{err}"
        );
    }

    #[test]
    fn block_operations_match_vector_ones() {
        let mass = Mass::sparse("M", tridiagonal(5))
            .unwrap()
            .restricted_to(&space(vec![false; 5], vec![0; 5]))
            .unwrap();
        let x = Mat::from_fn(5, 2, |i, j| (i + 3 * j) as f64 - 2.0);
        let applied = mass.apply_block(x.as_ref());
        let solved = mass.solve_block(x.as_ref());
        for j in 0..2 {
            let column: Vec<f64> = (0..5).map(|i| x[(i, j)]).collect();
            let a = mass.apply(&column);
            let s = mass.solve(&column);
            for i in 0..5 {
                assert!((applied[(i, j)] - a[i]).abs() < 1e-14);
                assert!((solved[(i, j)] - s[i]).abs() < 1e-14);
            }
        }
        assert!((mass.total() - (4.0 * 5.0 + 2.0 * 4.0)).abs() < 1e-12);
    }
}
