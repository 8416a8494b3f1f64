//! The full soft design (`tvf design --full`) solved with the wall-clock time of each step and
//! its report: the Dirichlet energy `S` assembled, the augmented system factored
//! ([`FullSoftDesign`]), the field solved with iterative refinement; the report lines and JSON
//! keys of [`TimedFullDesign`] say what was done and how accurate the solve is.

use crate::regularization::default_regularization;
use crate::soft_full::FullSoftDesign;
use crate::soft_options::SoftOptions;
use crate::{CompiledConstraint, DesignError};
use serde::Serialize;
use std::time::Instant;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_solvers::{FactorParallelism, FillOrdering, SolveReport};

/// The relative system residual a full solve must reach (or come within a factor 10 of the
/// rounding floor of its `f64` field, see [`SolveReport::meets`]).
pub const FULL_SOLVE_TARGET: f64 = 1e-8;

/// A field solved by the full soft design, with the times and sizes of its steps. Serialized
/// (the JSON report of `tvf design --full`) as `solver` (`"full"`), `assembly_ms`, `factor_ms`,
/// `solve_ms`, `ordering`, `factor_entries`, `factor_gflop`, `system_residuals` and
/// `rounding_floor`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TimedFullDesign {
    /// The field (`n1` coefficients).
    #[serde(skip)]
    pub field: Vec<f64>,
    /// Always `"full"` (the JSON report's `solver`).
    pub solver: &'static str,
    /// Milliseconds assembling `S` (and the regularization) from the complex.
    pub assembly_ms: f64,
    /// Milliseconds building and factoring the augmented system.
    pub factor_ms: f64,
    /// Milliseconds of the refined solve.
    pub solve_ms: f64,
    /// The fill-reducing ordering's name (`amd`, `nd`).
    pub ordering: &'static str,
    /// Stored entries of the sparse factor.
    pub factor_entries: usize,
    /// Floating-point operations of the numeric factorization, in 10⁹.
    pub factor_gflop: f64,
    /// The relative residual `‖b − Ax‖/‖b‖` after the direct solve and each refinement step.
    pub system_residuals: Vec<f64>,
    /// The residual that rounding the field to `f64` alone causes ([`SolveReport`]).
    pub rounding_floor: f64,
    /// Milliseconds of the factorization's system assembly ([`crate::FactorTimings`]).
    #[serde(skip)]
    pub system_assembly_ms: f64,
    /// Milliseconds of its ordering, symbolic and numeric factorization.
    #[serde(skip)]
    pub factorization_ms: f64,
}

/// Solves the full soft design of `complex` with smoothness weight `omega` (and the
/// [`default_regularization`]) for `constraints`, timing each step.
pub fn timed_full_design<H: HodgeComplex + ?Sized>(
    complex: &H,
    omega: f64,
    constraints: Vec<CompiledConstraint>,
    ordering: FillOrdering,
    parallelism: FactorParallelism,
) -> Result<TimedFullDesign, DesignError> {
    let start = Instant::now();
    complex.dirichlet_energy();
    let options = SoftOptions {
        omega,
        regularization: default_regularization(complex),
    };
    let assembly_ms = milliseconds(start);
    let start = Instant::now();
    let design = FullSoftDesign::of_complex(complex, options, constraints, ordering, parallelism)?;
    let factor_ms = milliseconds(start);
    let start = Instant::now();
    let (field, report) = design.solve();
    let solve_ms = milliseconds(start);
    let timings = design.timings();
    Ok(TimedFullDesign {
        field,
        solver: "full",
        assembly_ms,
        factor_ms,
        solve_ms,
        ordering: ordering.name(),
        factor_entries: design.factor_entries(),
        factor_gflop: design.factor_flop_count() / 1e9,
        system_residuals: report.residuals,
        rounding_floor: report.rounding_floor,
        system_assembly_ms: timings.assembly.as_secs_f64() * 1e3,
        factorization_ms: timings.factorization.as_secs_f64() * 1e3,
    })
}

impl TimedFullDesign {
    /// The report's lines: assembly, factorization, solve and the residual history.
    pub fn lines(&self) -> Vec<String> {
        let history: Vec<String> = self
            .system_residuals
            .iter()
            .map(|r| format!("{r:.1e}"))
            .collect();
        vec![
            format!("assembly        {:.3} ms (S)", self.assembly_ms),
            format!(
                "full factor     {:.3} ms (n1 = {}, augmented LDLᵀ, {} ordering, {} factor \
                 entries, {:.1} Gflop; system assembly {:.3} ms, ordering + symbolic + numeric \
                 {:.3} ms)",
                self.factor_ms,
                self.field.len(),
                self.ordering,
                self.factor_entries,
                self.factor_gflop,
                self.system_assembly_ms,
                self.factorization_ms,
            ),
            format!(
                "full solve      {:.3} ms ({} refinement steps)",
                self.solve_ms,
                self.system_residuals.len().saturating_sub(1)
            ),
            format!(
                "system residual ‖b − Ax‖/‖b‖: {} (rounding floor of an f64 field: {:.1e})",
                history.join(" → "),
                self.rounding_floor
            ),
        ]
    }

    /// The refinement's outcome as a [`SolveReport`].
    pub fn solve_report(&self) -> SolveReport {
        SolveReport {
            residuals: self.system_residuals.clone(),
            rounding_floor: self.rounding_floor,
        }
    }

    /// Whether the solve reached [`FULL_SOLVE_TARGET`] (or the rounding floor), and if it did
    /// only through the floor, a note saying why no `f64` field can do much better: `Ok(None)`
    /// for an accurate solve, `Ok(Some(note))` for one at the floor, `Err` for one above it.
    pub fn accuracy_note(&self) -> Result<Option<String>, SolveReport> {
        let report = self.solve_report();
        if !report.meets(FULL_SOLVE_TARGET) {
            return Err(report);
        }
        Ok((report.final_residual() > FULL_SOLVE_TARGET).then(|| {
            format!(
                "note: the residual {:.1e} is above 1e-8, but no f64 field can do much better: \
                 changing this field's entries in their last bit alone moves the residual by \
                 {:.1e} (the system is badly scaled, e.g. by slivers)",
                report.final_residual(),
                report.rounding_floor
            )
        }))
    }
}

/// Parses an ordering name (`amd`, `nd`, `nested-dissection` or `metis`); the error says which
/// names there are.
pub fn parse_fill_ordering(name: &str) -> Result<FillOrdering, String> {
    FillOrdering::from_name(name)
        .ok_or_else(|| format!("unknown ordering '{name}' (use amd or nd)"))
}

/// Milliseconds since `start`.
fn milliseconds(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}
