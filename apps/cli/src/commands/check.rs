//! `tvf check`: the conformance suite's core checks and a catalog entry's measured reference
//! checks on one mesh (on a polygon mesh: the core checks and the sampling and point evaluation
//! checks on polygons), or property-based on generated triangle or polygon meshes with the
//! minimal failing mesh written as OBJ (polygons kept as polygons; the logic:
//! `tvf_conformance::property_runner`; the report: `tvf_conformance::check_run_report`); in both
//! cases the accuracy checks (`tvf_conformance::accuracy`: consistency on patches, convergence on
//! the sphere and hemisphere) unless `--no-accuracy`.

use crate::context::RunContext;
use crate::discretization_flags::DiscretizationFlags;
use crate::mesh_input::OptionalMeshInput;
use crate::progress::Progress;
use crate::report::Report;
use anyhow::{bail, Context, Result};
use clap::builder::PossibleValuesParser;
use clap::Args;
use std::path::PathBuf;
use tvf_conformance::accuracy::{
    accuracy_report, consistency_on_mesh, convergence_not_applicable, AccuracyRequest,
};
use tvf_conformance::check_outcome::CheckOutcome;
use tvf_conformance::check_run_report::{
    entry_property_request, MeshCheckReport, PropertyRunReport,
};
use tvf_conformance::property_runner::{
    check_mesh, check_polygon_mesh, run_polygon_property, run_property, PropertyProgress,
};
use tvf_conformance::reference_report::catalog_reference_checks;
use tvf_core::discretization::HodgeComplex;
use tvf_core::io::write_obj;
use tvf_core::{SurfaceMesh, TriangleMesh};
use tvf_discretizations::{Catalog, CatalogEntry, DEFAULT_DISCRETIZATION};

/// `MESH`'s help text for `tvf check`.
const MESH_HELP: &str = "Mesh file (.obj, .off or .ply) to check the discretization on; omit to \
    check it on --cases generated meshes instead";

/// Arguments of `tvf check`.
#[derive(Args)]
#[command(after_help = "Examples:\n  \
    tvf check bunny.obj --discretization dec-circumcentric\n  \
    tvf check --example genus2 --complex mine/\n  \
    tvf check --discretization conforming-voronoi --cases 64 --seed 1\n  \
    tvf check --discretization whitney-galerkin --cases 16 -o minimal.obj --json\n  \
    tvf check quads.obj --discretization polygon-dec\n  \
    tvf check --discretization polygon-dec --meshes polygons --cases 32",
    mut_arg("mesh", |arg| arg.help(MESH_HELP))
)]
pub struct CheckArgs {
    #[command(flatten)]
    mesh: OptionalMeshInput,
    #[command(flatten)]
    discretization: DiscretizationFlags,
    /// Without MESH: number of generated meshes (closed of genus 0–5 and with boundary, several
    /// components, jittered, slivers, moved; Delaunay ones for entries that need them).
    #[arg(long, value_name = "N", default_value_t = 64)]
    cases: u32,
    /// Without MESH: seed of the generated meshes (the same seed draws the same meshes).
    #[arg(long, value_name = "S", default_value_t = 0)]
    seed: u64,
    /// Without MESH: generate `triangles` or `polygons` (quad tori and genus-g quad surfaces,
    /// cube-spheres, duals of triangle meshes, jittered non-planar polygons, holes, several
    /// components; shrinking keeps them polygon meshes) [default: polygons for an entry that
    /// accepts them, such as polygon-dec, else triangles].
    #[arg(long, value_name = "KIND", value_parser = PossibleValuesParser::new(["triangles", "polygons"]))]
    meshes: Option<String>,
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
    /// Skip the accuracy checks (consistency of linear functions on flat and curved patches,
    /// convergence of the lowest eigenvalues on regular and jittered refinements of the sphere
    /// and hemisphere, observed order ≥ 1.5), which run by default.
    #[arg(long)]
    no_accuracy: bool,
}

