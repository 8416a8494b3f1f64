//! [`DiagonalMass`]: what a mass matrix of the seam is today, a non-negative diagonal.

use super::DiscretizationError;
use super::NO_COMPONENT;

/// A lumped (diagonal) mass matrix: one finite, non-negative weight per node, positive on every
/// node that some face uses (a zero weight marks a node no face uses, see
/// [`super::NO_COMPONENT`]).
///
/// Every mass of a [`super::HodgeComplex`] has this type, so code that needs `M⁻¹` can take the
/// reciprocal entry by entry. A sparse symmetric positive definite (Galerkin) mass would become a
/// second type beside this one, with a factorization in place of [`DiagonalMass::inverse`].
#[derive(Debug, Clone, PartialEq)]
pub struct DiagonalMass {
    values: Vec<f64>,
}

impl DiagonalMass {
    /// Checks and wraps a diagonal: every entry finite and non-negative. `what` names the mass in
    /// the error (e.g. `"M1 (⋆1, the edge Hodge star)"`).
    pub fn new(what: &'static str, values: Vec<f64>) -> Result<Self, DiscretizationError> {
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
        Ok(Self { values })
    }

    /// Like [`DiagonalMass::new`], and also positive on every node whose component (in
    /// `components`, one per node) is not [`NO_COMPONENT`].
    pub fn positive_on_used_nodes(
        what: &'static str,
        values: Vec<f64>,
        components: &[usize],
    ) -> Result<Self, DiscretizationError> {
        let mass = Self::new(what, values)?;
        mass.check_positive_on(what, components)?;
        Ok(mass)
    }

    /// Fails with [`DiscretizationError::NotPositive`] unless every node whose component is not
    /// [`NO_COMPONENT`] has a positive weight.
    pub fn check_positive_on(
        &self,
        what: &'static str,
        components: &[usize],
    ) -> Result<(), DiscretizationError> {
        let zero: Vec<usize> = (0..self.values.len())
            .filter(|&i| self.values[i] <= 0.0 && components.get(i) != Some(&NO_COMPONENT))
            .collect();
        match zero.first() {
            Some(&first) => Err(DiscretizationError::NotPositive {
                what,
                count: zero.len(),
                first,
                value: self.values[first],
            }),
            None => Ok(()),
        }
    }

    /// The diagonal (`n` entries).
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Number of nodes `n`.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Whether the mass has no node.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// The (pseudo-)inverse diagonal: `1/m` for `m > 0`, and 0 where `m = 0` (unused nodes).
    pub fn inverse(&self) -> Vec<f64> {
        self.values
            .iter()
            .map(|&m| if m > 0.0 { 1.0 / m } else { 0.0 })
            .collect()
    }

    /// `M x` (`n` entries in, `n` out).
    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        x.iter().zip(&self.values).map(|(a, m)| a * m).collect()
    }

    /// `xᵀ M y`.
    pub fn inner(&self, x: &[f64], y: &[f64]) -> f64 {
        x.iter()
            .zip(y)
            .zip(&self.values)
            .map(|((a, b), m)| a * b * m)
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_negative_and_non_finite_entries() {
        let err = DiagonalMass::new("M1", vec![1.0, -2.0, 3.0, -0.5]).unwrap_err();
        assert_eq!(
            err,
            DiscretizationError::NotPositive {
                what: "M1",
                count: 2,
                first: 1,
                value: -2.0
            }
        );
        assert!(DiagonalMass::new("M1", vec![1.0, f64::NAN]).is_err());
    }

    #[test]
    fn zero_only_on_unused_nodes() {
        let used = [0, NO_COMPONENT, 0];
        assert!(DiagonalMass::positive_on_used_nodes("M0", vec![1.0, 0.0, 2.0], &used).is_ok());
        assert!(DiagonalMass::positive_on_used_nodes("M0", vec![0.0, 1.0, 2.0], &used).is_err());
        let mass = DiagonalMass::new("M0", vec![2.0, 0.0]).unwrap();
        assert_eq!(mass.inverse(), vec![0.5, 0.0]);
        assert_eq!(mass.inner(&[1.0, 5.0], &[3.0, 7.0]), 6.0);
    }
}
