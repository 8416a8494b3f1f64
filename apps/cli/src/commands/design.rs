//! `tvf design`: soft-constrained vector field design (Fisher et al. 2007, Section 8.4), full
//! (sparse Cholesky) or reduced (dense Cholesky in the eigenbasis). The problem, the solves and
//! their reports are `tvf_design::DesignProblem`'s.

use super::spline::DesignOutputArgs;
use crate::context::RunContext;
use crate::mesh_input::MeshInput;
use crate::report::Report;
use anyhow::{bail, Result};
use clap::Args;
use std::path::PathBuf;
use tvf_design::{
    parse_fill_ordering, FactorParallelism, FillOrdering, DEFAULT_FULL_ORDERING,
    SEQUENTIAL_FLOP_LIMIT,
};

/// Arguments of `tvf design`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf design bunny.obj --constraints constraints.json --full -o design.npy\n  \
tvf design bunny.obj --constraints constraints.json --reduced -k 1000 -o design.npy\n\n\
--reduced works in the basis of the K lowest eigenfields (-k K, the paper's d; computed once and cached) or \
of a --basis file. --full needs no basis (-k is refused); --decomposition, --mass or a --basis file choose \
its discretization."
)]
pub struct DesignArgs {
    #[command(flatten)]
    input: MeshInput,
    /// The constraint file (JSON, see README "Constraint files"); `weight` scales each constraint.
    #[arg(long, value_name = "C.json")]
    constraints: PathBuf,
    /// Solve the full system `(S + ωB + C̃ᵀWC̃) x = C̃ᵀWc` (sparse LDLᵀ of an augmented system).
    #[arg(
        long,
        conflicts_with_all = ["reduced", "fields"],
        required_unless_present = "reduced"
    )]
    full: bool,
    /// Fill-reducing ordering of the full system's sparse factorization: `nd` (nested dissection,
    /// METIS; the default, fewer flops on every mesh measured) or `amd`.
    #[arg(
        long,
        value_name = "amd|nd",
        conflicts_with = "reduced",
        value_parser = parse_fill_ordering
    )]
    ordering: Option<FillOrdering>,
    /// Solve the reduced system `(Λ + ωΛ² + CᵀWC) v = CᵀWc` in the eigenbasis.
    #[arg(long)]
    reduced: bool,
    #[command(flatten)]
    design: DesignOutputArgs,
}

/// Environment variable overriding [`SEQUENTIAL_FLOP_LIMIT`] for the full design's factorization
/// (a number of flops, e.g. `1e11`).
const SEQUENTIAL_FLOP_LIMIT_VARIABLE: &str = "TVF_SEQUENTIAL_FLOP_LIMIT";

/// The full design's threading: one thread below [`SEQUENTIAL_FLOP_LIMIT`] flops, or below the
/// value of [`SEQUENTIAL_FLOP_LIMIT_VARIABLE`] when it is set. A value that is not a
/// non-negative number is an error (a typo would otherwise silently change the threading).
fn factor_parallelism() -> Result<FactorParallelism> {
    let sequential_flop_limit = match std::env::var_os(SEQUENTIAL_FLOP_LIMIT_VARIABLE) {
        None => SEQUENTIAL_FLOP_LIMIT,
        Some(raw) => {
            let value = raw.to_string_lossy().into_owned();
            match value.trim().parse::<f64>() {
                Ok(limit) if limit >= 0.0 => limit,
                _ => bail!(
                    "environment variable {SEQUENTIAL_FLOP_LIMIT_VARIABLE} = '{value}': a \
                     non-negative number of flops, e.g. 1e11"
                ),
            }
        }
    };
    Ok(FactorParallelism::Auto {
        sequential_flop_limit,
    })
}

/// Runs `tvf design`.
pub fn run(args: DesignArgs, context: &RunContext) -> Result<()> {
    let mut report = Report::new(args.design.json);
    let catalog = context.catalog();
    let (problem, complex, constraints) =
        args.design
            .load(catalog, &args.input, &args.constraints, &mut report)?;
    let (field, residuals) = if args.full {
        let ordering = args.ordering.unwrap_or(DEFAULT_FULL_ORDERING);
        let parallelism = factor_parallelism()?;
        let solved =
            problem.full_design(complex.as_ref(), constraints.clone(), ordering, parallelism)?;
        report.add(solved.lines(), &solved);
        let residuals = problem.residuals(&solved.field, &constraints)?;
        if let Some(note) = problem.accuracy_note(&solved)? {
            report.line(note);
        }
        (solved.field, residuals)
    } else {
        let basis =
            args.design
                .reduced_basis(catalog, &problem, &args.input, &constraints, &mut report)?;
        let solved = problem.reduced_design(complex.as_ref(), &basis, &constraints)?;
        report.add(
            solved.reduced_design_lines(basis.len()),
            solved.reduced_design_times(),
        );
        let residuals = problem.residuals(&solved.field, &constraints)?;
        (solved.field, residuals)
    };
    args.design
        .finish(complex.as_ref(), &field, &residuals, report)
}
