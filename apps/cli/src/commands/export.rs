//! `tvf export`: a mesh and a field for other tools: VTK (ParaView), PLY (MeshLab, Polyscope)
//! with per-face vectors and scalars, or OBJ with the field's streamlines as polylines.

use super::spectral_inputs::read_field;
use crate::context::RunContext;
use crate::discretization_flags::DiscretizationFlags;
use crate::mesh_input::MeshInput;
use crate::output_rules::check_file_output;
use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};
use tvf_core::discretization::HodgeOperators;
use tvf_render::{streamline_polylines, write_obj, write_ply, write_vtk, FaceData};

const EXAMPLES: &str = "Examples:
  tvf export bunny.obj field.npy --format vtk -o field.vtk     (open in ParaView: cell data)
  tvf export bunny.obj field.npy -o field.ply                  (format from the extension)
  tvf export bunny.obj field.npy --format obj -o lines.obj     (mesh + streamlines as `l` polylines)

VTK and PLY carry per face: the vector `field` and the scalars `magnitude`, `divergence`, `curl`
and `energy` (as in `tvf render --color`).";

/// Export formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// VTK legacy ASCII polydata with cell data.
    Vtk,
    /// ASCII PLY with face properties.
    Ply,
    /// OBJ: the mesh and the field's streamlines as polylines.
    Obj,
}

/// Arguments of `tvf export`.
#[derive(Args)]
#[command(after_help = EXAMPLES)]
pub struct ExportArgs {
    #[command(flatten)]
    input: MeshInput,
    /// The field: one 3D vector per face (.npy F×3, or text `x y z` per line).
    #[arg(value_name = "FIELD", required_unless_present = "example")]
    field: Option<PathBuf>,
    /// Output format [default: from the output file's extension].
    #[arg(long, value_enum, value_name = "FORMAT")]
    format: Option<Format>,
    /// Output file.
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,
    /// Streamline density for OBJ (about this many separations² fit the surface).
    #[arg(long, value_name = "N", default_value_t = 2000)]
    streamlines: usize,
    #[command(flatten)]
    discretization: DiscretizationFlags,
}

fn format_of(path: &Path) -> Option<Format> {
    let extension = path.extension()?.to_str()?.to_ascii_lowercase();
    match extension.as_str() {
        "vtk" => Some(Format::Vtk),
        "ply" => Some(Format::Ply),
        "obj" => Some(Format::Obj),
        _ => None,
    }
}

/// Writes the export.
pub fn run(mut args: ExportArgs, context: &RunContext) -> Result<()> {
    let field = args.input.required_second(args.field.take(), "FIELD");
    check_file_output(&args.output, &args.input, &[Some(&field)])?;
    let mesh = args.input.load()?.mesh;
    let Some(format) = args.format.or_else(|| format_of(&args.output)) else {
        bail!(
            "{}: cannot tell the format from the extension; give --format vtk|ply|obj",
            args.output.display()
        );
    };
    let discretization = args
        .discretization
        .build(context.catalog(), &mesh, &args.input)?;
    let field = read_field(&field, discretization.require_sampling()?)?;
    let vectors = discretization.require_sampling()?.to_face_vectors(&field)?;
    match format {
        Format::Vtk | Format::Ply => {
            let data = FaceData::of_field(discretization.as_ref(), &mesh, &field, vectors)?;
            if format == Format::Vtk {
                write_vtk(&args.output, &mesh, &data)?;
            } else {
                write_ply(&args.output, &mesh, &data)?;
            }
            println!(
                "wrote {} ({} vertices, {} faces, per-face field + {} scalars)",
                args.output.display(),
                mesh.vertex_count(),
                mesh.face_count(),
                data.scalars.len()
            );
        }
        Format::Obj => {
            if args.streamlines == 0 {
                bail!("--streamlines 0: ask for at least one streamline");
            }
            let lines = streamline_polylines(&mesh, &vectors, args.streamlines)?;
            write_obj(&args.output, Some(&mesh), &lines)?;
            println!(
                "wrote {} ({} vertices, {} faces, {} streamlines)",
                args.output.display(),
                mesh.vertex_count(),
                mesh.face_count(),
                lines.iter().filter(|l| l.len() >= 2).count()
            );
        }
    }
    Ok(())
}
