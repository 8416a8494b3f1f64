//! [`SpectralFilter`]: scale a field's Fourier coefficients by functions of frequency, one for
//! the integrable and one for the co-integrable family, a constant for the harmonic part and one
//! for the rest field (Section 8.5 of the paper).

use crate::basis::{FieldFamily, SpectralBasisError};
use crate::filter_response::FrequencyResponse;
use crate::FieldBasis;
use thiserror::Error;

/// Why a filter could not be applied.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FilterError {
    /// The field does not fit the basis.
    #[error(transparent)]
    Basis(#[from] SpectralBasisError),
    /// A constant gain is negative or not finite.
    #[error("{what} gain {value} must be finite and ≥ 0")]
    BadGain {
        /// `harmonic` or `rest`.
        what: &'static str,
        /// The value.
        value: f64,
    },
    /// The field has a non-finite entry.
    #[error("field entry {index} is not finite")]
    NonFiniteField {
        /// Position in the `n1` coefficients (the complex's field numbering).
        index: usize,
    },
}

/// A spectral filter. With a basis `U` (`n1 × d`, `Uᵀ M_X U = I`) and a field `v` (`n1`,
/// pointwise), coefficients `c = Uᵀ M_X v` and rest field `v_r = v − U c`, the output is
///
/// ```text
/// v* = U (g ∘ c) + γ_r v_r,     g_i = F_α(√λ_i) (integrable), F_β(√λ_i) (co-integrable), γ_h (harmonic)
/// ```
///
/// computed as `γ_r v + U ((g − γ_r) ∘ c)` (one reconstruction). The parts stay
/// `M_X`-orthogonal, so a filter whose gains are all ≤ 1 never increases the `M_X` norm nor the
/// Dirichlet energy `vᵀ S v` (both are diagonal in an eigenbasis, and `v_r` is `S`-orthogonal to
/// `U`).
#[derive(Debug, Clone, PartialEq)]
pub struct SpectralFilter {
    /// `F_α`: gain of the integrable (curl-free) coefficients against frequency.
    pub integrable: FrequencyResponse,
    /// `F_β`: gain of the co-integrable (divergence-free) coefficients against frequency.
    pub cointegrable: FrequencyResponse,
    /// `γ_h`: gain of the harmonic part.
    pub harmonic_gain: f64,
    /// `γ_r`: gain of the rest field `v_r` (what the truncated basis cannot represent).
    pub rest_gain: f64,
}

impl Default for SpectralFilter {
    fn default() -> Self {
        Self::identity()
    }
}

/// The result of [`SpectralFilter::apply`].
#[derive(Debug, Clone, PartialEq)]
pub struct FilteredField {
    /// The filtered field `v*` (`n1`, pointwise).
    pub field: Vec<f64>,
    /// Coefficients `c = Uᵀ M_X v` of the input (`d`).
    pub coefficients: Vec<f64>,
    /// Coefficients `g ∘ c` of the output's represented part (`d`).
    pub filtered_coefficients: Vec<f64>,
    /// `‖v_r‖_{M_X}` of the input's rest field (integrated norm, units field × length).
    pub rest_norm: f64,
}

impl SpectralFilter {
    /// Gain 1 everywhere: returns the field unchanged.
    pub fn identity() -> Self {
        Self {
            integrable: FrequencyResponse::Identity,
            cointegrable: FrequencyResponse::Identity,
            harmonic_gain: 1.0,
            rest_gain: 1.0,
        }
    }

    /// The same response for both families, with harmonic gain 1 and rest gain `rest_gain`.
    pub fn both(response: FrequencyResponse, rest_gain: f64) -> Self {
        Self {
            integrable: response.clone(),
            cointegrable: response,
            harmonic_gain: 1.0,
            rest_gain,
        }
    }

    /// The gain the rest field (the part above the basis) gets when none is given: the
    /// responses continued beyond the basis, their gain at its highest frequency `√λ_max`, the
    /// larger of the two families' (1 for identity responses, so that filtering with every
    /// default returns the field; about `e^(−t·λ_max)` for a low-pass, which then removes the
    /// high frequencies the basis cannot represent instead of keeping them as noise).
    pub fn continued_rest_gain(
        integrable: &FrequencyResponse,
        cointegrable: &FrequencyResponse,
        basis: &(impl FieldBasis + ?Sized),
    ) -> f64 {
        let top = basis
            .eigenvalues()
            .iter()
            .copied()
            .fold(0.0f64, f64::max)
            .sqrt();
        integrable.gain(top).max(cointegrable.gain(top))
    }

    /// The gain of every basis field (`d` entries).
    pub fn gains(&self, basis: &(impl FieldBasis + ?Sized)) -> Vec<f64> {
        basis
            .families()
            .iter()
            .zip(basis.eigenvalues())
            .map(|(family, &lambda)| match family {
                FieldFamily::Harmonic => self.harmonic_gain,
                FieldFamily::Integrable => self.integrable.gain(lambda.sqrt()),
                FieldFamily::Cointegrable => self.cointegrable.gain(lambda.sqrt()),
            })
            .collect()
    }

    /// Filters `field` (`n1` pointwise coefficients) in `basis`.
    pub fn apply(
        &self,
        basis: &(impl FieldBasis + ?Sized),
        field: &[f64],
    ) -> Result<FilteredField, FilterError> {
        for (what, value) in [("harmonic", self.harmonic_gain), ("rest", self.rest_gain)] {
            if !value.is_finite() || value < 0.0 {
                return Err(FilterError::BadGain { what, value });
            }
        }
        if let Some(index) = field.iter().position(|x| !x.is_finite()) {
            return Err(FilterError::NonFiniteField { index });
        }
        let coefficients = basis.coefficients(field)?;
        let gains = self.gains(basis);
        let filtered_coefficients: Vec<f64> = coefficients
            .iter()
            .zip(&gains)
            .map(|(c, g)| g * c)
            .collect();
        let delta: Vec<f64> = coefficients
            .iter()
            .zip(&gains)
            .map(|(c, g)| (g - self.rest_gain) * c)
            .collect();
        // Both syntheses in one pass over the basis (one read of a basis file, not two).
        let [represented, mut output]: [Vec<f64>; 2] = basis
            .reconstruct_many(&[&coefficients, &delta])?
            .try_into()
            .expect("one synthesis per coefficient set");
        let rest: Vec<f64> = field.iter().zip(&represented).map(|(v, u)| v - u).collect();
        let rest_norm = basis.inner_product(&rest, &rest).max(0.0).sqrt();
        output
            .iter_mut()
            .zip(field)
            .for_each(|(o, v)| *o += self.rest_gain * v);
        Ok(FilteredField {
            field: output,
            coefficients,
            filtered_coefficients,
            rest_norm,
        })
    }
}
