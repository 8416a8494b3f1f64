//! Sparse Cholesky factorization of symmetric positive-definite matrices.
//!
//! # Semidefinite Laplacians
//! A cotan or Crouzeix–Raviart stiffness matrix `S` is only positive *semi*definite: constants
//! (one per connected component) are in its kernel, so [`SparseCholesky::new`] rejects it with
//! [`SolverError::NotPositiveDefinite`]. Callers choose one of:
//! - **shift**: factor `S − σM` with a small σ < 0 (e.g. `σ = −1e-8 · λ_max`); this is SPD
//!   and is exactly what shift-and-invert eigensolvers need;
//! - **pin**: fix one unknown per connected component (remove its row and column, or add a
//!   large value to its diagonal), which makes the reduced matrix SPD; the solution is then
//!   defined up to the pinned values;
//! - **regularise**: add a screening term `S + εM` (ε > 0), as in screened-Poisson problems.

use crate::convert::{square_dimension, upper_triangle_csc};
use crate::error::SolverError;
use crate::ordering::FillOrdering;
use crate::sparse_ldlt::SparseLdlt;
use faer::{Mat, MatRef};

/// Sparse `LDLᵀ = A` factorization of a symmetric positive-definite matrix, with all pivots
/// checked to be positive (so it is a Cholesky factorization `A = (L D^½)(L D^½)ᵀ`).
///
/// Supernodal (faer), AMD-ordered unless another [`FillOrdering`] is chosen with
/// [`SparseCholesky::with_ordering`]. The symbolic analysis is kept so that
/// [`SparseCholesky::refactor`] only redoes the numeric part.
#[derive(Debug)]
pub struct SparseCholesky {
    ldlt: SparseLdlt,
}

impl SparseCholesky {
    /// Factors a symmetric positive-definite `n × n` matrix given in full storage (both
    /// triangles) or upper-triangular storage, as a CSC or CSR `sprs` matrix.
    /// The strict lower triangle is ignored (symmetry is not checked).
    ///
    /// Errors: [`SolverError::NotSquare`], [`SolverError::NonFinite`],
    /// [`SolverError::NotPositiveDefinite`] (with the offending row/column in input numbering).
    pub fn new(matrix: &sprs::CsMat<f64>) -> Result<Self, SolverError> {
        Self::with_ordering(matrix, FillOrdering::Amd)
    }

    /// The same as [`SparseCholesky::new`] with the fill-reducing `ordering` of choice
    /// (nested dissection pays off for large or dense-ish matrices from meshes).
    ///
    /// Errors: those of [`SparseCholesky::new`], and [`SolverError::Factorization`] if the
    /// nested-dissection ordering fails.
    pub fn with_ordering(
        matrix: &sprs::CsMat<f64>,
        ordering: FillOrdering,
    ) -> Result<Self, SolverError> {
        square_dimension(matrix)?;
        let upper = upper_triangle_csc(matrix)?;
        let ldlt =
            SparseLdlt::with_ordering(upper.as_ref(), ordering).map_err(singular_to_not_pd)?;
        let this = Self { ldlt };
        this.check_positive()?;
        Ok(this)
    }

    /// Number of stored values of the factor `L` (a measure of fill-in).
    pub fn factor_len(&self) -> usize {
        self.ldlt.factor_len()
    }

    /// The fill-reducing ordering this factorization was analysed with.
    pub fn ordering(&self) -> FillOrdering {
        self.ldlt.ordering()
    }

    /// Dimension `n` of the factored matrix.
    pub fn dimension(&self) -> usize {
        self.ldlt.dimension()
    }

    /// Solves `A x = rhs` for one right-hand side of length `n`.
    ///
    /// # Panics
    /// If `rhs.len() != self.dimension()` (a programming error, not an input error).
    pub fn solve(&self, rhs: &[f64]) -> Vec<f64> {
        assert_eq!(
            rhs.len(),
            self.dimension(),
            "SparseCholesky::solve: rhs length must equal the dimension"
        );
        let mut x = Mat::from_fn(rhs.len(), 1, |i, _| rhs[i]);
        self.ldlt.solve_in_place(x.as_mut());
        (0..rhs.len()).map(|i| x[(i, 0)]).collect()
    }

    /// Solves `A X = rhs` for an `n × r` block of right-hand sides (all solved together).
    ///
    /// # Panics
    /// If `rhs.nrows() != self.dimension()`.
    pub fn solve_many(&self, rhs: MatRef<'_, f64>) -> Mat<f64> {
        assert_eq!(
            rhs.nrows(),
            self.dimension(),
            "SparseCholesky::solve_many: rhs must have n rows"
        );
        let mut x = rhs.to_owned();
        self.ldlt.solve_in_place(x.as_mut());
        x
    }

    /// Overwrites the `n × r` block `rhs` with `A⁻¹ rhs`.
    ///
    /// # Panics
    /// If `rhs.nrows() != self.dimension()`.
    pub fn solve_in_place(&self, rhs: faer::MatMut<'_, f64>) {
        self.ldlt.solve_in_place(rhs);
    }

    /// Refactors a matrix with the same sparsity pattern (same storage: full or upper),
    /// reusing the symbolic analysis.
    ///
    /// Errors: [`SolverError::PatternMismatch`], [`SolverError::NonFinite`],
    /// [`SolverError::NotPositiveDefinite`]. After an error the factorization is unusable
    /// until a successful `refactor`.
    pub fn refactor(&mut self, matrix: &sprs::CsMat<f64>) -> Result<(), SolverError> {
        let (rows, cols) = matrix.shape();
        if rows != self.dimension() || cols != self.dimension() {
            return Err(SolverError::DimensionMismatch {
                context: "SparseCholesky::refactor",
                expected: self.dimension(),
                actual: rows.max(cols),
            });
        }
        let upper = upper_triangle_csc(matrix)?;
        self.ldlt
            .refactor(upper.as_ref())
            .map_err(singular_to_not_pd)?;
        self.check_positive()
    }

    fn check_positive(&self) -> Result<(), SolverError> {
        let pivots = self.ldlt.pivots();
        match pivots.iter().position(|&d| d <= 0.0 || !d.is_finite()) {
            Some(k) => Err(SolverError::NotPositiveDefinite {
                pivot: self.ldlt.original_index(k),
                value: pivots[k],
            }),
            None => Ok(()),
        }
    }
}

fn singular_to_not_pd(error: SolverError) -> SolverError {
    match error {
        SolverError::Singular { pivot } => SolverError::NotPositiveDefinite { pivot, value: 0.0 },
        other => other,
    }
}
