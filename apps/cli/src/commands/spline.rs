//! `tvf spline`: a tangential vector field spline (hard constraints, Section 7) from a JSON
//! constraint file, in a loaded or freshly computed eigenbasis.

use crate::basis_source::BasisSource;
use crate::context::RunContext;
use crate::mesh_input::MeshInput;
use crate::output_rules::check_output;
use crate::report::Report;
use anyhow::{Context, Result};
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tvf_core::discretization::HodgeComplex;
use tvf_core::discretization::HodgeOperators;
use tvf_core::SurfaceMesh;
use tvf_design::{
    checked_residuals, timed_spline, worst_residual, CompiledConstraint, ConstraintAssembler,
    ConstraintResidual, ConstraintSet, ReducedBasis,
};
use tvf_discretizations::{BoxedComplex, Catalog};
use tvf_spectral::write_tangent_field;

/// Arguments of `tvf spline`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf spline bunny.obj --constraints constraints.json -k 1000 -o spline.npy\n  \
tvf spline bunny.obj --constraints constraints.json --basis bunny.tvfb -o spline.npy\n  \
tvf render bunny.obj spline.npy --constraints constraints.json -o spline.png   (look at it)\n\n\
The spline lives in the basis of the K lowest eigenfields (-k K, the paper's d; computed once and cached, \
K ≥ n1 (the field dimension: 2F for face fields, E for DEC/Whitney): the complete basis) or of a --basis file; constraints are met exactly in that basis."
)]
pub struct SplineArgs {
    #[command(flatten)]
    input: MeshInput,
    /// The constraint file (JSON, see README "Constraint files").
    #[arg(long, value_name = "C.json")]
    constraints: PathBuf,
    #[command(flatten)]
    basis: BasisSource,
    /// Output field: one 3D vector per face (.npy F×3, or text by extension).
    #[arg(short, long, value_name = "FIELD")]
    output: PathBuf,
    /// Print the report (sizes, times in ms, residuals) as one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// Everything a design command needs before it starts solving.
pub struct DesignInputs {
    /// The mesh.
    pub mesh: SurfaceMesh,
    /// The constraint set, fingerprint checked.
    pub set: ConstraintSet,
    /// The constraint file (for messages).
    pub constraints_path: PathBuf,
}

/// Loads the mesh and the constraint file (checking its mesh fingerprint, if any).
pub fn load_inputs(
    input: &MeshInput,
    constraints: &Path,
    report: &mut Report,
) -> Result<DesignInputs> {
    let mesh = input.load()?.mesh;
    let set = ConstraintSet::load(constraints)?;
    set.check_fingerprint(&format!("{:016x}", mesh.fingerprint()), constraints)?;
    report.line(format!(
        "mesh            {} ({} faces, genus {})",
        input.label(),
        mesh.face_count(),
        mesh.genus()
    ));
    report.line(format!(
        "constraints     {} from {} (omega {})",
        set.constraints.len(),
        constraints.display(),
        set.omega
    ));
    report.set("mesh", input.label());
    report.set("faces", mesh.face_count());
    report.set("genus", mesh.genus());
    report.set("constraints_file", constraints.display().to_string());
    report.set("omega", set.omega);
    Ok(DesignInputs {
        mesh,
        set,
        constraints_path: constraints.to_path_buf(),
    })
}

/// The discretization of `source` (the basis file's, or the flags'), without the basis: for
/// checking the constraints before an expensive basis computation.
pub fn discretization(
    catalog: &Catalog,
    inputs: &DesignInputs,
    input: &MeshInput,
    source: &BasisSource,
) -> Result<BoxedComplex> {
    source.options.discretization(catalog, &inputs.mesh, input)
}

/// The basis of `source` (loaded, cached or computed; see [`crate::basis_source`]), row-major
/// for the solvers.
pub fn reduced_basis(
    catalog: &Catalog,
    inputs: &DesignInputs,
    input: &MeshInput,
    source: &BasisSource,
    report: &mut Report,
) -> Result<ReducedBasis> {
    let start = Instant::now();
    let resolved = source.resolve(catalog, &inputs.mesh, input)?;
    let seconds = start.elapsed().as_secs_f64();
    report.line(format!(
        "basis           {} fields of {} ready in {seconds:.3} s",
        resolved.basis.len(),
        resolved.discretization.id(),
    ));
    report.set("basis_fields", resolved.basis.len());
    report.set("discretization", resolved.discretization.id());
    report.set("basis_seconds", seconds);
    Ok(ReducedBasis::from_spectral(&resolved.basis)?)
}

/// Compiles the set's constraints for `complex`; errors name the constraint file.
pub fn compile<H: HodgeComplex + ?Sized>(
    complex: &H,
    inputs: &DesignInputs,
) -> Result<Vec<CompiledConstraint>> {
    ConstraintAssembler::new(complex, &inputs.mesh)
        .compile_all(&inputs.set.constraints)
        .with_context(|| format!("{}", inputs.constraints_path.display()))
}

/// The residuals of the solved `field`, or an error naming the constraint file and the
/// constraint when the field or a residual is NaN or infinite.
pub fn solution_residuals(
    field: &[f64],
    constraints: &[CompiledConstraint],
    inputs: &DesignInputs,
) -> Result<Vec<ConstraintResidual>> {
    checked_residuals(field, constraints, inputs.set.omega)
        .with_context(|| format!("{}", inputs.constraints_path.display()))
}

/// Reports one line per constraint residual and the worst relative one (JSON: `residuals`
/// as `[{id, absolute, relative}]` and `worst_relative_residual`).
pub fn report_residuals(residuals: &[ConstraintResidual], report: &mut Report) {
    report.line("constraint residuals (|C̃x − c|, relative):");
    for r in residuals {
        report.line(format!(
            "  {:<16} {:.3e}  {:.3e}",
            r.id, r.absolute, r.relative
        ));
    }
    let worst = worst_residual(residuals).map_or(0.0, |r| r.relative);
    report.line(format!("worst relative residual {worst:.3e}"));
    let list: Vec<_> = residuals
        .iter()
        .map(|r| serde_json::json!({"id": r.id, "absolute": r.absolute, "relative": r.relative}))
        .collect();
    report.set("residuals", list);
    report.set("worst_relative_residual", worst);
}

/// Runs `tvf spline`.
pub fn run(args: SplineArgs, context: &RunContext) -> Result<()> {
    let mut report = Report::new(args.json);
    let basis_file = args.basis.options.basis.as_deref();
    let inputs = [Some(args.constraints.as_path()), basis_file];
    check_output(&args.output, &args.input, &inputs)?;
    let inputs = load_inputs(&args.input, &args.constraints, &mut report)?;
    let catalog = context.catalog();
    let discretization = discretization(catalog, &inputs, &args.input, &args.basis)?;
    spline_with(
        catalog,
        discretization.as_ref(),
        &inputs,
        &args,
        &mut report,
    )?;
    report.finish()
}

fn spline_with<H: HodgeComplex + ?Sized>(
    catalog: &Catalog,
    complex: &H,
    inputs: &DesignInputs,
    args: &SplineArgs,
    report: &mut Report,
) -> Result<()> {
    let constraints = compile(complex, inputs)?;
    let basis = reduced_basis(catalog, inputs, &args.input, &args.basis, report)?;
    let solved = timed_spline(&basis, inputs.set.omega, &constraints)
        .with_context(|| format!("{}", inputs.constraints_path.display()))?;
    let (setup_ms, solve_ms, map_ms) = (solved.setup_ms, solved.solve_ms, solved.map_ms);
    report.line(format!(
        "spline setup    {setup_ms:.3} ms ({} constraints, {} rows, d = {})",
        constraints.len(),
        solved.rows,
        basis.len()
    ));
    report.line(format!(
        "spline solve    {solve_ms:.3} ms reduced + {map_ms:.3} ms mapping to the full field"
    ));
    report.set("rows", solved.rows);
    report.set("setup_ms", setup_ms);
    report.set("solve_ms", solve_ms);
    report.set("map_ms", map_ms);
    let field = solved.field;
    report_residuals(&solution_residuals(&field, &constraints, inputs)?, report);
    write_tangent_field(&args.output, complex.require_sampling()?, &field)?;
    report.line(format!("wrote {}", args.output.display()));
    report.set("output", args.output.display().to_string());
    Ok(())
}
