//! `tvf spline`: a tangential vector field spline (hard constraints, Section 7) from a JSON
//! constraint file, in a loaded or freshly computed eigenbasis.

use crate::basis_source::{Decomposition, Mass};
use crate::mesh_input::MeshInput;
use crate::progress::Progress;
use anyhow::{bail, Context, Result};
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tvf_core::discretization::{FieldSpace, HodgeComplex};
use tvf_core::SurfaceMesh;
use tvf_design::{
    CompiledConstraint, ConstraintAssembler, ConstraintResidual, ConstraintSet, ReducedBasis,
    SplineSession,
};
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};
use tvf_spectral::{
    compute_basis, load_basis, mesh_fingerprint, read_basis_header, write_tangent_field,
    BasisFileKey, BasisRequest, SpectralBasis,
};

/// Basis size used when neither `--basis` nor `-k` is given.
const DEFAULT_FIELDS: usize = 200;

/// Where the eigenbasis comes from (shared by `tvf spline` and `tvf design`).
#[derive(Args, Debug, Clone)]
pub struct BasisChoice {
    /// A basis file (.tvfb, `tvf basis`) of this mesh; its discretization is used.
    #[arg(long, value_name = "FILE", conflicts_with = "fields")]
    basis: Option<PathBuf>,
    /// Compute the K lowest eigenfields (harmonic ones included) instead of loading a basis;
    /// K ≥ 2F gives the complete basis [default: 200].
    #[arg(short = 'k', value_name = "K")]
    fields: Option<usize>,
    /// Hodge decomposition when no basis file is given (alias: --discretization).
    #[arg(
        long,
        alias = "discretization",
        value_enum,
        value_name = "NAME",
        default_value = "conforming"
    )]
    decomposition: Decomposition,
    /// Mass lumping when no basis file is given.
    #[arg(long, value_enum, value_name = "NAME", default_value = "barycentric")]
    mass: Mass,
}

/// Arguments of `tvf spline`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf spline bunny.obj --constraints constraints.json -k 300 -o spline.npy\n  \
tvf spline bunny.obj --constraints constraints.json --basis bunny.tvfb -o spline.npy\n  \
tvf render bunny.obj spline.npy --constraints constraints.json -o spline.png   (look at it)"
)]
pub struct SplineArgs {
    #[command(flatten)]
    input: MeshInput,
    /// The constraint file (JSON, see README "Constraint files").
    #[arg(long, value_name = "C.json")]
    constraints: PathBuf,
    #[command(flatten)]
    basis: BasisChoice,
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

/// The complex named by a basis file, or by `--decomposition` and `--mass`.
pub enum AnyComplex {
    /// The conforming decomposition.
    Conforming(Conforming),
    /// The nonconforming decomposition.
    Nonconforming(Nonconforming),
}

/// The discretization and (loaded) basis selected by `choice`.
pub fn select_complex(
    mesh: &SurfaceMesh,
    choice: &BasisChoice,
) -> Result<(AnyComplex, Option<SpectralBasis>)> {
    let Some(path) = &choice.basis else {
        let lumping = choice.mass.lumping();
        let complex = match choice.decomposition {
            Decomposition::Nonconforming => {
                AnyComplex::Nonconforming(Nonconforming::new(mesh, lumping)?)
            }
            Decomposition::Conforming => AnyComplex::Conforming(Conforming::new(mesh, lumping)?),
        };
        return Ok((complex, None));
    };
    let start = Instant::now();
    let header = read_basis_header(path)?;
    let key = BasisFileKey {
        discretization: header.key.discretization.clone(),
        mesh_fingerprint: mesh_fingerprint(mesh),
        face_count: mesh.face_count(),
    };
    let basis = load_basis(path, &key)?;
    println!(
        "basis           {} fields loaded from {} in {:.3} s",
        basis.len(),
        path.display(),
        start.elapsed().as_secs_f64()
    );
    for lumping in [MassLumping::Barycentric, MassLumping::Voronoi] {
        let conforming = Conforming::new(mesh, lumping)?;
        if conforming.name() == header.key.discretization {
            return Ok((AnyComplex::Conforming(conforming), Some(basis)));
        }
        let nonconforming = Nonconforming::new(mesh, lumping)?;
        if nonconforming.name() == header.key.discretization {
            return Ok((AnyComplex::Nonconforming(nonconforming), Some(basis)));
        }
    }
    bail!(
        "{}: unknown discretization '{}' in the basis file",
        path.display(),
        header.key.discretization
    )
}

/// The loaded basis, or the `-k` lowest eigenfields of `complex`, row-major for the solvers.
pub fn reduced_basis<H: HodgeComplex>(
    complex: &H,
    loaded: Option<SpectralBasis>,
    choice: &BasisChoice,
) -> Result<ReducedBasis> {
    let basis = match loaded {
        Some(basis) => basis,
        None => {
            let start = Instant::now();
            let fields = choice.fields.unwrap_or(DEFAULT_FIELDS);
            // K ≥ 2F asks for every field: the complete basis (dense eigensolvers).
            let request = if fields >= complex.fields().dimension() {
                BasisRequest::complete()
            } else {
                BasisRequest::fields(fields)
            };
            let progress = Progress::new("basis");
            let callback = progress.basis_callback();
            let basis = compute_basis(complex, &request.with_progress(&callback))
                .with_context(|| format!("cannot compute {fields} eigenfields"))?;
            progress.finish(format!("{} fields", basis.len()));
            println!(
                "basis           {} fields of {} computed in {:.3} s",
                basis.len(),
                complex.name(),
                start.elapsed().as_secs_f64()
            );
            basis
        }
    };
    Ok(ReducedBasis::from_spectral(&basis)?)
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
    let (complex, loaded) = select_complex(&inputs.mesh, &args.basis)?;
    match &complex {
        AnyComplex::Conforming(c) => spline_with(c, &inputs, loaded, &args),
        AnyComplex::Nonconforming(c) => spline_with(c, &inputs, loaded, &args),
    }
}

fn spline_with<H: HodgeComplex>(
    complex: &H,
    inputs: &DesignInputs,
    loaded: Option<SpectralBasis>,
    args: &SplineArgs,
) -> Result<()> {
    let constraints = compile(complex, inputs)?;
    let basis = reduced_basis(complex, loaded, &args.basis)?;
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