/// Runs the checks; exits with an error naming the failed checks if any fails. JSON keys:
/// `discretization`, `passed`, `checks` (one object per check: `name`, `status`, `measured`,
/// `limit`, `detail`), `failed` (names); for generated meshes also `cases`, `seed`,
/// `cases_passed` (`checks` then holds each check's worst case) and, on a failure,
/// `counterexample` (`path`, `faces`, `description`, `reproduce`, `checks`, `reproduced`: false for
/// a failure that did not come back when the mesh was checked again).
pub fn run(args: CheckArgs, context: &RunContext) -> Result<()> {
    let catalog = context.catalog();
    let mut report = Report::new(args.json);
    let input = match args.mesh.input() {
        Some(input) => input,
        None => {
            let id = args
                .discretization
                .requested_id()
                .unwrap_or_else(|| DEFAULT_DISCRETIZATION.to_string());
            return check_generated(&args, &id, catalog, report);
        }
    };
    let loaded = input.load()?.mesh;
    let id = match &args.discretization.complex {
        Some(dir) => format!("the matrices of {}", dir.display()),
        None => args.discretization.id(&loaded),
    };
    let flags = &args.discretization;
    let mut checked = match loaded.as_triangles() {
        Some(mesh) => {
            let builder = |mesh: &TriangleMesh| -> Result<Box<dyn HodgeComplex>, String> {
                flags
                    .build(catalog, &SurfaceMesh::from(mesh.clone()), &input)
                    .map_err(|e| format!("{e:#}"))
            };
            check_mesh(&builder, mesh, catalog_reference_checks(&id))
        }
        None => {
            let builder = |mesh: &SurfaceMesh| -> Result<Box<dyn HodgeComplex>, String> {
                flags
                    .build(catalog, mesh, &input)
                    .map_err(|e| format!("{e:#}"))
            };
            check_polygon_mesh(&builder, &loaded)
        }
    };
    if !args.no_accuracy {
        let complex = flags.build(catalog, &loaded, &input);
        let on_mesh = match &complex {
            Ok(complex) => consistency_on_mesh(complex.as_ref(), &loaded),
            // The core checks report the refusal.
            Err(_) => Vec::new(),
        };
        checked.outcomes.extend(on_mesh);
        checked.outcomes.extend(accuracy(&args, catalog, &id)?);
    }
    let checked = MeshCheckReport::new(&id, &input.label(), loaded.face_count(), checked);
    report.add(checked.lines(), &checked);
    finish(report, checked.failure_message())
}

/// The accuracy checks of the discretization `id` built by `catalog` with the flags' boundary
/// condition; for a `--complex` folder, the convergence checks as not applicable (a folder holds
/// the matrices of one mesh).
fn accuracy(args: &CheckArgs, catalog: &Catalog, id: &str) -> Result<Vec<CheckOutcome>> {
    if args.discretization.complex.is_some() {
        return Ok(convergence_not_applicable(
            "a folder holds the matrices of one mesh: the refinement sequences need a \
             discretization that builds on any mesh (a catalog entry)",
        ));
    }
    let entry = catalog.get(id)?;
    let boundary = args.discretization.boundary_condition();
    let build = |mesh: &SurfaceMesh| -> Result<Box<dyn HodgeComplex>, String> {
        catalog
            .build_complex(id, Some(boundary), mesh)
            .map_err(|e| e.to_string())
    };
    let progress = Progress::new("check");
    progress.update(
        "accuracy checks (patches; sphere and hemisphere refinements)",
        0,
        1,
    );
    let request = AccuracyRequest::new(!entry.needs_triangles());
    let report = accuracy_report(&build, &request);
    progress.finish(format!(
        "accuracy checks: {} of {} passed",
        report
            .outcomes
            .iter()
            .filter(|o| o.status == tvf_conformance::check_outcome::CheckStatus::Passed)
            .count(),
        report.outcomes.len()
    ));
    Ok(report.outcomes)
}

/// The name the running program was called by (`tvf`, or a program of your own that runs tvf's
/// command line with its catalog), for commands it prints to be run again.
fn program_name() -> String {
    std::env::args_os()
        .next()
        .and_then(|arg0| {
            let path = PathBuf::from(arg0);
            path.file_stem().map(|s| s.to_string_lossy().into_owned())
        })
        .unwrap_or_else(|| "tvf".to_string())
}

