//! Fourier analysis of a field in a [`crate::SpectralBasis`] (or any [`FieldBasis`]): the coefficients `α`, `β`, `γ` by family,
//! reconstruction, and the rest field the truncated basis cannot represent.

use crate::{FieldBasis, FieldFamily, SpectralBasisError};

/// The Fourier representation of one field `v` (equation (11) of the paper) in a basis `U`.
#[derive(Debug, Clone, PartialEq)]
pub struct FourierAnalysis {
    /// All coefficients `Uᵀ M_X v` in basis order (`d` entries, integrated: units of `v` times
    /// length).
    pub coefficients: Vec<f64>,
    /// Integrable coefficients `α_i = ⟨v, Φ_i⟩` with their eigenvalues `λ_i`, ascending.
    pub alpha: Vec<(f64, f64)>,
    /// Co-integrable coefficients `β_i = ⟨v, Ψ_i⟩` with their eigenvalues `μ_i`, ascending.
    pub beta: Vec<(f64, f64)>,
    /// Harmonic coefficients `γ_i = ⟨v, Γ_i⟩`.
    pub gamma: Vec<f64>,
    /// The rest field `v_r = v − U Uᵀ M_X v` (`n1` pointwise entries): the part of `v` outside the
    /// span of the basis (zero for a complete basis).
    pub rest: Vec<f64>,
    /// `‖v‖_{M_X}`.
    pub norm: f64,
    /// `‖v_r‖_{M_X} / ‖v‖_{M_X}` (0 for a zero field).
    pub relative_rest_norm: f64,
}

impl FourierAnalysis {
    /// Analyses `field` (`n1` pointwise coefficients) in `basis`.
    pub fn new<B: FieldBasis + ?Sized>(
        basis: &B,
        field: &[f64],
    ) -> Result<Self, SpectralBasisError> {
        let coefficients = basis.coefficients(field)?;
        let projection = basis.reconstruct(&coefficients)?;
        let rest: Vec<f64> = field.iter().zip(&projection).map(|(v, p)| v - p).collect();
        let norm = basis.inner_product(field, field).sqrt();
        let rest_norm = basis.inner_product(&rest, &rest).sqrt();
        let pick = |family| {
            coefficients
                .iter()
                .zip(basis.eigenvalues())
                .zip(basis.families())
                .filter(move |(_, &f)| f == family)
                .map(|((&c, &l), _)| (l, c))
        };
        Ok(Self {
            alpha: pick(FieldFamily::Integrable).collect(),
            beta: pick(FieldFamily::Cointegrable).collect(),
            gamma: pick(FieldFamily::Harmonic).map(|(_, c)| c).collect(),
            coefficients,
            rest,
            norm,
            relative_rest_norm: if norm > 0.0 { rest_norm / norm } else { 0.0 },
        })
    }

    /// Energy `Σ c²` of the coefficients of one family (integrated, units of `‖v‖²_{M_X}`).
    pub fn family_energy(&self, family: FieldFamily) -> f64 {
        match family {
            FieldFamily::Integrable => self.alpha.iter().map(|(_, c)| c * c).sum(),
            FieldFamily::Cointegrable => self.beta.iter().map(|(_, c)| c * c).sum(),
            FieldFamily::Harmonic => self.gamma.iter().map(|c| c * c).sum(),
        }
    }
}

/// The field `U c + rest` from coefficients `c` (`d` entries) and an optional rest field: the
/// inverse of [`FourierAnalysis::new`] when given its coefficients and rest.
pub fn reconstruct_with_rest<B: FieldBasis + ?Sized>(
    basis: &B,
    coefficients: &[f64],
    rest: Option<&[f64]>,
) -> Result<Vec<f64>, SpectralBasisError> {
    let mut field = basis.reconstruct(coefficients)?;
    if let Some(rest) = rest {
        if rest.len() != field.len() {
            return Err(SpectralBasisError::LengthMismatch {
                what: "rest field",
                expected: field.len(),
                actual: rest.len(),
            });
        }
        field.iter_mut().zip(rest).for_each(|(f, r)| *f += r);
    }
    Ok(field)
}
