//! `tvf decompress`: the fields of a `.tvfc` file (a `--basis` file of eigenfunctions read in
//! blocks: the synthesis is the loaded basis's bit for bit where `M1` is diagonal).

use super::spectral_inputs::{identified_basis, inputs_for_mesh};
use crate::basis_source::BasisSource;
use crate::context::RunContext;
use crate::mesh_input::MeshInput;
use crate::output_rules::check_output;
use crate::progress::Progress;
use anyhow::{anyhow, Result};
use clap::Args;
use std::path::PathBuf;
use tvf_spectral::{
    check_computed_field, decompress_with_progress, field_basis_id, write_field_frames, BasisSize,
    CompressedFields, FieldCodec,
};

/// Arguments of `tvf decompress`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf decompress bunny.obj field.tvfc --basis bunny.tvfb -o field.npy\n\nA file with one frame is written to OUT (.npy or text by extension). A sequence is \
written as one .npy array F×3×T if OUT ends in .npy, otherwise into the folder OUT as frame_00000.npy, ... \
The mesh and the basis must be the ones the file was compressed with (checked by fingerprint and basis id)."
)]
pub struct DecompressArgs {
    #[command(flatten)]
    input: MeshInput,
    /// The compressed file (.tvfc).
    #[arg(value_name = "FILE.tvfc", required_unless_present = "example")]
    compressed: Option<PathBuf>,
    #[command(flatten)]
    basis: BasisSource,
    /// Output field file, array or folder (see below).
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,
}

/// Decodes every frame and writes them.
pub fn run(mut args: DecompressArgs, context: &RunContext) -> Result<()> {
    let compressed = args
        .input
        .required_second(args.compressed.take(), "FILE.tvfc");
    let basis_file = args.basis.options.basis.as_deref();
    check_output(&args.output, &args.input, &[Some(&compressed), basis_file])?;
    // The mesh first: a bad mesh is reported before a bad file.
    let mesh = args.input.load()?.mesh;
    let file = CompressedFields::read(&compressed)?;
    let inputs = inputs_for_mesh(context.catalog(), mesh, &args.input, &args.basis.options)?;
    file.header
        .check_fits(&inputs.mesh, inputs.complex.as_ref())
        .map_err(|e| anyhow!("{}: {e}", compressed.display()))?;
    let mesh_fingerprint = inputs.mesh.fingerprint();
    // Without --basis or -k, compute the basis of as many pairs as the file keeps. A `--basis`
    // file of eigenfunctions is read in blocks (unless its fields would not get the loaded
    // basis's id, which the file carries).
    let size = args
        .basis
        .size_or(BasisSize::Pairs(file.header.pairs as usize));
    let setup = identified_basis(
        context.catalog(),
        &args.input,
        &args.basis.options,
        inputs,
        size,
    )?;
    let id = field_basis_id(setup.basis())?;
    let codec = FieldCodec::for_file(setup.basis(), mesh_fingerprint, id, &file.header)
        .map_err(|e| anyhow::anyhow!("{}: {e}", compressed.display()))?;
    // A progress bar for sequences (plain lines off a terminal, nothing with `--quiet`).
    let count = file.frames.len();
    let progress = (count > 1).then(|| Progress::new("decompress"));
    let on_frame = |done| {
        if let Some(progress) = &progress {
            progress.update("frames", done, count);
        }
    };
    let frames = decompress_with_progress(&codec, &file, &on_frame)?;
    if let Some(progress) = &progress {
        progress.finish(format!("{count} frames decoded"));
    }
    for (k, frame) in frames.iter().enumerate() {
        check_computed_field(
            frame,
            &format!("frame {k} of {}", compressed.display()),
            "its coefficients are too large for f64 arithmetic",
        )?;
    }
    write_field_frames(&args.output, setup.fields()?, &frames)?;
    println!("frames    {}", frames.len());
    println!("wrote     {}", args.output.display());
    Ok(())
}
