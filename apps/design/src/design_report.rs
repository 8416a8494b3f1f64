//! What `tvf spline` and `tvf design` report about a solved field, as text lines and JSON keys:
//! the constraint residuals ([`ResidualReport`]) and the steps of a reduced solve
//! ([`TimedReducedSolve::spline_lines`], [`ReducedDesignTimes`]). Every report part derives
//! `Serialize` for its keys (a JSON object) and has `lines()` for its text.

use crate::solution_check::worst_residual;
use crate::spline::ConstraintResidual;
use crate::timed_reduced_solve::TimedReducedSolve;
use serde::Serialize;

/// The residual of every constraint and the worst relative one. Serialized as `residuals`
/// (`[{id, absolute, relative}]`) and `worst_relative_residual`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResidualReport {
    /// One residual per constraint, in the order of the constraint file.
    pub residuals: Vec<ConstraintResidual>,
    /// The largest relative residual (0 without constraints).
    pub worst_relative_residual: f64,
}

impl ResidualReport {
    /// The report of `residuals` (see [`worst_residual`]).
    pub fn new(residuals: Vec<ConstraintResidual>) -> Self {
        let worst_relative_residual = worst_residual(&residuals).map_or(0.0, |r| r.relative);
        Self {
            residuals,
            worst_relative_residual,
        }
    }

    /// A heading, one line per constraint (id, absolute, relative) and the worst relative
    /// residual.
    pub fn lines(&self) -> Vec<String> {
        let mut lines = vec!["constraint residuals (|C̃x − c|, relative):".to_string()];
        lines.extend(
            self.residuals
                .iter()
                .map(|r| format!("  {:<16} {:.3e}  {:.3e}", r.id, r.absolute, r.relative)),
        );
        lines.push(format!(
            "worst relative residual {:.3e}",
            self.worst_relative_residual
        ));
        lines
    }
}

/// The keys of a reduced soft design's times: `solver` (`"reduced"`), `factor_ms`, `solve_ms`
/// and `map_ms`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ReducedDesignTimes {
    /// Always `"reduced"`.
    pub solver: &'static str,
    /// Milliseconds setting up and factoring the reduced system.
    pub factor_ms: f64,
    /// Milliseconds of the reduced solve.
    pub solve_ms: f64,
    /// Milliseconds mapping the reduced coefficients to the full field.
    pub map_ms: f64,
}

impl TimedReducedSolve {
    /// The lines of a spline solve with `constraints` constraints in a basis of `d` fields
    /// (its keys: the serialized [`TimedReducedSolve`]).
    pub fn spline_lines(&self, constraints: usize, d: usize) -> Vec<String> {
        vec![
            format!(
                "spline setup    {:.3} ms ({constraints} constraints, {} rows, d = {d})",
                self.setup_ms, self.rows
            ),
            format!(
                "spline solve    {:.3} ms reduced + {:.3} ms mapping to the full field",
                self.solve_ms, self.map_ms
            ),
        ]
    }

    /// The times of a reduced soft design, for its JSON keys.
    pub fn reduced_design_times(&self) -> ReducedDesignTimes {
        ReducedDesignTimes {
            solver: "reduced",
            factor_ms: self.setup_ms,
            solve_ms: self.solve_ms,
            map_ms: self.map_ms,
        }
    }

    /// The lines of a reduced soft design in a basis of `d` fields.
    pub fn reduced_design_lines(&self, d: usize) -> Vec<String> {
        vec![
            format!("reduced factor  {:.3} ms (d = {d})", self.setup_ms),
            format!(
                "reduced solve   {:.3} ms + {:.3} ms mapping to the full field",
                self.solve_ms, self.map_ms
            ),
        ]
    }
}
