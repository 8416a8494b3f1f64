//! The discretization comparison: catalog entries (the built-in ones, [`crate::registry`], or
//! any others) through the convergence study of `tvf convergence`
//! ([`tvf_convergence`]) on icospheres under refinement — each family's lowest
//! eigenvalues against the unit sphere's `l(l+1)`, the orders and the time to build each basis —
//! as the study's Markdown table and log–log plot.
//!
//! The unit sphere has every `l(l+1)` (`l ≥ 1`, multiplicity `2l+1`) once in each family; the
//! first `L` degrees are `L(L+2)` eigenvalues per family.

use crate::step_log::StepLog;
use tvf_convergence::study::{
    run_convergence, Candidate, ConvergenceConfig, ConvergenceReport, Surface,
};
use tvf_discretizations::CatalogEntry;
use tvf_figures::convergence_plot::convergence_plot;
use tvf_figures::FigureError;
use tvf_render::Plot;

/// What the comparison runs.
#[derive(Debug, Clone, PartialEq)]
pub struct ComparisonConfig {
    /// Icosphere subdivision levels (`20·4^level` faces), ascending.
    pub levels: Vec<u32>,
    /// Highest spherical-harmonic degree `L` compared: `L(L+2)` eigenvalues per family.
    pub max_degree: usize,
}

impl Default for ComparisonConfig {
    fn default() -> Self {
        Self {
            levels: (1..=6).collect(),
            max_degree: 5,
        }
    }
}

impl ComparisonConfig {
    /// The convergence study it stands for: the sphere, the levels, `L(L+2)` eigenvalues.
    pub fn study(&self) -> ConvergenceConfig {
        ConvergenceConfig {
            surfaces: vec![Surface::Sphere],
            levels: self.levels.clone(),
            eigenvalues: self.max_degree * (self.max_degree + 2),
        }
    }
}

/// Runs every discretization of `entries` on every level of `config`, one progress note per
/// basis.
pub fn run(
    entries: &[CatalogEntry],
    config: &ComparisonConfig,
    progress: &StepLog,
) -> Result<ConvergenceReport, FigureError> {
    let candidates: Vec<Candidate<'_>> = entries.iter().map(Candidate::from_entry).collect();
    run_convergence(&candidates, &config.study(), &|_, _, row| {
        progress.note(format!("comparison: {}", row.summary()))
    })
    .map_err(|e| FigureError::Invalid(e.to_string()))
}

/// Log–log plot of both families' errors against `h`, one colour per discretization.
pub fn plot(report: &ConvergenceReport, width: u32, height: u32) -> Plot {
    convergence_plot(report, Surface::Sphere, width, height)
}
