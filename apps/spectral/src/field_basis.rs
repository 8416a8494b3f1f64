//! [`FieldBasis`]: what spectral processing needs of a Fourier basis — its eigenvalues and
//! families, the projection `Uᵀ M1 v` and the synthesis `U c` — whether its fields are held in
//! memory ([`crate::SpectralBasis`]) or read from a basis file a block of columns at a time
//! ([`crate::BasisFileBlocks`]). Filters and Fourier analyses take any of them.

use crate::{FieldFamily, SpectralBasis, SpectralBasisError};

/// A Fourier basis `U` (`n1 × d`, `Uᵀ M1 U = I`) seen through its products.
pub trait FieldBasis {
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

    /// `M1` inner product `aᵀ M1 b` of two fields (`n1` entries each).
    fn inner_product(&self, a: &[f64], b: &[f64]) -> f64;
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
}
