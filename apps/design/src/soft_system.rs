//! [`SoftSystem`]: what [`crate::FullSoftDesign`] asks of its factored soft-design system,
//! whatever the masses of the complex ([`crate::diagonal_system`] for a diagonal `M1` and a
//! sparse `S`, [`crate::galerkin_soft`] for any other masses), and [`Factoring`], how that
//! system is factored.

use crate::constraint::CompiledConstraint;
use crate::error::DesignError;
use std::fmt::Debug;
use std::time::Instant;
use tvf_solvers::iterative_refinement::SolveReport;
use tvf_solvers::{FactorParallelism, FillOrdering, SparseLdlt};

/// How an augmented system is factored: the fill-reducing ordering of its symbolic analyses and
/// the threading of its factorizations and solves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Factoring {
    /// The fill-reducing ordering (kept for later symbolic analyses).
    pub(crate) ordering: FillOrdering,
    /// One thread or all of them, chosen per factorization.
    pub(crate) parallelism: FactorParallelism,
}

/// A factored soft-design system `A x = b`, `A = S + ωB + εM1 + C̃ᵀWC̃` (see
/// [`crate::FullSoftDesign`]). Every vector has `n1` values; with fixed field nodes the entries
/// there are ignored on input and zero on output.
pub(crate) trait SoftSystem: Debug + Send + Sync {
    /// The factorization of the augmented system.
    fn factor(&self) -> &SparseLdlt;

    /// Number of field coefficients `n1`.
    fn field_dimension(&self) -> usize;

    /// Replaces the constraints (columns checked by the caller) and refactors, numerically only
    /// when the pattern and the unknowns of the system hold them; returns whether the symbolic
    /// analysis was reused and the time the assembly ended.
    fn set_constraints(
        &mut self,
        constraints: &[CompiledConstraint],
        factoring: Factoring,
    ) -> Result<(bool, Instant), DesignError>;

    /// `A x`, without forming `B` (see [`crate::FullSoftDesign::apply`]).
    fn apply(&self, x: &[f64]) -> Vec<f64>;

    /// `b − A x` in double-double (see [`crate::FullSoftDesign::accurate_residual`]).
    fn accurate_residual(&self, x: &[f64], b: &[f64]) -> Vec<f64>;

    /// The solution of `A x = b` through the factor, refined on `A` (see
    /// [`crate::FullSoftDesign::solve`]).
    fn solve(&self, b: &[f64]) -> (Vec<f64>, SolveReport);
}
