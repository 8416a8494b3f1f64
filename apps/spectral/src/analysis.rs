//! Spectral analysis of a field: its Fourier coefficients against frequency (the paper's
//! Figure 8) and how its energy splits over the Hodge decomposition (built on
//! [`FourierAnalysis`]).

use crate::basis::{FieldFamily, SpectralBasis, SpectralBasisError};
use crate::fourier::FourierAnalysis;
use tvf_core::discretization::{HodgeComplex, Mass};
use tvf_discretizations::{DecompositionError, HodgeDecomposer, HodgeParts};

/// One basis field's coefficient.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoefficientEntry {
    /// Position in the basis (ascending eigenvalue).
    pub index: usize,
    /// Family of the basis field.
    pub family: FieldFamily,
    /// Eigenvalue `λ` (1/length²).
    pub eigenvalue: f64,
    /// Frequency `√λ` (1/length).
    pub frequency: f64,
    /// Coefficient `u_iᵀ M_X v` (integrated: field × length).
    pub coefficient: f64,
}

/// Squared `M_X` norms (integrated, field² × area) of the parts of a field.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EnergySplit {
    /// Integrable (curl-free) part.
    pub integrable: f64,
    /// Co-integrable (divergence-free) part.
    pub cointegrable: f64,
    /// Harmonic part.
    pub harmonic: f64,
    /// Rest field (what a truncated basis cannot represent; 0 for an exact decomposition).
    pub rest: f64,
}

impl EnergySplit {
    /// Sum of the four parts (equals `‖v‖²_{M1}` since the parts are `M1`-orthogonal).
    pub fn total(&self) -> f64 {
        self.integrable + self.cointegrable + self.harmonic + self.rest
    }

    /// The squared norms of the three parts of an exact Hodge decomposition in the field mass
    /// `M1`; `rest` is 0.
    pub fn of_hodge_parts(parts: &HodgeParts, field_mass: &Mass) -> Self {
        let norm2 = |x: &[f64]| -> f64 {
            match field_mass.diagonal_values() {
                Some(mass) => x.iter().zip(mass).map(|(a, m)| a * a * m).sum(),
                None => field_mass.inner(x, x),
            }
        };
        Self {
            integrable: norm2(&parts.integrable),
            cointegrable: norm2(&parts.cointegrable),
            harmonic: norm2(&parts.harmonic),
            rest: 0.0,
        }
    }
}

/// The energies of the exact Hodge decomposition of `field` (`n1` coefficients) by `complex`
/// ([`HodgeDecomposer`]), in its field mass `M1` ([`EnergySplit::of_hodge_parts`]): what a
/// truncated basis's split is compared with.
pub fn exact_hodge_energies(
    complex: &dyn HodgeComplex,
    field: &[f64],
) -> Result<EnergySplit, DecompositionError> {
    let parts = HodgeDecomposer::new(complex)?.decompose(field)?;
    Ok(EnergySplit::of_hodge_parts(&parts, complex.m1()))
}

/// The spectral analysis of one field in one basis.
#[derive(Debug, Clone, PartialEq)]
pub struct SpectralAnalysis {
    /// One entry per basis field, ascending frequency.
    pub entries: Vec<CoefficientEntry>,
    /// Energy of the represented families (`Σ c_i²` per family) and of the rest field `‖v_r‖²`.
    pub energy: EnergySplit,
    /// `‖v‖²_{M_X}` of the field.
    pub field_energy: f64,
    /// Dirichlet energy `Σ λ_i c_i²` of the represented part (integrated, field²); equals
    /// `vᵀ S v` when the basis is complete.
    pub represented_dirichlet_energy: f64,
}

impl SpectralAnalysis {
    /// Analyses `field` (`n1` pointwise coefficients in the complex's field numbering) in `basis`.
    pub fn new(basis: &SpectralBasis, field: &[f64]) -> Result<Self, SpectralBasisError> {
        let fourier = FourierAnalysis::new(basis, field)?;
        let energy = EnergySplit {
            integrable: fourier.family_energy(FieldFamily::Integrable),
            cointegrable: fourier.family_energy(FieldFamily::Cointegrable),
            harmonic: fourier.family_energy(FieldFamily::Harmonic),
            rest: basis.inner_product(&fourier.rest, &fourier.rest),
        };
        let entries: Vec<CoefficientEntry> = fourier
            .coefficients
            .iter()
            .zip(basis.eigenvalues())
            .zip(basis.families())
            .enumerate()
            .map(
                |(index, ((&coefficient, &eigenvalue), &family))| CoefficientEntry {
                    index,
                    family,
                    eigenvalue,
                    frequency: eigenvalue.sqrt(),
                    coefficient,
                },
            )
            .collect();
        let represented_dirichlet_energy = entries
            .iter()
            .map(|e| e.eigenvalue * e.coefficient * e.coefficient)
            .sum();
        Ok(Self {
            entries,
            energy,
            field_energy: fourier.norm * fourier.norm,
            represented_dirichlet_energy,
        })
    }

    /// The coefficients as CSV: a header `index,family,eigenvalue,frequency,coefficient`, then
    /// one line per basis field (numbers in `{:e}` notation).
    pub fn coefficients_csv(&self) -> String {
        let mut csv = String::from("index,family,eigenvalue,frequency,coefficient\n");
        for e in &self.entries {
            csv.push_str(&format!(
                "{},{},{:e},{:e},{:e}\n",
                e.index,
                e.family.name(),
                e.eigenvalue,
                e.frequency,
                e.coefficient
            ));
        }
        csv
    }

    /// The entries of one family, ascending frequency.
    pub fn family(&self, family: FieldFamily) -> impl Iterator<Item = &CoefficientEntry> + '_ {
        self.entries.iter().filter(move |e| e.family == family)
    }

    /// Relative size of the rest field, `‖v_r‖ / ‖v‖` (0 for a zero field).
    pub fn relative_rest_norm(&self) -> f64 {
        if self.field_energy > 0.0 {
            (self.energy.rest.max(0.0) / self.field_energy).sqrt()
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::discretization::HodgeOperators;

    #[test]
    fn the_exact_energies_add_up_to_the_field_energy() {
        let (_, complex) = crate::test_torus::torus_complex("conforming-consistent");
        let n = complex.field_dimension();
        let field: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let split = exact_hodge_energies(complex.as_ref(), &field).unwrap();
        let energy = complex.m1().inner(&field, &field);
        assert!(
            (split.total() - energy).abs() <= 1e-9 * energy,
            "{split:?} {energy}"
        );
        assert!(split.integrable > 0.0 && split.cointegrable > 0.0 && split.harmonic > 0.0);
        assert_eq!(split.rest, 0.0);
        assert!(exact_hodge_energies(complex.as_ref(), &field[1..]).is_err());
    }
}
