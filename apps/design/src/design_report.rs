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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn residuals_are_listed_with_the_worst_one() {
        let r = |id: &str, relative| ConstraintResidual {
            id: id.into(),
            absolute: 2.0 * relative,
            relative,
        };
        let report = ResidualReport::new(vec![r("east", 1e-3), r("source", 2e-2)]);
        assert_eq!(report.worst_relative_residual, 2e-2);
        let lines = report.lines();
        assert_eq!(lines.len(), 4);
        assert_eq!(lines[1], "  east             2.000e-3  1.000e-3");
        assert_eq!(lines[3], "worst relative residual 2.000e-2");
        let keys = serde_json::to_value(&report).unwrap();
        assert_eq!(keys["residuals"][1]["id"], "source");
        assert_eq!(keys["residuals"][1]["absolute"], 4e-2);
        assert_eq!(ResidualReport::new(Vec::new()).worst_relative_residual, 0.0);
    }

    #[test]
    fn reduced_solves_report_their_steps() {
        let solved = TimedReducedSolve {
            field: vec![1.0],
            rows: 3,
            setup_ms: 1.0,
            solve_ms: 2.0,
            map_ms: 0.5,
        };
        assert_eq!(
            solved.spline_lines(2, 10)[0],
            "spline setup    1.000 ms (2 constraints, 3 rows, d = 10)"
        );
        let keys = serde_json::to_value(&solved).unwrap();
        assert_eq!(
            keys,
            serde_json::json!({"rows": 3, "setup_ms": 1.0, "solve_ms": 2.0, "map_ms": 0.5})
        );
        assert_eq!(
            solved.reduced_design_lines(10)[1],
            "reduced solve   2.000 ms + 0.500 ms mapping to the full field"
        );
        let keys = serde_json::to_value(solved.reduced_design_times()).unwrap();
        assert_eq!(keys["solver"], "reduced");
        assert_eq!(keys["factor_ms"], 1.0);
    }
}
