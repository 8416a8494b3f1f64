//! `tvf compress`: a field, or a time-dependent sequence of fields, as the lowest `k` pairs of
//! Fourier coefficients in a `.tvfc` file.

use super::spectral_inputs::{read_frames, FieldArgs};
use crate::context::RunContext;
use crate::progress::Progress;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use tvf_spectral::{
    compress_with_progress, field_basis_id, BasisSize, CoefficientCoding, CompressionSummary,
    FieldCodec, FrameSource,
};

/// Arguments of `tvf compress`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf compress bunny.obj field.npy --basis bunny.tvfb --pairs 300 --bits 12 -o field.tvfc\n  tvf compress torus.obj frames/ --pairs 200 -o sequence.tvfc   (basis computed once, then cached)\n\nFIELD is one field file (.npy F×3 or text `x y z` per line), or a sequence: an .npy \
array F×3×T, or a folder of .npy/.txt frames (taken in file-name order). All frames go into one .tvfc file \
(compressed in parallel) and the report gives the mean and worst per-frame error.\n\n\
Kept fields: the lowest P integrable and the lowest P co-integrable fields of the basis plus every harmonic \
field (a family with fewer than P fields is kept whole). Without --bits the coefficients are stored as 64-bit \
floats (the paper's rate, 2·64·P/V bits per vertex); with --bits Q they are quantised uniformly to Q-bit \
symbols (step = largest |coefficient| / (2^(Q-1) - 1) per frame) and range-coded."
)]
pub struct CompressArgs {
    #[command(flatten)]
    inputs: FieldArgs,
    /// Coefficient pairs kept: the lowest P integrable + P co-integrable coefficients, plus the
    /// harmonic ones (without --basis or -k, the basis computed is these fields).
    #[arg(long, value_name = "P")]
    pairs: usize,
    /// Quantise the coefficients to Q-bit symbols (2 to 32) and range-code them.
    #[arg(long, value_name = "Q", value_parser = clap::value_parser!(u32).range(2..=32))]
    bits: Option<u32>,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
    /// Output file (.tvfc), written atomically.
    #[arg(short, long, value_name = "FILE.tvfc")]
    output: PathBuf,
}

/// Compresses the frames, writes the file and reports size and error.
pub fn run(mut args: CompressArgs, context: &RunContext) -> Result<()> {
    let field = args.inputs.field_path_for_file(&args.output, &[])?;
    let size = args.inputs.basis.size_or(BasisSize::Pairs(args.pairs));
    let inputs = args.inputs.load(context.catalog())?;
    let (frames, source) = read_frames(&field, inputs.fields()?)?;
    let (vertex_count, mesh_fingerprint) = (inputs.mesh.vertex_count(), inputs.mesh.fingerprint());
    // A `--basis` file of eigenfunctions is read in blocks, never loaded whole, unless its
    // fields would not get the basis id of the loaded basis, which `tvf decompress` checks.
    let setup = args
        .inputs
        .identified_basis(context.catalog(), inputs, size)?;
    let basis = setup.basis();
    let coding = match args.bits {
        Some(bits) => CoefficientCoding::Quantized { bits },
        None => CoefficientCoding::Float64,
    };
    let id = field_basis_id(basis)?;
    let codec = FieldCodec::new(basis, mesh_fingerprint, id, args.pairs, coding)?;
    // A progress bar for sequences (plain lines off a terminal, nothing with `--quiet`).
    let progress = (frames.len() > 1).then(|| Progress::new("compress"));
    let on_frame = |done| {
        if let Some(progress) = &progress {
            progress.update("frames", done, frames.len());
        }
    };
    let mass = basis.field_mass();
    let (file, report) = compress_with_progress(&codec, mass, &frames, vertex_count, &on_frame)?;
    if let Some(progress) = &progress {
        progress.finish(format!(
            "{} frames, {} bytes, worst relative error {:.3e}",
            report.frames,
            report.bytes,
            report.worst_error()
        ));
    }
    file.write_atomic(&args.output)?;
    let summary = CompressionSummary {
        report: &report,
        output: &args.output,
        pairs: args.pairs,
        coding,
        sequence: source != FrameSource::Single,
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&summary.to_json())?);
    } else {
        print!("{}", summary.text());
    }
    Ok(())
}
