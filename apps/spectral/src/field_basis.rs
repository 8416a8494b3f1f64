//! [`FieldBasis`]: what spectral processing needs of a Fourier basis — its eigenvalues and
//! families, the projection `Uᵀ M1 v`, the synthesis `U c`, a few rows of `U` (the reduced
//! constraints of splines and soft design) and every field once (the basis id of compressed
//! files) — whether its fields are held in memory ([`crate::SpectralBasis`]) or read from a
//! basis file a block of columns at a time ([`crate::BasisFileBlocks`]). Filters, Fourier
//! analyses, the codec and the reduced solvers take any of them.

use crate::{FieldFamily, SpectralBasis, SpectralBasisError};
use rayon::prelude::*;
use tvf_core::discretization::Mass;

/// A Fourier basis `U` (`n1 × d`, `Uᵀ M1 U = I`) seen through its products.
pub trait FieldBasis: Send + Sync {
    /// Number of basis fields `d`.
    fn len(&self) -> usize;

    /// Whether the basis has no field.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Dimension `n1` of the field space.
    fn field_dimension(&self) -> usize;

    /// Eigenvalues `λ_i` of `L`, ascending, `d` entries (units 1/length²).
    fn eigenvalues(&self) -> &[f64];

    /// Family of each basis field, `d` entries.
    fn families(&self) -> &[FieldFamily];

    /// Fourier coefficients `Uᵀ M1 v` of a field `v` (`n1` entries), `d` entries.
    fn coefficients(&self, field: &[f64]) -> Result<Vec<f64>, SpectralBasisError>;

    /// The field `U c` for coefficients `c` (`d` entries), `n1` entries.
    fn reconstruct(&self, coefficients: &[f64]) -> Result<Vec<f64>, SpectralBasisError>;

    /// The fields `U c` of several coefficient vectors `sets` (`d` entries each), `n1` entries
    /// each, equal bit for bit to [`FieldBasis::reconstruct`] of each: in parallel for a basis
    /// in memory, in one pass over the file for a basis file read in blocks (so that decoding a
    /// sequence or a rate–distortion curve reads the file once and holds one block).
    fn reconstruct_many(&self, sets: &[&[f64]]) -> Result<Vec<Vec<f64>>, SpectralBasisError> {
        sets.par_iter().map(|c| self.reconstruct(c)).collect()
    }

    /// `M1` inner product `aᵀ M1 b` of two fields (`n1` entries each).
    fn inner_product(&self, a: &[f64], b: &[f64]) -> f64;

    /// The field mass `M1` (`n1 × n1`) the basis is orthonormal in.
    fn field_mass(&self) -> &Mass;

    /// Rows `U[r, ·]` of the fields (`d` values each, in basis order) for the field coefficients
    /// `r` of `rows` (each `< n1`): what a constraint row `C̃ U` needs.
    fn rows(&self, rows: &[usize]) -> Result<Vec<Vec<f64>>, SpectralBasisError>;

    /// Calls `visit(i, U[·, i])` once with every basis field `i` (`n1` values), from several
    /// threads and in no fixed order.
    fn visit_fields(
        &self,
        visit: &(dyn Fn(usize, &[f64]) + Sync),
    ) -> Result<(), SpectralBasisError>;
}

/// Checks that every row index of `rows` is below `n1`.
pub(crate) fn check_rows(rows: &[usize], n1: usize) -> Result<(), SpectralBasisError> {
    match rows.iter().find(|&&r| r >= n1) {
        Some(&r) => Err(SpectralBasisError::LengthMismatch {
            what: "row of the fields (must be below the field dimension n1)",
            expected: n1,
            actual: r,
        }),
        None => Ok(()),
    }
}

impl FieldBasis for SpectralBasis {
    fn len(&self) -> usize {
        SpectralBasis::len(self)
    }

    fn field_dimension(&self) -> usize {
        SpectralBasis::field_dimension(self)
    }

    fn eigenvalues(&self) -> &[f64] {
        SpectralBasis::eigenvalues(self)
    }

    fn families(&self) -> &[FieldFamily] {
        SpectralBasis::families(self)
    }

    fn coefficients(&self, field: &[f64]) -> Result<Vec<f64>, SpectralBasisError> {
        SpectralBasis::coefficients(self, field)
    }

    fn reconstruct(&self, coefficients: &[f64]) -> Result<Vec<f64>, SpectralBasisError> {
        SpectralBasis::reconstruct(self, coefficients)
    }

    fn inner_product(&self, a: &[f64], b: &[f64]) -> f64 {
        SpectralBasis::inner_product(self, a, b)
    }

    fn field_mass(&self) -> &Mass {
        SpectralBasis::field_mass(self)
    }

    fn rows(&self, rows: &[usize]) -> Result<Vec<Vec<f64>>, SpectralBasisError> {
        check_rows(rows, self.field_dimension())?;
        let fields = self.fields();
        Ok(rows
            .iter()
            .map(|&r| (0..self.len()).map(|i| fields[(r, i)]).collect())
            .collect())
    }

    fn visit_fields(
        &self,
        visit: &(dyn Fn(usize, &[f64]) + Sync),
    ) -> Result<(), SpectralBasisError> {
        let fields = self.fields();
        (0..self.len()).into_par_iter().for_each(|i| {
            let column = fields.col(i);
            match column.try_as_col_major() {
                Some(column) => visit(i, column.as_slice()),
                None => visit(i, &column.iter().copied().collect::<Vec<f64>>()),
            }
        });
        Ok(())
    }
}
