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
use tvf_core::discretization::{HodgeComplex, HodgeOperators, Mass, MassForm};
use tvf_core::io::{AtomicWriter, StagedFolder};
use tvf_core::mesh::ValidationReport;
use tvf_core::SurfaceMesh;
use tvf_spectral::{npy_bytes, write_sparse_npz, NpyData};

/// Arguments of `tvf operators`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf operators bunny.obj -o matrices/\n  tvf operators --example torus --discretization dec-circumcentric -o matrices/\n  \
tvf operators bunny.obj --format npz -o matrices/   (scipy.sparse.load_npz(\"matrices/S.npz\"))\n\n\
Unreferenced vertices of the input are dropped: vertex_map.npy (int64, one entry per mesh vertex) \
gives the input index of every row/column of a vertex-indexed matrix."
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
        .build(context.catalog(), &mesh, &args.input.label())?;
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
    let mut masses = serde_json::Map::new();
    for (name, mass) in [
        ("M0", complex.m0()),
        ("M1", complex.m1()),
        ("M2", complex.m2()),
    ] {
        let file = mass_file_name(name, mass.form());
        masses.insert(name.to_string(), mass_info(&file, mass));
        matrices.push((file, mass.stored_matrix()));
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
    let dropped = report.unreferenced_vertices();
    let (n0, n1, n2) = (
        complex.potential_dimension(),
        complex.field_dimension(),
        complex.co_potential_dimension(),
    );
    let nodes = |space: &tvf_core::discretization::NodeSpace| space.kind.name();
    let info = json!({
        "discretization": complex.id(),
        "vertices": mesh.vertex_count(),
        "input_vertices": report.input_vertex_count,
        "matrix_format": match format {
            MatrixFormat::Mtx => "Matrix Market (.mtx)",
            MatrixFormat::Npz => "scipy.sparse CSR (.npz, scipy.sparse.load_npz)",
        },
        "edges": mesh.edge_count(),
        "faces": mesh.face_count(),
        "components": mesh.component_count(),
        "genus": mesh.genus(),
        "harmonic_dimension": complex.topology().harmonic_dimension,
        "closed": mesh.is_closed(),
        "nodes": {
            "potentials": nodes(complex.potential_nodes()),
            "fields": nodes(complex.field_nodes()),
            "co_potentials": nodes(complex.co_potential_nodes()),
        },
        "fixed_nodes": {
            "about": "nodes the boundary condition fixes to zero: their columns of d0 (potentials), rows of d0 and columns of d1 (fields) or rows of d1 (co-potentials) are empty",
            "potentials": complex.potential_nodes().dirichlet_count(),
            "fields": complex.field_nodes().dirichlet_count(),
            "co_potentials": complex.co_potential_nodes().dirichlet_count(),
        },
        "matrices": {
            "d0": format!("{n1} x {n0}, gradient: potentials -> fields (pointwise)"),
            "d1": format!("{n2} x {n1}, integrated curl: fields -> co-potentials; d1 d0 = 0"),
            "M0": format!("{n0} x {n0}, potential mass (integrated, area)"),
            "M1": format!("{n1} x {n1}, field mass: x^T M1 y = integral of <x, y>"),
            "M2": format!("{n2} x {n2}, turns d1's integrated values into pointwise ones (1/area); M2^-1 is the co-potential mass"),
            "S0": format!("{n0} x {n0} potential stiffness d0^T M1 d0 (the cotan matrix for P1 potentials)"),
            "S2": format!("{n2} x {n2} co-potential stiffness d1 M1^-1 d1^T"),
            "S": format!("{n1} x {n1} Dirichlet energy M1 d0 M0^-1 d0^T M1 + d1^T M2 d1"),
            "B": format!("{n1} x {n1} biharmonic energy S M1^-1 S"),
            "J": if complex.rotation().is_some() {
                format!("{n1} x {n1}, +pi/2 rotation per face, (a, b) -> (-b, a)")
            } else {
                "not written: this discretization has no rotation of fields".to_string()
            },
        },
        "masses": masses,
        "not_written": not_written,
        "conventions": {
            "indices": "0-based in this file, in .npz and .npy files; Matrix Market files are 1-based",
            "face_frames": "a face-frame field stores face t at rows 2t, 2t+1 in the frame e1 = normalize(p_i1 - p_i0), e2 = n x e1",
            "edges": "edges (a, b) with a < b in lexicographic order; a 1-form is the field integrated from a to b",
            "vertex_order": if dropped == 0 {
                format!("as in the input mesh ({} vertices, none unreferenced); vertex_map.npy is the identity", report.input_vertex_count)
            } else {
                format!(
                    "the input's vertices in input order without the {dropped} unreferenced ones \
                     ({} of {} kept): vertex_map.npy[v] is the input index of mesh vertex v",
                    report.original_vertex.len(),
                    report.input_vertex_count
                )
            },
            "face_orientation": "counter-clockwise seen from outside, n = (p1 - p0) x (p2 - p0) normalized",
        },
    });
    let text = serde_json::to_string_pretty(&info)? + "\n";
    write_atomically(out, "info.json", |w| w.write_all(text.as_bytes()))?;
    Ok(matrices.len())
}

/// The file name of a mass: its name, with `_inverse` when the file holds the inverse (the form
/// in which it is sparse).
fn mass_file_name(name: &str, form: MassForm) -> String {
    match form {
        MassForm::Direct => name.to_string(),
        MassForm::Inverse => format!("{name}_inverse"),
    }
}

/// What `info.json` says of a mass: its file, whether the file holds the mass or its inverse,
/// and whether it is diagonal.
fn mass_info(file: &str, mass: &Mass) -> serde_json::Value {
    json!({
        "file": file,
        "form": mass.form().name(),
        "storage": if mass.is_diagonal() { "diagonal" } else { "sparse" },
    })
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
