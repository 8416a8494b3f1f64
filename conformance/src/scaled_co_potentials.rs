//! [`ScaledCoPotentials`]: the smallest complex that is not in the catalog, the wrapper of the
//! seam's documentation (`tvf_core::discretization`), run through the whole core suite.

use tvf_core::discretization::{ComplexParts, DiscretizationError, FieldSampling, HodgeComplex};

/// Any complex with its co-potential inner product `M2⁻¹` scaled by `factor` (so `M2` by
/// `1/factor`); `d0`, `d1`, `M0`, `M1`, the nodes and the sampling are the inner complex's.
///
/// Its new [`ComplexParts`] own a fresh operator cache, so every derived operator sees the new `M2`: the co-exact
/// eigenvalues (of `(d1 M1⁻¹ d1ᵀ, M2⁻¹)`) are the inner ones divided by `factor`, and so are the
/// co-exact eigenvalues of its own `L`. Forwarding the inner cache would leave `L` with the old
/// co-exact part while the co-exact eigenproblem changes.
pub struct ScaledCoPotentials<H> {
    inner: H,
    parts: ComplexParts,
}

impl<H: HodgeComplex> ScaledCoPotentials<H> {
    /// Wraps `inner`, scaling `M2⁻¹` by `factor` (positive); id `{inner id}-scaled-co-potentials`.
    pub fn new(inner: H, factor: f64) -> Result<Self, DiscretizationError> {
        let m2 = inner.m2().scaled("M2 (scaled)", 1.0 / factor);
        let id = format!("{}-scaled-co-potentials", inner.id());
        let parts = inner.parts().with_co_potential_mass(id, m2)?;
        Ok(Self { inner, parts })
    }
}

impl<H: HodgeComplex> HodgeComplex for ScaledCoPotentials<H> {
    fn parts(&self) -> &ComplexParts {
        &self.parts
    }

    fn sampling(&self) -> Option<&dyn FieldSampling> {
        self.inner.sampling()
    }
}
