//! `tvf demo`: the tour. Computes a basis on a generated bumpy torus (or `--mesh`) and writes a
//! web page of pictures and numbers, each step timed.

use crate::basis_source::compute;
use crate::context::RunContext;
use crate::discretization_flags::DiscretizationFlags;
use crate::mesh_input::MeshInput;
use crate::output_rules::{commit, stage};
use crate::picture_options::parse_size;
use crate::progress::note;
use anyhow::{bail, Result};
use clap::Args;
use std::path::{Path, PathBuf};
use tvf_discretizations::BoxedComplex;
use tvf_figures::demo::{default_mesh, run as run_demo, DemoConfig, DemoHost};
use tvf_figures::FigureError;
use tvf_spectral::{BasisSize, SpectralBasis};

const EXAMPLES: &str = "Examples:
  tvf demo -o demo-out                  (then open demo-out/index.html)
  tvf demo -o demo-bunny --mesh bunny-closed.obj -k 300

The default mesh is a bumpy torus with 14,400 faces and the basis has its 400 lowest
eigenfields (-k 400: 2 harmonic fields, then integrable and co-integrable ones, about 200 of
each); the whole demo takes well under two minutes on two cores.";

/// Eigenfields of the default basis (`-k`).
const DEFAULT_FIELDS: usize = 400;

/// Eigenfields of the `--quick` basis.
const QUICK_FIELDS: usize = 60;

/// Fewest eigenfields the demo accepts: three pairs to show plus the harmonic fields.
const MIN_FIELDS: usize = 10;

/// Arguments of `tvf demo`.
#[derive(Args)]
#[command(after_help = EXAMPLES)]
pub struct DemoArgs {
    /// Output folder (created if missing): index.html and the pictures.
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    /// A mesh file instead of the generated bumpy torus (closed or with boundary; --boundary
    /// picks the boundary condition).
    #[arg(long, value_name = "MESH")]
    mesh: Option<PathBuf>,
    /// Basis size: the K lowest eigenfields, harmonic ones included (the paper's d)
    /// [default: 400; 60 with --quick].
    #[arg(short = 'k', value_name = "K")]
    fields: Option<usize>,
    /// Size of a full-width picture (grid panels are half of it each way).
    #[arg(long, value_name = "WxH", default_value = "800x600")]
    size: String,
    #[command(flatten)]
    discretization: DiscretizationFlags,
    /// A small mesh, basis and pictures, for tests (a few seconds).
    #[arg(long, hide = true)]
    quick: bool,
}

/// Runs the demo.
pub fn run(args: DemoArgs, context: &RunContext) -> Result<()> {
    if let Some(dir) = &args.discretization.complex {
        bail!(
            "--complex {}: tvf demo builds a catalog discretization on its mesh; run the other \
             subcommands (spectrum, filter, render ...) on your matrices",
            dir.display()
        );
    }
    let inputs: Vec<&Path> = args.mesh.as_deref().into_iter().collect();
    tvf_core::io::check_output(&args.output, &inputs)?;
    let (width, height) = if args.quick {
        (320, 240)
    } else {
        parse_size(&args.size)?
    };
    let (mesh, mesh_name) = match &args.mesh {
        Some(path) => {
            let input = MeshInput::file(path.clone());
            (input.load()?.mesh, input.label())
        }
        None => default_mesh(args.quick)?,
    };
    let fields = args.fields.unwrap_or(if args.quick {
        QUICK_FIELDS
    } else {
        DEFAULT_FIELDS
    });
    if fields < MIN_FIELDS {
        bail!("-k {fields}: the demo needs at least {MIN_FIELDS} eigenfields");
    }
    // The pages and pictures go to a temporary sibling folder, renamed into place at the end.
    let staged = stage(&args.output)?;
    let discretization = args.discretization.id(&mesh);
    let config = DemoConfig {
        output: staged.path().to_path_buf(),
        mesh,
        mesh_name,
        fields,
        catalog: context.catalog().clone(),
        discretization,
        width,
        height,
        fur_strands: if args.quick { 1500 } else { 25_000 },
    };
    let index = run_demo(&config, &CommandLineHost)?;
    commit(staged)?;
    let index = args.output.join(index.file_name().unwrap_or_default());
    println!("wrote {}", index.display());
    Ok(())
}

/// The demo run from the command line: bases computed with a progress bar, notes on stderr
/// (hidden by `--quiet`).
struct CommandLineHost;

impl DemoHost for CommandLineHost {
    fn compute_basis(
        &self,
        complex: &BoxedComplex,
        size: BasisSize,
    ) -> Result<SpectralBasis, FigureError> {
        compute(complex, size).map_err(|e| FigureError::Host(e.into()))
    }

    fn note(&self, message: &str) {
        note(message);
    }
}
