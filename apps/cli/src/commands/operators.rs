//! `tvf operators`: writes the paper's matrices of a mesh as Matrix Market files (or as `.npz`
//! files `scipy.sparse.load_npz` reads), with the map from the mesh's vertices to the input's.

use crate::context::RunContext;
use crate::discretization_flags::DiscretizationFlags;
use crate::mesh_input::MeshInput;
use crate::output_rules::{check_output, commit, stage};
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use tvf_spectral::{write_complex_folder, MatrixFileFormat};

/// Arguments of `tvf operators`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf operators bunny.obj -o matrices/\n  tvf operators --example torus --discretization dec-circumcentric -o matrices/\n  \
tvf operators bunny.obj --format npz -o matrices/   (scipy.sparse.load_npz(\"matrices/S.npz\"))\n\n\
Unreferenced vertices of the input are dropped: vertex_map.npy (int64, one entry per mesh vertex) \
gives the input index of every row/column of a vertex-indexed matrix.\n\n\
The folder reads back with --complex DIR on every subcommand (edit d0, d1, M0, M1 or M2 first: \
the derived S, S0, S2, B and J are ignored)."
)]
pub struct OperatorsArgs {
    #[command(flatten)]
    input: MeshInput,
    #[command(flatten)]
    discretization: DiscretizationFlags,
    /// Output folder (created if missing).
    #[arg(short, long = "output", visible_alias = "out", value_name = "DIR")]
    out: PathBuf,
    /// File format of the matrices: Matrix Market (`NAME.mtx`, 1-based) or scipy's sparse
    /// `.npz` (`NAME.npz`, CSR, read by `scipy.sparse.load_npz`).
    #[arg(long, value_enum, default_value_t = MatrixFormat::Mtx)]
    format: MatrixFormat,
}

/// How `tvf operators` writes a matrix.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum MatrixFormat {
    /// Matrix Market coordinate files (`.mtx`).
    Mtx,
    /// `scipy.sparse.save_npz` layout (`.npz`, CSR).
    Npz,
}

/// Writes the five matrices of the complex (d0, d1, M0, M1, M2), the derived S0, S2, S, B, J
/// where the complex has a rotation, vertex_map.npy and info.json.
pub fn run(args: OperatorsArgs, context: &RunContext) -> Result<()> {
    check_output(&args.out, &args.input, &[])?;
    let loaded = args.input.load()?;
    let mesh = loaded.mesh;
    let complex = args
        .discretization
        .build(context.catalog(), &mesh, &args.input)?;
    let format = match args.format {
        MatrixFormat::Mtx => MatrixFileFormat::MatrixMarket,
        MatrixFormat::Npz => MatrixFileFormat::SparseNpz,
    };
    let staged = stage(&args.out)?;
    let written = write_complex_folder(complex.as_ref(), &mesh, &loaded.report, format, &staged)?;
    let out = staged.target().to_path_buf();
    commit(staged)?;
    println!(
        "wrote {written} matrices and info.json to {} ({})",
        out.display(),
        complex.id()
    );
    Ok(())
}
