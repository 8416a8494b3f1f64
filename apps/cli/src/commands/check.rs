//! `tvf check`: the conformance suite's core checks and a catalog entry's measured reference
//! checks on one mesh, or property-based on generated meshes with the minimal failing mesh
//! written as OBJ (the logic: `tvf_conformance::property_runner`).

use crate::context::RunContext;
use crate::discretization_flags::DiscretizationFlags;
use crate::mesh_input::MeshInput;
use crate::progress::Progress;
use crate::report::Report;
use anyhow::{bail, Context, Result};
use clap::builder::PossibleValuesParser;
use clap::Args;
use serde_json::json;
use std::path::PathBuf;
use tvf_conformance::check_outcome::CheckOutcome;
use tvf_conformance::check_report::CheckReport;
use tvf_conformance::property_runner::{
    check_mesh, run_property, PropertyProgress, PropertyReport, PropertyRequest,
};
use tvf_conformance::reference_report::catalog_reference_checks;
use tvf_conformance::strategies::MeshNeeds;
use tvf_core::discretization::HodgeComplex;
use tvf_core::generate::EXAMPLE_NAMES;
use tvf_core::io::write_obj;
use tvf_core::SurfaceMesh;

/// Arguments of `tvf check`.
#[derive(Args)]
#[command(after_help = "Examples:\n  \
    tvf check bunny.obj --discretization dec-circumcentric\n  \
    tvf check --example genus2 --complex mine/\n  \
    tvf check --discretization conforming-voronoi --cases 64 --seed 1\n  \
    tvf check --discretization whitney-galerkin --cases 16 -o minimal.obj --json")]
pub struct CheckArgs {
    /// Mesh file (.obj, .off or .ply) to check the discretization on; omit to check it on
    /// --cases generated meshes instead.
    #[arg(value_name = "MESH")]
    mesh: Option<PathBuf>,
    /// A built-in example mesh instead of a MESH file.
    #[arg(
        long,
        value_name = "NAME",
        conflicts_with = "mesh",
        value_parser = PossibleValuesParser::new(EXAMPLE_NAMES)
    )]
    example: Option<String>,
    #[command(flatten)]
    discretization: DiscretizationFlags,
    /// Without MESH: number of generated meshes (closed of genus 0–5 and with boundary, several
    /// components, jittered, slivers, moved; Delaunay ones for entries that need them).
    #[arg(long, value_name = "N", default_value_t = 64)]
    cases: u32,
    /// Without MESH: seed of the generated meshes (the same seed draws the same meshes).
    #[arg(long, value_name = "S", default_value_t = 0)]
    seed: u64,
    /// Without MESH: where the minimal failing mesh is written (OBJ) when a case fails.
    #[arg(
        short = 'o',
        long = "output",
        value_name = "OBJ",
        default_value = "counterexample.obj"
    )]
    output: PathBuf,
    /// Print the report as one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// Runs the checks; exits with an error naming the failed checks if any fails. JSON keys:
