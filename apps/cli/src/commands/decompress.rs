//! `tvf decompress`: the fields of a `.tvfc` file.

use super::spectral_inputs::{load_setup, write_frames};
use crate::basis_source::BasisSource;
use crate::mesh_input::MeshInput;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use tvf_spectral::{basis_id, CompressedFields, FieldCodec};

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
    #[arg(value_name = "FILE.tvfc")]
    compressed: PathBuf,
    #[command(flatten)]
    basis: BasisSource,
    /// Output field file, array or folder (see below).
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,
}

/// Decodes every frame and writes them.
pub fn run(args: DecompressArgs) -> Result<()> {
    let file = CompressedFields::read(&args.compressed)?;
    // Without --basis or -k, compute the basis of as many pairs as the file keeps.
    let pairs = args.basis.pairs.or(Some(file.header.pairs as usize));
    let setup = load_setup(&args.input, &args.basis.options, pairs)?;
    let id = basis_id(&setup.basis);
    let codec = FieldCodec::for_file(&setup.basis, setup.mesh_fingerprint, id, &file.header)
        .map_err(|e| anyhow::anyhow!("{}: {e}", args.compressed.display()))?;
    let frames = codec.decompress(&file)?;
    write_frames(&args.output, &setup.fields, &frames)?;
    println!("frames    {}", frames.len());
    println!("wrote     {}", args.output.display());
    Ok(())
}
