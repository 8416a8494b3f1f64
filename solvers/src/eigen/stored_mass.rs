//! The mass of a pencil as the pencil stores it: a checked positive diagonal, or a sparse SPD
//! matrix in full storage with its sparse Cholesky factorization (made once, for `M⁻¹` in the
//! refinement, the eigenfield residuals and the spectrum bound) and its diagonal.

use super::mass::{full_symmetric_mass, Mass, MassMatrix};
use super::sparse_summaries::diagonal_of;
use crate::convert::upper_triangle_csc;
use crate::dense_eigen::check_mass;
use crate::error::SolverError;
use crate::sparse_ldlt::SparseLdlt;
use faer::sparse::SparseColMat;
use faer::Mat;

/// A sparse SPD mass: full storage, its Cholesky factorization and its diagonal.
pub(crate) struct SparseMass {
    pub(crate) full: SparseColMat<usize, f64>,
    /// `LDLᵀ = M`, all pivots positive, solved on one thread.
    pub(crate) factor: SparseLdlt,
    /// The diagonal of `M`.
    pub(crate) diagonal: Vec<f64>,
}

impl SparseMass {
    /// Checks and factors the mass `m` of a pencil of dimension `n`.
    ///
    /// Errors: [`SolverError::NotSquare`], [`SolverError::NonFinite`],
    /// [`SolverError::DimensionMismatch`], [`SolverError::MatrixNotPositiveDefinite`] naming the
    /// mass matrix.
    pub(crate) fn new(m: &sprs::CsMat<f64>, n: usize) -> Result<Self, SolverError> {
        let full = full_symmetric_mass(m, n, "mass matrix dimension")?;
        let upper = upper_triangle_csc(m)?;
        let factor = SparseLdlt::positive_definite(upper.as_ref(), "mass matrix")?;
        let diagonal = diagonal_of(full.as_ref());
        Ok(Self {
            full,
            factor,
            diagonal,
        })
    }
}

/// Checks a diagonal mass of a pencil of dimension `n`: `n` entries ([`check_mass`]: positive,
/// finite).
///
/// Errors: [`SolverError::DimensionMismatch`], else as [`check_mass`].
pub(crate) fn check_diagonal_mass(mass: &[f64], n: usize) -> Result<(), SolverError> {
    if mass.len() != n {
        return Err(SolverError::DimensionMismatch {
            context: "mass diagonal length",
            expected: n,
            actual: mass.len(),
        });
    }
    check_mass(mass)
}

/// The mass of a pencil as stored (one per pencil, never moved after construction: the size
/// of the variants does not matter).
#[allow(clippy::large_enum_variant)]
pub(crate) enum StoredMass<'a> {
    Diagonal(&'a [f64]),
    Sparse(SparseMass),
}

impl StoredMass<'_> {
    /// The mass as the kernels see it (input order).
    pub(crate) fn view(&self) -> Mass<'_> {
        match self {
            StoredMass::Diagonal(mass) => Mass::Diagonal(mass),
            StoredMass::Sparse(m) => Mass::Sparse(m.full.as_ref()),
        }
    }

    /// The mass of the caller, checked (see [`SparseMass::new`], [`check_mass`]).
    pub(crate) fn new(mass: MassMatrix<'_>, n: usize) -> Result<StoredMass<'_>, SolverError> {
        match mass {
            MassMatrix::Diagonal(mass) => {
                check_diagonal_mass(mass, n)?;
                Ok(StoredMass::Diagonal(mass))
            }
            MassMatrix::Sparse(m) => Ok(StoredMass::Sparse(SparseMass::new(m, n)?)),
        }
    }

    /// `Σ_ij M_ij` (the total mass: the area of a surface for P1 or face masses).
    pub(crate) fn total(&self) -> f64 {
        match self {
            StoredMass::Diagonal(mass) => mass.iter().sum(),
            StoredMass::Sparse(m) => m.full.val().iter().sum(),
        }
    }
}

/// `M x` and `M⁻¹ x` of a stored mass, for the Lanczos bound.
#[derive(Clone, Copy)]
pub(crate) enum MassSolver<'a> {
    Diagonal(&'a [f64]),
    Sparse(&'a SparseMass),
}

impl MassSolver<'_> {
    /// `M x`.
    pub(crate) fn apply(self, x: &[f64]) -> Vec<f64> {
        let column = faer::MatRef::from_column_major_slice(x, x.len(), 1);
        let product = match self {
            MassSolver::Diagonal(d) => Mass::Diagonal(d).times(column),
            MassSolver::Sparse(m) => Mass::Sparse(m.full.as_ref()).times(column),
        };
        (0..x.len()).map(|i| product[(i, 0)]).collect()
    }

    /// `M⁻¹ x`.
    pub(crate) fn solve(self, x: &[f64]) -> Vec<f64> {
        match self {
            MassSolver::Diagonal(mass) => x.iter().zip(mass).map(|(v, m)| v / m).collect(),
            MassSolver::Sparse(m) => {
                let mut column = Mat::from_fn(x.len(), 1, |i, _| x[i]);
                m.factor.solve_in_place(column.as_mut());
                (0..x.len()).map(|i| column[(i, 0)]).collect()
            }
        }
    }
}