/// `discretization`, `passed`, `checks` (one object per check: `name`, `status`, `measured`,
/// `limit`, `detail`), `failed` (names); for generated meshes also `cases`, `seed`,
/// `cases_passed` (`checks` then holds each check's worst case) and, on a failure,
/// `counterexample` (`path`, `faces`, `description`, `reproduce`, `checks`).
pub fn run(args: CheckArgs, context: &RunContext) -> Result<()> {
    let catalog = context.catalog();
    let id = match &args.discretization.complex {
        Some(dir) => format!("the matrices of {}", dir.display()),
        None => args.discretization.id(),
    };
    let reference = catalog_reference_checks(&id);
    let mut report = Report::new(args.json);
    report.set("discretization", &id);
    let input = match (&args.mesh, &args.example) {
        (Some(path), _) => Some(MeshInput::file(path.clone())),
        (None, Some(name)) => Some(MeshInput::example(name)),
        (None, None) => None,
    };
    match &input {
        Some(input) => {
            let mesh = input.load()?.mesh;
            let builder = |mesh: &SurfaceMesh| -> Result<Box<dyn HodgeComplex>, String> {
                let flags = &args.discretization;
                flags
                    .build(catalog, mesh, input)
                    .map_err(|e| format!("{e:#}"))
            };
            let checked = check_mesh(&builder, &mesh, reference);
            report.line(format!(
                "{id} on {} ({} faces): {}",
                input.label(),
                mesh.face_count(),
                verdict(checked.passed())
            ));
            print_outcomes(&report, &checked.outcomes);
            report.set("passed", checked.passed());
            report.set("checks", &checked.outcomes);
            finish(report, &checked)
        }
        None => {
            if let Some(dir) = &args.discretization.complex {
                bail!(
                    "--complex {}: a folder holds the matrices of one mesh; give that MESH \
                     (generated meshes need a catalog entry)",
                    dir.display()
                );
            }
            let entry = catalog.get(&id)?;
            let boundary = args.discretization.boundary_condition();
            let builder = |mesh: &SurfaceMesh| -> Result<Box<dyn HodgeComplex>, String> {
                catalog
                    .build_complex(&id, Some(boundary), mesh)
                    .map_err(|e| e.to_string())
            };
            let mut request = PropertyRequest::new(args.cases, args.seed, MeshNeeds::default());
            request.needs.delaunay = entry.needs_delaunay();
            request.reference = reference.to_vec();
            let progress = Progress::new("check");
            let on_progress = |event: PropertyProgress| match event {
                PropertyProgress::CasePassed { index } => {
                    progress.update("generated meshes", index as usize, args.cases as usize)
                }
                PropertyProgress::Shrinking { steps } => {
                    progress.update("shrinking the failing mesh", steps as usize, 512)
                }
            };
            let outcome = run_property(&builder, &request, &on_progress);
            progress.finish(format!(
                "{} of {} meshes passed",
                outcome.cases_passed, args.cases
            ));
            property_report(&args, &id, &mut report, &outcome)?;
            match outcome.counterexample {
                Some(counterexample) => finish(report, &counterexample.report),
                None => report.finish(),
            }
        }
    }
}

/// Reports a property run (and writes the counterexample).
fn property_report(
    args: &CheckArgs,
    id: &str,
    report: &mut Report,
    outcome: &PropertyReport,
) -> Result<()> {
    report.set("cases", args.cases);
    report.set("seed", args.seed);
    report.set("cases_passed", outcome.cases_passed);
    report.set("passed", outcome.passed());
    report.line(format!(
        "{id} on {} generated meshes (seed {}): {}",
        args.cases,
        args.seed,
        verdict(outcome.passed())
    ));
    if let Some(reason) = &outcome.aborted {
        bail!("the property run stopped: {reason}");
    }
    report.line(format!(
        "worst case of each check over the {} passing meshes:",
        outcome.cases_passed
    ));
    print_outcomes(report, &outcome.worst);
    report.set("checks", &outcome.worst);
    let Some(counterexample) = &outcome.counterexample else {
        return Ok(());
    };
    let mesh = &counterexample.mesh.mesh;
    write_obj(&args.output, mesh).with_context(|| args.output.display().to_string())?;
    let reproduce = format!("tvf check {} --discretization {id}", args.output.display());
    report.line(format!(
        "minimal failing mesh ({} faces): {}\n  written to {}; reproduce with: {reproduce}",
        mesh.face_count(),
        counterexample.mesh.name,
        args.output.display()
    ));
    print_outcomes(report, &counterexample.report.outcomes);
    report.set(
        "counterexample",
        json!({
            "path": args.output.display().to_string(),
            "faces": mesh.face_count(),
            "description": counterexample.mesh.name,
            "reproduce": reproduce,
            "checks": counterexample.report.outcomes,
        }),
    );
    Ok(())
}

/// Prints the JSON report, then fails naming the failed checks, if any.
fn finish(mut report: Report, checked: &CheckReport) -> Result<()> {
    let failed: Vec<String> = checked.failures().iter().map(|o| o.name.clone()).collect();
    report.set("failed", &failed);
    report.finish()?;
    if !failed.is_empty() {
        bail!("failed checks: {}", failed.join(", "));
    }
    Ok(())
}

fn verdict(passed: bool) -> &'static str {
    if passed {
        "passed"
    } else {
        "FAILED"
    }
}

/// One aligned line per check: status, name, measured value against its limit, detail.
fn print_outcomes(report: &Report, outcomes: &[CheckOutcome]) {
    for o in outcomes {
        report.line(format!(
            "  {:<7} {:<48} {:>11} ≤ {:<11} {}",
            o.status.name(),
            o.name,
            number(o.measured),
            number(o.limit),
            o.detail
        ));
    }
}

fn number(x: f64) -> String {
    if x.is_nan() {
        "-".to_string()
    } else {
        format!("{x:.3e}")
    }
}
