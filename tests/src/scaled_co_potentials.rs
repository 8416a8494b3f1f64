//! [`ScaledCoPotentials`]: the smallest complex that is not in the catalog, the wrapper of the
//! seam's documentation (`tvf_core::discretization`), run through the whole core suite.

use sprs::CsMat;
use tvf_core::discretization::{
    ComplexTopology, DiagonalMass, DiscretizationError, FieldSampling, HodgeComplex, NodeSpace,
    OperatorCache,
};

/// Any complex with its co-potential inner product `M2⁻¹` scaled by `factor` (so `M2` by
/// `1/factor`); `d0`, `d1`, `M0`, `M1`, the nodes and the sampling are the inner complex's.
///
/// It owns a fresh [`OperatorCache`], so every derived operator sees the new `M2`: the co-exact
/// eigenvalues (of `(d1 M1⁻¹ d1ᵀ, M2⁻¹)`) are the inner ones divided by `factor`, and so are the
/// co-exact eigenvalues of its own `L`. Forwarding the inner cache would leave `L` with the old
/// co-exact part while the co-exact eigenproblem changes.
pub struct ScaledCoPotentials<H> {
    inner: H,
    id: String,
    m2: DiagonalMass,
    cache: OperatorCache,
}

impl<H: HodgeComplex> ScaledCoPotentials<H> {
    /// Wraps `inner`, scaling `M2⁻¹` by `factor` (positive); id `{inner id}-scaled-co-potentials`.
    pub fn new(inner: H, factor: f64) -> Result<Self, DiscretizationError> {
        let m2 = inner.m2().values().iter().map(|m| m / factor).collect();
        Ok(Self {
            id: format!("{}-scaled-co-potentials", inner.id()),
            m2: DiagonalMass::new("M2", m2)?,
            inner,
            cache: OperatorCache::default(),
        })
    }
}

impl<H: HodgeComplex> HodgeComplex for ScaledCoPotentials<H> {
    fn id(&self) -> &str {
        &self.id
    }

    fn d0(&self) -> &CsMat<f64> {
        self.inner.d0()
    }

    fn d1(&self) -> &CsMat<f64> {
        self.inner.d1()
    }

    fn m0(&self) -> &DiagonalMass {
        self.inner.m0()
    }

    fn m1(&self) -> &DiagonalMass {
        self.inner.m1()
    }

    fn m2(&self) -> &DiagonalMass {
        &self.m2
    }

    fn potential_nodes(&self) -> &NodeSpace {
        self.inner.potential_nodes()
    }

    fn field_nodes(&self) -> &NodeSpace {
        self.inner.field_nodes()
    }

    fn co_potential_nodes(&self) -> &NodeSpace {
        self.inner.co_potential_nodes()
    }

    fn topology(&self) -> &ComplexTopology {
        self.inner.topology()
    }

    fn operator_cache(&self) -> &OperatorCache {
        &self.cache
    }

    fn sampling(&self) -> Option<&dyn FieldSampling> {
        self.inner.sampling()
    }
}
