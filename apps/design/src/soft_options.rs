//! [`SoftOptions`]: the weights of soft-constrained design, shared by the full and the reduced
//! solvers (and the systems behind the full one) so that the two agree.

use crate::error::DesignError;

/// Parameters of soft design (full and reduced use the same ones, so that they agree).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoftOptions {
    /// Weight `ω ≥ 0` of the biharmonic term: energy `E_D + ω E_B`.
    pub omega: f64,
    /// `ε ≥ 0`: a screening term `ε M1` (units 1/length²) that makes the system definite on
    /// the harmonic fields when the constraints do not fix them (genus > 0). See
    /// [`crate::default_regularization`].
    pub regularization: f64,
}

impl SoftOptions {
    /// Checks that both weights are finite and non-negative.
    ///
    /// Errors: [`DesignError::BadParameter`] naming the first weight that is not.
    pub(crate) fn check(self) -> Result<(), DesignError> {
        for (what, value) in [
            ("omega", self.omega),
            ("regularization", self.regularization),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(DesignError::BadParameter { what, value });
            }
        }
        Ok(())
    }
}
