//! `tvf design`: soft-constrained vector field design (Fisher et al. 2007, Section 8.4), full
//! (sparse Cholesky) or reduced (dense Cholesky in the eigenbasis).

use super::spline::{
    compile, discretization, load_inputs, reduced_basis, report_residuals, solution_residuals,
    DesignInputs,
};
use crate::basis_source::BasisSource;
use crate::context::RunContext;
use crate::mesh_input::MeshInput;
use crate::output_rules::check_output;
use crate::report::Report;
use anyhow::{bail, Context, Result};
use clap::Args;
use std::path::PathBuf;
use std::time::Instant;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_design::{
    default_regularization, timed_reduced_design, FactorParallelism, FillOrdering, FullSoftDesign,
    SoftOptions, DEFAULT_FULL_ORDERING, SEQUENTIAL_FLOP_LIMIT,
};
use tvf_discretizations::Catalog;
use tvf_spectral::write_tangent_field;

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
    #[arg(long, value_name = "amd|nd", conflicts_with = "reduced", value_parser = parse_ordering)]
    ordering: Option<FillOrdering>,
    /// Solve the reduced system `(Λ + ωΛ² + CᵀWC) v = CᵀWc` in the eigenbasis.
    #[arg(long)]
    reduced: bool,
    #[command(flatten)]
    basis: BasisSource,
    /// Output field: one 3D vector per face (.npy F×3, or text by extension).
    #[arg(short, long, value_name = "FIELD")]
    output: PathBuf,
    /// Print the report (sizes, times in ms, residuals) as one JSON object on stdout.
    #[arg(long)]
    json: bool,
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
    let mut report = Report::new(args.json);
    let basis_file = args.basis.options.basis.as_deref();
    let inputs = [Some(args.constraints.as_path()), basis_file];
    check_output(&args.output, &args.input, &inputs)?;
    let inputs = load_inputs(&args.input, &args.constraints, &mut report)?;
    let catalog = context.catalog();
    let complex = discretization(catalog, &inputs, &args.input, &args.basis)?;
    design_with(catalog, complex.as_ref(), &inputs, &args, &mut report)?;
    report.finish()
}

fn design_with<H: HodgeComplex + ?Sized>(
    catalog: &Catalog,
    complex: &H,
    inputs: &DesignInputs,
    args: &DesignArgs,
    out: &mut Report,
) -> Result<()> {
    let constraints = compile(complex, inputs)?;
    let start = Instant::now();
    complex.dirichlet_energy();
    let options = SoftOptions {
        omega: inputs.set.omega,
        regularization: default_regularization(complex),
    };
    let field = if args.full {
        let assembly = start.elapsed();
        let start = Instant::now();
        let ordering = args.ordering.unwrap_or(DEFAULT_FULL_ORDERING);
        let design = FullSoftDesign::of_complex(
            complex,
            options,
            constraints.clone(),
            ordering,
            factor_parallelism()?,
        )
        .with_context(|| {
            format!(
                "{}: the full soft-design system (omega {:e}) cannot be factored",
                inputs.constraints_path.display(),
                inputs.set.omega
            )
        })?;
        let factor = start.elapsed();
        let timings = design.timings();
        let start = Instant::now();
        let (field, report) = design.solve();
        let solve = start.elapsed();
        let (assembly_ms, factor_ms, solve_ms) = (
            assembly.as_secs_f64() * 1e3,
            factor.as_secs_f64() * 1e3,
            solve.as_secs_f64() * 1e3,
        );
        out.line(format!("assembly        {assembly_ms:.3} ms (S)"));
        out.line(format!(
            "full factor     {factor_ms:.3} ms (n1 = {}, augmented LDLᵀ, {} ordering, {} factor entries, \
             {:.1} Gflop; system assembly {:.3} ms, ordering + symbolic + numeric {:.3} ms)",
            field.len(),
            ordering.name(),
            design.factor_entries(),
            design.factor_flop_count() / 1e9,
            timings.assembly.as_secs_f64() * 1e3,
            timings.factorization.as_secs_f64() * 1e3,
        ));
        out.line(format!(
            "full solve      {solve_ms:.3} ms ({} refinement steps)",
            report.residuals.len() - 1
        ));
        let history: Vec<String> = report
            .residuals
            .iter()
            .map(|r| format!("{r:.1e}"))
            .collect();
        out.line(format!(
            "system residual ‖b − Ax‖/‖b‖: {} (rounding floor of an f64 field: {:.1e})",
            history.join(" → "),
            report.rounding_floor
        ));
        out.set("solver", "full");
        out.set("assembly_ms", assembly_ms);
        out.set("factor_ms", factor_ms);
        out.set("solve_ms", solve_ms);
        out.set("ordering", ordering.name());
        out.set("factor_entries", design.factor_entries());
        out.set("factor_gflop", design.factor_flop_count() / 1e9);
        out.set("system_residuals", &report.residuals);
        out.set("rounding_floor", report.rounding_floor);
        solution_residuals(&field, &constraints, inputs)?;
        if !report.meets(1e-8) {
            bail!(
                "{}: the full solve reached only a relative residual of {:.1e} (the rounding floor of an \
                 f64 field is {:.1e})",
                inputs.constraints_path.display(),
                report.final_residual(),
                report.rounding_floor
            );
        }
        if report.final_residual() > 1e-8 {
            out.line(format!(
                "note: the residual {:.1e} is above 1e-8, but no f64 field can do much better: \
                 changing this field's entries in their last bit alone moves the residual by {:.1e} \
                 (the system is badly scaled, e.g. by slivers)",
                report.final_residual(),
                report.rounding_floor
            ));
        }
        field
    } else {
        let basis = reduced_basis(catalog, inputs, &args.input, &args.basis, out)?;
        let solved = timed_reduced_design(&basis, options, &constraints)
            .with_context(|| format!("{}", inputs.constraints_path.display()))?;
        let (factor_ms, solve_ms, map_ms) = (solved.setup_ms, solved.solve_ms, solved.map_ms);
        out.line(format!(
            "reduced factor  {factor_ms:.3} ms (d = {})",
            basis.len()
        ));
        out.line(format!(
            "reduced solve   {solve_ms:.3} ms + {map_ms:.3} ms mapping to the full field"
        ));
        out.set("solver", "reduced");
        out.set("factor_ms", factor_ms);
        out.set("solve_ms", solve_ms);
        out.set("map_ms", map_ms);
        solved.field
    };
    report_residuals(&solution_residuals(&field, &constraints, inputs)?, out);
    write_tangent_field(&args.output, complex.require_sampling()?, &field)?;
    out.line(format!("wrote {}", args.output.display()));
    out.set("output", args.output.display().to_string());
    Ok(())
}

/// Parses `--ordering` (`amd`, `nd`, `nested-dissection` or `metis`).
fn parse_ordering(name: &str) -> Result<FillOrdering, String> {
    FillOrdering::from_name(name)
        .ok_or_else(|| format!("unknown ordering '{name}' (use amd or nd)"))
}