/// Whether the property run draws polygon meshes: `--meshes`, else polygons for an entry that
/// accepts them. Fails for polygons asked of an entry that needs triangles.
fn generates_polygons(args: &CheckArgs, entry: &CatalogEntry) -> Result<bool> {
    let polygons = match args.meshes.as_deref() {
        Some(kind) => kind == "polygons",
        None => !entry.needs_triangles(),
    };
    if polygons && entry.needs_triangles() {
        bail!(
            "--meshes polygons: the discretization '{}' needs triangle meshes \
             (polygon-dec accepts polygons)",
            entry.id()
        );
    }
    Ok(polygons)
}

/// The property run on `--cases` generated meshes (and the counterexample written as OBJ, a
/// polygon mesh with its polygons).
fn check_generated(
    args: &CheckArgs,
    id: &str,
    catalog: &Catalog,
    mut report: Report,
) -> Result<()> {
    if let Some(dir) = &args.discretization.complex {
        bail!(
            "--complex {}: a folder holds the matrices of one mesh; give that MESH \
             (generated meshes need a catalog entry)",
            dir.display()
        );
    }
    if args.cases == 0 {
        bail!("--cases 0: check at least one generated mesh");
    }
    // The counterexample is written after the run, which can take hours: its path is checked
    // first.
    tvf_core::io::check_file_output(&args.output, &[])
        .context("--output: where the minimal failing mesh would be written")?;
    let entry = catalog.get(id)?;
    let polygons = generates_polygons(args, entry)?;
    let request = entry_property_request(entry, args.cases, args.seed);
    let boundary = args.discretization.boundary_condition();
    let progress = Progress::new("check");
    let on_progress = |event: PropertyProgress| match event {
        PropertyProgress::CasePassed { index } => {
            progress.update("generated meshes", index as usize, args.cases as usize)
        }
        PropertyProgress::Shrinking { steps } => {
            progress.update("shrinking the failing mesh", steps as usize, 512)
        }
    };
    let build = |mesh: &SurfaceMesh| -> Result<Box<dyn HodgeComplex>, String> {
        catalog
            .build_complex(id, Some(boundary), mesh)
            .map_err(|e| e.to_string())
    };
    let program = program_name();
    let (run, counterexample) = if polygons {
        let outcome = run_polygon_property(&build, &request, &on_progress);
        let run = PropertyRunReport::new(&program, id, &request, &outcome, &args.output);
        (run, outcome.counterexample.map(|c| c.mesh.mesh))
    } else {
        let builder = |mesh: &TriangleMesh| build(&SurfaceMesh::from(mesh.clone()));
        let outcome = run_property(&builder, &request, &on_progress);
        let run = PropertyRunReport::new(&program, id, &request, &outcome, &args.output);
        let mesh = outcome
            .counterexample
            .map(|c| SurfaceMesh::from(c.mesh.mesh));
        (run, mesh)
    };
    progress.finish(run.cases_summary());
    let run = if args.no_accuracy || run.aborted.is_some() {
        run
    } else {
        run.with_accuracy(accuracy(args, catalog, id)?)
    };
    report.add(run.lines(), &run);
    if let Some(message) = run.abort_message() {
        bail!(message);
    }
    if let Some(mesh) = &counterexample {
        write_obj(&args.output, mesh).with_context(|| args.output.display().to_string())?;
        run.counterexample_lines()
            .iter()
            .for_each(|line| report.line(line));
    }
    finish(report, run.failure_message())
}

/// Prints the JSON report, then fails with `failure` (naming the failed checks), if any.
fn finish(report: Report, failure: Option<String>) -> Result<()> {
    report.finish()?;
    match failure {
        Some(message) => bail!(message),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reproduce command names the program that runs, not `tvf` (a program of your own
    /// with its own catalog, such as the example crate's, runs this code too).
    #[test]
    fn the_program_name_is_the_running_binary() {
        let exe = std::env::current_exe().unwrap();
        let stem = exe.file_stem().unwrap().to_string_lossy();
        assert_eq!(program_name(), stem);
    }
}
