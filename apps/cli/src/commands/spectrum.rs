//! `tvf spectrum`: the lowest eigenvalues of the Hodge–Laplacian on tangent fields, labelled by
//! family.

use crate::context::RunContext;
use crate::discretization_flags::DiscretizationFlags;
use crate::mesh_input::MeshInput;
use crate::progress::Progress;
use anyhow::{bail, Context, Result};
use clap::Args;
use serde_json::json;
use std::time::Instant;
use tvf_core::discretization::HodgeOperators;
use tvf_spectral::{compute_eigenfunction_basis, BasisRequest};

/// Arguments of `tvf spectrum`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf spectrum bunny.obj -k 100\n  tvf spectrum --example genus3 -k 50 --decomposition nonconforming --json\n\nWith --json, prints {\"eigenvalues\": [...ascending], \"labels\": \
[\"harmonic\"|\"integrable\"|\"cointegrable\", ...], \"seconds\": ...} (plus the mesh and the \
discretization) to stdout. Eigenvalues are in 1/length² (frequencies are their square roots)."
)]
pub struct SpectrumArgs {
    #[command(flatten)]
    input: MeshInput,
    /// The K lowest eigenvalues, harmonic zeros included: those of the basis of K eigenfields
    /// (`tvf basis -k K`, the paper's d); K ≥ n1 (the field dimension: 2F for face fields, E
    /// for DEC/Whitney) gives all of them.
    #[arg(short = 'k', value_name = "K")]
    count: usize,
    #[command(flatten)]
    discretization: DiscretizationFlags,
    /// Print JSON to stdout instead of a table.
    #[arg(long)]
    json: bool,
}

/// Computes and prints the spectrum.
pub fn run(args: SpectrumArgs, context: &RunContext) -> Result<()> {
    if args.count == 0 {
        bail!("-k 0: ask for at least one eigenvalue");
    }
    let start = Instant::now();
    let mesh = args.input.load()?.mesh;
    let discretization = args
        .discretization
        .build(context.catalog(), &mesh, &args.input)?;
    let progress = Progress::new("spectrum");
    let (basis, _) = {
        let callback = progress.basis_callback();
        // K ≥ n1: every eigenvalue (the complete basis), as for `tvf basis -k K`.
        let request = BasisRequest::lowest(args.count, discretization.field_dimension())
            .with_progress(&callback);
        compute_eigenfunction_basis(discretization.as_ref(), &request)
            .with_context(|| format!("{}: cannot compute the spectrum", args.input.label()))?
    };
    let seconds = start.elapsed().as_secs_f64();
    progress.finish(format!("{} eigenvalues in {seconds:.2} s", basis.len()));
    if args.json {
        let labels: Vec<&str> = basis.families().iter().map(|f| f.name()).collect();
        let out = json!({
            "mesh": args.input.label(),
            "discretization": discretization.id(),
            "faces": mesh.face_count(),
            "eigenvalues": basis.eigenvalues(),
            "labels": labels,
            "seconds": seconds,
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        print!("{}", basis.spectrum_table());
    }
    Ok(())
}
