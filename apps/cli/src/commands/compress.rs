//! `tvf compress`: a field, or a time-dependent sequence of fields, as the lowest `k` pairs of
//! Fourier coefficients in a `.tvfc` file.

use super::spectral_inputs::{read_frames, FieldArgs};
use crate::context::RunContext;
use crate::progress::Progress;
use anyhow::Result;
use clap::Args;
use rayon::prelude::*;
use serde_json::json;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use tvf_core::discretization::Mass;
use tvf_spectral::BasisSize;
use tvf_spectral::FrameSource;
use tvf_spectral::{
    basis_id, relative_l2_error, CoefficientCoding, CompressedFields, CompressionError,
    CompressionReport, FieldCodec,
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
    let field = args.inputs.field_path_for(&args.output, &[])?;
    let size = args.inputs.basis.size_or(BasisSize::Pairs(args.pairs));
    let inputs = args.inputs.load(context.catalog())?;
    let (frames, source) = read_frames(&field, inputs.fields()?)?;
    let setup = args.inputs.setup(context.catalog(), inputs, size)?;
    let coding = match args.bits {
        Some(bits) => CoefficientCoding::Quantized { bits },
        None => CoefficientCoding::Float64,
    };
    let id = basis_id(&setup.basis);
    let codec = FieldCodec::new(&setup.basis, setup.mesh_fingerprint, id, args.pairs, coding)?;
    let (file, report) = compress_frames(
        &codec,
        setup.basis.field_mass(),
        &frames,
        setup.mesh.vertex_count(),
    )?;
    file.write_atomic(&args.output)?;
    let coding_name = match coding {
        CoefficientCoding::Float64 => "f64".to_string(),
        CoefficientCoding::Quantized { bits } => format!("quantised {bits} bits, range-coded"),
    };
    if args.json {
        let value = json!({
            "output": args.output.display().to_string(),
            "frames": report.frames,
            "sequence": source != FrameSource::Single,
            "pairs": args.pairs,
            "coefficients_per_frame": report.coefficients_per_frame,
            "coding": coding_name,
            "bytes": report.bytes,
            "bits_per_vertex": report.bits_per_vertex(),
            "rate_against_two_doubles": report.rate_against_two_doubles(),
            "rate_against_two_floats": report.rate_against_two_floats(),
            "mean_relative_error": report.mean_error(),
            "worst_relative_error": report.worst_error(),
            "relative_errors": report.relative_errors,
        });
        println!("{}", serde_json::to_string_pretty(&value)?);
    } else {
        println!("frames                {}", report.frames);
        println!(
            "coefficients/frame    {} ({} pairs, {coding_name})",
            report.coefficients_per_frame, args.pairs
        );
        println!("file size             {} bytes", report.bytes);
        println!(
            "bits per vertex       {:.3} (per frame)",
            report.bits_per_vertex()
        );
        println!(
            "rate vs 2 doubles/face {:.2}",
            report.rate_against_two_doubles()
        );
        println!(
            "rate vs 2 floats/face {:.2}",
            report.rate_against_two_floats()
        );
        println!(
            "relative L2 error     mean {:.4e}, worst {:.4e}",
            report.mean_error(),
            report.worst_error()
        );
        println!("wrote                 {}", args.output.display());
    }
    Ok(())
}

/// Encodes every frame (in parallel) and decodes it again to measure its relative `M1` error,
/// with a progress bar for sequences (plain lines off a terminal, nothing with `--quiet`).
fn compress_frames(
    codec: &FieldCodec<'_>,
    mass: &Mass,
    frames: &[Vec<f64>],
    vertex_count: usize,
) -> Result<(CompressedFields, CompressionReport)> {
    if frames.is_empty() {
        return Err(CompressionError::NoFrames.into());
    }
    let progress = (frames.len() > 1).then(|| Progress::new("compress"));
    let done = AtomicUsize::new(0);
    let encoded = frames
        .par_iter()
        .map(|field| {
            let payload = codec.encode(field)?;
            let error = relative_l2_error(mass, field, &codec.decode(&payload)?);
            let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
            if let Some(progress) = &progress {
                progress.update("frames", finished, frames.len());
            }
            Ok((payload, error))
        })
        .collect::<Result<Vec<_>, CompressionError>>()?;
    let (payloads, relative_errors): (Vec<_>, Vec<_>) = encoded.into_iter().unzip();
    let file = CompressedFields {
        header: *codec.header(),
        frames: payloads,
    };
    let report = CompressionReport {
        bytes: file.to_bytes().len(),
        frames: frames.len(),
        vertex_count,
        field_dimension: mass.len(),
        coefficients_per_frame: codec.selection().len(),
        relative_errors,
    };
    if let Some(progress) = &progress {
        progress.finish(format!(
            "{} frames, {} bytes, worst relative error {:.3e}",
            report.frames,
            report.bytes,
            report.worst_error()
        ));
    }
    Ok((file, report))
}
