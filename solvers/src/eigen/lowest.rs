//! [`lowest_eigenpairs`]: the lowest eigenpairs of one pencil (the driver is
//! [`super::interval_slicing`]).

use super::interval_slicing::{lowest_eigenpairs_of, EigenRequest};
use super::pencil::Pencil;
use super::types::{EigenOptions, Eigenpairs};
use crate::error::SolverError;

/// The lowest `k` eigenpairs of `A x = λ M x` (with what they cost: [`Eigenpairs::statistics`]).
///
/// - `a`: `n × n` sparse symmetric positive-semidefinite matrix (e.g. a stiffness matrix,
///   integrated), full or upper-triangular storage, CSC or CSR. It may have several zero
///   eigenvalues (one per connected component for a Laplacian). Mildly negative eigenvalues
///   are found too.
/// - `mass_diagonal`: the `n` positive entries of the diagonal mass matrix `M`.
///
/// Returns every eigenvalue up to the k-th, in ascending order, with repeated eigenvalues
/// repeated: completeness is verified by Sylvester's law of inertia (the number of negative
/// pivots of `A − σM` for a shift σ above the k-th eigenvalue equals the number of computed
/// eigenvalues below σ). If a multiple eigenvalue straddles position `k`, the returned
/// vectors span part of its eigenspace. Small problems (`n ≤ options.dense_threshold` or
/// `3k ≥ n`) are solved densely.
///
/// Errors: [`SolverError::NotSquare`], [`SolverError::DimensionMismatch`],
/// [`SolverError::NonFinite`], [`SolverError::MassNotPositive`],
/// [`SolverError::TooManyEigenpairs`] (`k > n`), [`SolverError::NoConvergence`].
pub fn lowest_eigenpairs(
    a: &sprs::CsMat<f64>,
    mass_diagonal: &[f64],
    k: usize,
    options: &EigenOptions<'_>,
) -> Result<Eigenpairs, SolverError> {
    let pencil = Pencil::new(a, mass_diagonal)?;
    let request = EigenRequest {
        pencil: &pencil,
        count: k,
        top: None,
        seed: options.seed,
    };
    let mut solution = lowest_eigenpairs_of(&[request], options).map_err(|e| e.source)?;
    let mut pairs = solution
        .pairs
        .pop()
        .ok_or_else(|| SolverError::NoConvergence {
            reason: "the driver returned no result".into(),
        })?;
    // With one request the call's statistics (phase times included) are the pencil's.
    pairs.statistics = solution.statistics;
    Ok(pairs)
}
