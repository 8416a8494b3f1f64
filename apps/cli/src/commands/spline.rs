//! `tvf spline`: a tangential vector field spline (hard constraints, Section 7) from a JSON
//! constraint file, in a loaded or freshly computed eigenbasis.

use crate::basis_source::{BasisSource, Discretization};
use crate::mesh_input::MeshInput;
use crate::with_complex;
use anyhow::{Context, Result};
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tvf_core::discretization::HodgeComplex;
use tvf_core::SurfaceMesh;
use tvf_design::{
    CompiledConstraint, ConstraintAssembler, ConstraintResidual, ConstraintSet, ReducedBasis,
    SplineSession,
};
use tvf_spectral::{mesh_fingerprint, write_tangent_field};

/// Arguments of `tvf spline`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf spline bunny.obj --constraints constraints.json -k 1000 -o spline.npy\n  \
tvf spline bunny.obj --constraints constraints.json --basis bunny.tvfb -o spline.npy\n  \
tvf render bunny.obj spline.npy --constraints constraints.json -o spline.png   (look at it)\n\n\
The spline lives in the basis of the K lowest eigenfields (-k K, the paper's d; computed once and cached, \
K ≥ 2F: the complete basis) or of a --basis file; constraints are met exactly in that basis."
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
pub fn load_inputs(input: &MeshInput, constraints: &Path) -> Result<DesignInputs> {
    let mesh = input.load()?.mesh;
    let set = ConstraintSet::load(constraints)?;
    set.check_fingerprint(&format!("{:016x}", mesh_fingerprint(&mesh)), constraints)?;
    println!(
        "mesh            {} ({} faces, genus {})",
        input.label(),
        mesh.face_count(),
        mesh.genus()
    );
    println!(
        "constraints     {} from {} (omega {})",
        set.constraints.len(),
        constraints.display(),
        set.omega
    );
    Ok(DesignInputs {
        mesh,
        set,
        constraints_path: constraints.to_path_buf(),
    })
}

/// The discretization of `source` (the basis file's, or the flags'), without the basis: for
/// checking the constraints before an expensive basis computation.
pub fn discretization(
    inputs: &DesignInputs,
    input: &MeshInput,
    source: &BasisSource,
) -> Result<Discretization> {
    source.options.discretization(&inputs.mesh, input)
}

/// The basis of `source` (loaded, cached or computed; see [`crate::basis_source`]), row-major
/// for the solvers.
pub fn reduced_basis(
    inputs: &DesignInputs,
    input: &MeshInput,
    source: &BasisSource,
) -> Result<ReducedBasis> {
    let start = Instant::now();
    let resolved = source.resolve(&inputs.mesh, input)?;
    println!(
        "basis           {} fields of {} ready in {:.3} s",
        resolved.basis.len(),
        resolved.discretization.name(),
        start.elapsed().as_secs_f64()
    );
    Ok(ReducedBasis::from_spectral(&resolved.basis)?)
}

/// Compiles the set's constraints for `complex`; errors name the constraint file.
pub fn compile<H: HodgeComplex>(
    complex: &H,
    inputs: &DesignInputs,
) -> Result<Vec<CompiledConstraint>> {
    ConstraintAssembler::new(complex, &inputs.mesh)
        .compile_all(&inputs.set.constraints)
        .with_context(|| format!("{}", inputs.constraints_path.display()))
}

/// Prints one line per constraint residual and the worst relative one.
pub fn print_residuals(residuals: &[ConstraintResidual]) {
    println!("constraint residuals (|C̃x − c|, relative):");
    for r in residuals {
        println!("  {:<16} {:.3e}  {:.3e}", r.id, r.absolute, r.relative);
    }
    let worst = residuals.iter().map(|r| r.relative).fold(0.0, f64::max);
    println!("worst relative residual {worst:.3e}");
}

/// Runs `tvf spline`.
pub fn run(args: SplineArgs) -> Result<()> {
    let inputs = load_inputs(&args.input, &args.constraints)?;
    let discretization = discretization(&inputs, &args.input, &args.basis)?;
    with_complex!(&discretization, c => spline_with(c, &inputs, &args))
}

fn spline_with<H: HodgeComplex>(
    complex: &H,
    inputs: &DesignInputs,
    args: &SplineArgs,
) -> Result<()> {
    let constraints = compile(complex, inputs)?;
    let basis = reduced_basis(inputs, &args.input, &args.basis)?;
    let start = Instant::now();
    let mut session = SplineSession::new(&basis, inputs.set.omega)?;
    for c in constraints {
        session
            .add(c)
            .with_context(|| format!("{}", inputs.constraints_path.display()))?;
    }
    let setup = start.elapsed();
    let start = Instant::now();
    let v = session.solve();
    let solve = start.elapsed();
    let start = Instant::now();
    let mut field = vec![0.0; basis.field_dimension()];
    basis.map(&v, &mut field)?;
    let map = start.elapsed();
    println!(
        "spline setup    {:.3} ms ({} constraints, {} rows, d = {})",
        setup.as_secs_f64() * 1e3,
        session.ids().len(),
        session.row_count(),
        basis.len()
    );
    println!(
        "spline solve    {:.3} ms reduced + {:.3} ms mapping to the full field",
        solve.as_secs_f64() * 1e3,
        map.as_secs_f64() * 1e3
    );
    print_residuals(&session.residuals(&field));
    write_tangent_field(&args.output, complex.fields(), &field)?;
    println!("wrote {}", args.output.display());
    Ok(())
}
