//! `tvf basis`: compute the Fourier basis of a mesh (Section 6) and save it as a `.tvfb` file
//! and/or as numpy arrays (`--export DIR`).

use crate::context::RunContext;
use crate::discretization_flags::DiscretizationFlags;
use crate::mesh_input::MeshInput;
use crate::output_rules::{check_file_output, check_output};
use crate::progress::{note, Progress};
use anyhow::{bail, Context, Result};
use clap::Args;
use std::path::PathBuf;
use tvf_core::discretization::HodgeOperators;
use tvf_spectral::{
    compute_eigenfunction_basis, save_basis_outputs, save_computed_basis, BasisFileKey,
    BasisRequest, BasisSummary, SavedBasis, SavedBasisError,
};

/// Arguments of `tvf basis`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf basis bunny.obj -k 1000 -o bunny.tvfb\n  tvf basis bunny.obj -k 100 --export bunny-basis/   (np.load(\"bunny-basis/fields.npy\"))\n  tvf basis --example genus2 -k 200 --decomposition nonconforming --mass voronoi -o g2.tvfb\n\nThe basis holds the K eigenfields of lowest eigenvalue of the Hodge–Laplacian (the paper's d): \
the 2g harmonic fields first, then integrable and co-integrable eigenfields mixed as their eigenvalues come, \
sorted by eigenvalue (`tvf spectrum -k K` lists the same K eigenvalues). K ≥ n1 (the field dimension: 2F for face fields, E for DEC/Whitney) gives the complete basis. The file is tied to the mesh \
(fingerprint of its vertices and faces), to the discretization and to its matrices (a hash of the five \
matrices and the fixed nodes); other commands take it with --basis."
)]
pub struct BasisArgs {
    #[command(flatten)]
    input: MeshInput,
    /// Basis size: the K lowest eigenfields of the Hodge–Laplacian, harmonic ones included (the
    /// paper's d); K ≥ n1 (the field dimension: 2F for face fields, E for DEC/Whitney) gives
    /// the complete basis.
    #[arg(short = 'k', value_name = "K")]
    fields: usize,
    #[command(flatten)]
    discretization: DiscretizationFlags,
    /// Seed of the random fields and start vectors (equal seeds give identical files).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Output basis file (.tvfb).
    #[arg(short, long, value_name = "FILE", required_unless_present = "export")]
    output: Option<PathBuf>,
    /// Also (or instead) write the basis as numpy arrays into the folder DIR: eigenvalues.npy,
    /// families.npy, coefficients.npy (n1 × K), fields.npy (F × 3 × K, at the face centroids)
    /// and frames.npy (F × 2 × 3).
    #[arg(long, value_name = "DIR")]
    export: Option<PathBuf>,
    /// Print a summary (counts, eigenvalues, labels, seconds) as one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// Computes and saves the basis.
pub fn run(args: BasisArgs, context: &RunContext) -> Result<()> {
    if args.fields == 0 {
        bail!("-k 0: ask for at least one eigenfield");
    }
    if let Some(output) = &args.output {
        check_file_output(output, &args.input, &[])?;
    }
    if let Some(export) = &args.export {
        check_output(export, &args.input, &[])?;
    }
    let mesh = args.input.load()?.mesh;
    let discretization = args
        .discretization
        .build(context.catalog(), &mesh, &args.input)?;
    let progress = Progress::new("basis");
    let key = BasisFileKey::new(&mesh, discretization.as_ref());
    let cannot_compute = || format!("{}: cannot compute the basis", args.input.label());
    let saved = {
        let callback = progress.basis_callback();
        let request = BasisRequest::lowest(args.fields, discretization.field_dimension())
            .with_seed(args.seed)
            .with_progress(&callback);
        match (&args.output, &args.export) {
            // Without arrays to export, each finished interval's eigenfunctions go straight to
            // the file, so they are never all in memory.
            (Some(output), None) => {
                save_computed_basis(output, discretization.as_ref(), &request, &key).map_err(
                    |e| match e {
                        SavedBasisError::Compute(e) => {
                            anyhow::Error::new(e).context(cannot_compute())
                        }
                        SavedBasisError::File(e) => anyhow::Error::new(e),
                    },
                )?
            }
            _ => {
                let (basis, report) =
                    compute_eigenfunction_basis(discretization.as_ref(), &request)
                        .with_context(cannot_compute)?;
                // The file holds the eigenfunctions (about half the bytes of the dense fields).
                let writing = save_basis_outputs(
                    &basis,
                    discretization.as_ref(),
                    &key,
                    args.output.as_deref(),
                    args.export.as_deref(),
                )?;
                SavedBasis {
                    eigenvalues: basis.eigenvalues().to_vec(),
                    families: basis.families().to_vec(),
                    report,
                    streamed: false,
                    writing,
                }
            }
        }
    };
    let summary = BasisSummary {
        mesh: &args.input.label(),
        discretization: &key.discretization,
        eigenvalues: &saved.eigenvalues,
        families: &saved.families,
        report: &saved.report,
        writing: saved.writing,
        file: args.output.as_deref(),
        arrays: args.export.as_deref(),
    };
    progress.finish(summary.headline());
    let kept = tvf_spectral::FamilyCounts::of(&saved.families);
    saved.report.notes(kept).into_iter().for_each(note);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&summary.to_json())?);
    }
    Ok(())
}
