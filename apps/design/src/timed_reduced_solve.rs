//! Reduced solves in the eigenbasis with the wall-clock time of each step (what `tvf spline` and
//! `tvf design --reduced` report): the system set up and factored with the constraints, solved
//! for the `d` reduced coefficients, and the coefficients mapped to the full field.

use crate::{
    CompiledConstraint, DesignError, ReducedBasis, ReducedSoftDesign, SoftOptions, SplineSession,
};
use serde::Serialize;
use std::time::Instant;

/// A field solved in a reduced basis, with the times of its steps. Serialized (the JSON report
/// of `tvf spline`) as `rows`, `setup_ms`, `solve_ms` and `map_ms`; see also
/// [`crate::design_report`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TimedReducedSolve {
    /// The full field (`n1` coefficients).
    #[serde(skip)]
    pub field: Vec<f64>,
    /// Active constraint rows of the system.
    pub rows: usize,
    /// Milliseconds to set the system up with the constraints (and factor it).
    pub setup_ms: f64,
    /// Milliseconds of the reduced solve.
    pub solve_ms: f64,
    /// Milliseconds mapping the reduced coefficients to the full field.
    pub map_ms: f64,
}

/// The vector spline through `constraints` in `basis` with smoothness weight `omega`
/// ([`SplineSession`]).
pub fn timed_spline(
    basis: &ReducedBasis,
    omega: f64,
    constraints: &[CompiledConstraint],
) -> Result<TimedReducedSolve, DesignError> {
    let start = Instant::now();
    let mut session = SplineSession::new(basis, omega)?;
    for c in constraints.iter().cloned() {
        session.add(c)?;
    }
    let setup_ms = milliseconds(start);
    let start = Instant::now();
    let v = session.solve();
    finish(
        basis,
        &v,
        session.row_count(),
        setup_ms,
        milliseconds(start),
    )
}

/// The soft design with `constraints` in `basis` ([`ReducedSoftDesign`]); `rows` counts the
/// constraints' value rows.
pub fn timed_reduced_design(
    basis: &ReducedBasis,
    options: SoftOptions,
    constraints: &[CompiledConstraint],
) -> Result<TimedReducedSolve, DesignError> {
    let start = Instant::now();
    let mut design = ReducedSoftDesign::new(basis, options)?;
    design.add_all(constraints.iter().cloned())?;
    let setup_ms = milliseconds(start);
    let start = Instant::now();
    let v = design.solve();
    let rows = constraints.iter().map(|c| c.values.len()).sum();
    finish(basis, &v, rows, setup_ms, milliseconds(start))
}

/// Maps the reduced coefficients `v` to the full field and collects the times.
fn finish(
    basis: &ReducedBasis,
    v: &[f64],
    rows: usize,
    setup_ms: f64,
    solve_ms: f64,
) -> Result<TimedReducedSolve, DesignError> {
    let start = Instant::now();
    let mut field = vec![0.0; basis.field_dimension()];
    basis.map(v, &mut field)?;
    Ok(TimedReducedSolve {
        field,
        rows,
        setup_ms,
        solve_ms,
        map_ms: milliseconds(start),
    })
}

/// Milliseconds since `start`.
fn milliseconds(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}
