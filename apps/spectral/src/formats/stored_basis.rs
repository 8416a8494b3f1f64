//! [`StoredBasis`]: a basis as a basis file holds it, dense fields or eigenfunctions.

use crate::{EigenfunctionBasis, FieldFamily, SpectralBasis, SpectralBasisError};
use tvf_core::discretization::HodgeComplex;

/// A basis read from a basis file, in the form the file holds it.
#[derive(Debug, Clone)]
pub enum StoredBasis {
    /// Dense fields (`n1 × d`) with `M1` as the file stores it (diagonal or sparse).
    Fields(Box<SpectralBasis>),
    /// Eigenfunctions; the fields need the complex the basis was computed for.
    Eigenfunctions(Box<EigenfunctionBasis>),
}

impl StoredBasis {
    /// Number of basis fields `d`.
    pub fn len(&self) -> usize {
        self.eigenvalues().len()
    }

    /// Whether the basis has no field.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Eigenvalues, ascending (`d` entries, 1/length²).
    pub fn eigenvalues(&self) -> &[f64] {
        match self {
            StoredBasis::Fields(basis) => basis.eigenvalues(),
            StoredBasis::Eigenfunctions(basis) => basis.eigenvalues(),
        }
    }

    /// Family of each basis field (`d` entries).
    pub fn families(&self) -> &[FieldFamily] {
        match self {
            StoredBasis::Fields(basis) => basis.families(),
            StoredBasis::Eigenfunctions(basis) => basis.families(),
        }
    }

    /// The basis with dense fields: eigenfunctions are turned into fields through the sparse
    /// gradients of `complex` (in parallel), with `M1` from `complex`. Errors when `complex`
    /// does not have the shapes of the stored basis.
    pub fn into_fields<H: HodgeComplex + ?Sized>(
        self,
        complex: &H,
    ) -> Result<SpectralBasis, SpectralBasisError> {
        match self {
            StoredBasis::Fields(basis) => Ok(*basis),
            StoredBasis::Eigenfunctions(compact) => {
                compact.check_complex(complex)?;
                SpectralBasis::new(
                    compact.eigenvalues().to_vec(),
                    compact.families().to_vec(),
                    compact.dense_fields(complex),
                    complex.m1().clone(),
                )
            }
        }
    }
}
