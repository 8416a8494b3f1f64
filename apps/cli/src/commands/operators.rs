//! `tvf operators`: writes the paper's matrices of a mesh as Matrix Market files (or as `.npz`
//! files `scipy.sparse.load_npz` reads), with the map from the mesh's vertices to the input's.

use crate::context::RunContext;
use crate::discretization_flags::DiscretizationFlags;
use crate::mesh_input::MeshInput;
use crate::output_rules::{check_output, commit, stage};
use anyhow::{Context, Result};
use clap::Args;
use serde_json::json;
use sprs::CsMat;
use std::io::Write;
use std::path::PathBuf;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::io::{AtomicWriter, StagedFolder};
use tvf_core::mesh::ValidationReport;
use tvf_core::SurfaceMesh;
use tvf_spectral::{
    complex_folder_info, mass_file_name, npy_bytes, write_sparse_npz, MatrixFileFormat, NpyData,
};

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
    let staged = stage(&args.out)?;
    let written = write_all(
        complex.as_ref(),
        &mesh,
        &loaded.report,
        args.format,
        &staged,
    )?;
    let out = staged.target().to_path_buf();
    commit(staged)?;
    println!(
        "wrote {written} matrices and info.json to {} ({})",
        out.display(),
        complex.id()
    );
    Ok(())
}

/// Writes every file of `complex` into `out`; returns the number of matrices.
fn write_all(
    complex: &dyn HodgeComplex,
    mesh: &SurfaceMesh,
    report: &ValidationReport,
    format: MatrixFormat,
    out: &StagedFolder,
) -> Result<usize> {
    let mut matrices: Vec<(String, CsMat<f64>)> = vec![
        ("d0".into(), complex.d0().clone()),
        ("d1".into(), complex.d1().clone()),
    ];
    for (name, mass) in [
        ("M0", complex.m0()),
        ("M1", complex.m1()),
        ("M2", complex.m2()),
    ] {
        matrices.push((mass_file_name(name, mass.form()), mass.stored_matrix()));
    }
    matrices.push(("S0".into(), complex.potential_stiffness().clone()));
    let mut not_written = serde_json::Map::new();
    for (name, operator, why) in [
        (
            "S2",
            complex.co_potential_stiffness(),
            "d1 M1^-1 d1^T with a non-diagonal M1",
        ),
        (
            "S",
            complex.dirichlet_energy(),
            "it contains M0^-1 or M2 of a non-diagonal mass",
        ),
        (
            "B",
            complex.biharmonic_energy(),
            "S M1^-1 S with a non-diagonal M1 or a dense S",
        ),
    ] {
        match operator.as_sparse() {
            Some(matrix) => matrices.push((name.into(), matrix.clone())),
            None => {
                not_written.insert(name.into(), json!(format!("dense: {why}")));
            }
        }
    }
    if let Some(rotation) = complex.rotation() {
        matrices.push(("J".into(), rotation.rotation().clone()));
    }
    for (name, matrix) in &matrices {
        match format {
            MatrixFormat::Mtx => write_atomically(out, &format!("{name}.mtx"), |w| {
                sprs::io::write_matrix_market_to_bufwrite(w, matrix)
            })?,
            MatrixFormat::Npz => write_atomically(out, &format!("{name}.npz"), |w| {
                let mut buffer = std::io::Cursor::new(Vec::new());
                write_sparse_npz(&mut buffer, matrix)?;
                w.write_all(buffer.get_ref())
            })?,
        }
    }
    let vertex_map: Vec<i64> = report.original_vertex.iter().map(|&v| v as i64).collect();
    write_atomically(out, "vertex_map.npy", |w| {
        w.write_all(&npy_bytes(&NpyData::I64(&vertex_map), &[vertex_map.len()]))
    })?;
    let file_format = match format {
        MatrixFormat::Mtx => MatrixFileFormat::MatrixMarket,
        MatrixFormat::Npz => MatrixFileFormat::SparseNpz,
    };
    let info = complex_folder_info(complex, mesh, report, file_format, not_written);
    let text = serde_json::to_string_pretty(&info)? + "\n";
    write_atomically(out, "info.json", |w| w.write_all(text.as_bytes()))?;
    Ok(matrices.len())
}

/// Writes the file `name` of the staged folder `out` atomically
/// ([`tvf_core::io::write_atomically`]); errors name the file in the output folder.
fn write_atomically(
    out: &StagedFolder,
    name: &str,
    fill: impl FnOnce(&mut AtomicWriter<'_>) -> std::io::Result<()>,
) -> Result<()> {
    tvf_core::io::write_atomically(&out.path().join(name), fill)
        .with_context(|| format!("cannot write {}", out.target().join(name).display()))
}
