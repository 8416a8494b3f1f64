//! [`OperatorCache`]: where a complex keeps the operators derived from its five matrices.

use super::LinearOperator;
use sprs::CsMat;
use std::sync::OnceLock;

/// Derived sparse operators of one complex, each computed on first use by
/// [`super::HodgeOperators`] and kept. An implementor of [`super::HodgeComplex`] owns one
/// (`OperatorCache::default()`) and never fills it itself.
#[derive(Debug, Default)]
pub struct OperatorCache {
    pub(crate) potential_stiffness: OnceLock<CsMat<f64>>,
    pub(crate) co_potential_stiffness: OnceLock<LinearOperator>,
    pub(crate) potential_divergence: OnceLock<LinearOperator>,
    pub(crate) co_potential_curl: OnceLock<LinearOperator>,
    pub(crate) co_gradient: OnceLock<LinearOperator>,
    pub(crate) dirichlet_energy: OnceLock<LinearOperator>,
    pub(crate) hodge_laplacian: OnceLock<LinearOperator>,
    pub(crate) biharmonic_energy: OnceLock<LinearOperator>,
    pub(crate) other_divergence: OnceLock<LinearOperator>,
    pub(crate) other_curl: OnceLock<LinearOperator>,
}

impl Clone for OperatorCache {
    /// A clone starts empty: the clone of a complex may be changed before first use.
    fn clone(&self) -> Self {
        Self::default()
    }
}
