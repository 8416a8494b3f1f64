//! `tvf render`: a picture of a mesh and (optionally) a tangent field, in software.

use super::spectral_inputs::read_field;
use crate::context::RunContext;
use crate::discretization_flags::DiscretizationFlags;
use crate::mesh_input::{usage_error, MeshInput};
use crate::output_rules::check_file_output;
use crate::picture_options::{face_quantity_arg, parse_size, parse_view, style_arg};
use crate::progress::note;
use anyhow::{bail, Result};
use clap::error::ErrorKind;
use clap::Args;
use std::path::PathBuf;
use std::time::Instant;
use tvf_core::discretization::HodgeOperators;
use tvf_figures::constraint_markers::constraint_file_markers;
use tvf_figures::panels::hodge_parts_grid;
use tvf_render::{draw_field, save_png, FaceQuantity, Overlays, Style, Tint, View};

const EXAMPLES: &str = "Examples:
  tvf render bunny.obj field.npy -o field.png --color curl --style streamlines
  tvf render --example bumpy-torus -o torus.png --view 60,35 --size 1200x900
  tvf render --example bumpy-torus field.npy -o field.png   (an example mesh in place of MESH)
  tvf render mesh.obj spline.npy -o spline.png --constraints constraints.json --style lic
  tvf render mesh.obj field.npy -o parts.png --parts   (field and its three Hodge parts)

Colours: magnitude and energy use a sequential map, divergence and curl a blue–white–red map
symmetric about 0. Divergence and curl are the decomposition's own pointwise operators at the
face centroid (conforming: div at vertices, curl at edge midpoints, averaged over the face's
three nodes); energy is the Dirichlet energy density (mean of div² over the face's nodes plus
mean of curl²), which integrates to xᵀSx. Constraint markers: vector orange (with its
direction), source red, sink blue, vortex green.";

fn view_arg(text: &str) -> Result<(f64, f64), String> {
    parse_view(text).map_err(|e| e.to_string())
}

fn size_arg(text: &str) -> Result<(u32, u32), String> {
    parse_size(text).map_err(|e| e.to_string())
}

/// Arguments of `tvf render`.
#[derive(Args)]
#[command(after_help = EXAMPLES)]
pub struct RenderArgs {
    #[command(flatten)]
    input: MeshInput,
    /// The field: one 3D vector per face (.npy F×3, or text `x y z` per line); omit to render
    /// the mesh alone.
    #[arg(value_name = "FIELD")]
    field: Option<PathBuf>,
    /// Output PNG file.
    #[arg(short, long, value_name = "OUT.png")]
    output: PathBuf,
    /// Per-face colour map: magnitude, divergence, curl, energy or none [default: magnitude with
    /// a field, none without].
    #[arg(long, value_name = "QUANTITY", value_parser = face_quantity_arg)]
    color: Option<FaceQuantity>,
    /// How the field is drawn: arrows, streamlines, lic or none.
    #[arg(long, value_name = "STYLE", default_value = "streamlines", value_parser = style_arg)]
    style: Style,
    /// Camera turn and elevation in degrees.
    #[arg(long, value_name = "YAW,PITCH", default_value = "30,20", value_parser = view_arg, allow_hyphen_values = true)]
    view: (f64, f64),
    /// Magnification over the automatic fit.
    #[arg(long, value_name = "FACTOR", default_value_t = 1.0)]
    zoom: f64,
    /// Image size in pixels.
    #[arg(long, value_name = "WxH", default_value = "1024x768", value_parser = size_arg)]
    size: (u32, u32),
    /// Overlay the constraints of this constraint file (JSON, see README).
    #[arg(long, value_name = "C.json")]
    constraints: Option<PathBuf>,
    /// Draw the field and its integrable, co-integrable and harmonic parts as a 2×2 grid (needs
    /// FIELD).
    #[arg(long)]
    parts: bool,
    /// Leave out the polygon edges drawn over a quad or polygon mesh (its faces are shaded
    /// through a display triangulation; the edges show the polygons). No effect on triangles.
    #[arg(long)]
    no_polygon_edges: bool,
    #[command(flatten)]
    discretization: DiscretizationFlags,
    /// Title printed at the top of the picture.
    #[arg(long, value_name = "TEXT")]
    title: Option<String>,
}

/// Renders the picture and writes the PNG.
pub fn run(mut args: RenderArgs, context: &RunContext) -> Result<()> {
    let field_path = args.input.optional_second(args.field.take(), "FIELD");
    let inputs = [field_path.as_deref(), args.constraints.as_deref()];
    check_file_output(&args.output, &args.input, &inputs)?;
    if args.parts && field_path.is_none() {
        usage_error(
            ErrorKind::MissingRequiredArgument,
            "--parts needs a FIELD to decompose".to_string(),
        );
    }
    if !(args.zoom.is_finite() && args.zoom > 0.0) {
        bail!("--zoom {}: must be a positive number", args.zoom);
    }
    let start = Instant::now();
    let mesh = args.input.load()?.mesh;
    let discretization = args
        .discretization
        .build(context.catalog(), &mesh, &args.input)?;
    let field = match &field_path {
        Some(path) => Some(read_field(path, discretization.require_sampling()?)?),
        None => None,
    };
    let color = Tint::Quantity(args.color.unwrap_or(if field.is_some() {
        FaceQuantity::Magnitude
    } else {
        FaceQuantity::None
    }));
    // The same checks as for splines: every index in range, values finite (errors name the
    // file and the constraint's id).
    let markers = match &args.constraints {
        Some(path) => constraint_file_markers(path, &mesh, discretization.as_ref(), args.size.1)?,
        None => Vec::new(),
    };
    let (width, height) = args.size;
    let view = |width, height| View {
        width,
        height,
        yaw: args.view.0,
        pitch: args.view.1,
        zoom: args.zoom,
    };
    let overlays = Overlays {
        markers,
        title: args.title.clone(),
        hide_polygon_edges: args.no_polygon_edges,
        ..Default::default()
    };
    let image = match (&field, args.parts) {
        (Some(field), true) => hodge_parts_grid(
            &mesh,
            discretization.as_ref(),
            field,
            (color, args.style),
            &overlays,
            view(width, height),
        )?,
        _ => draw_field(
            &mesh,
            discretization.as_ref(),
            field.as_deref(),
            color,
            args.style,
            overlays,
            view(width, height),
        )?,
    };
    save_png(&image, &args.output)?;
    note(format!(
        "rendered {} faces in {:.2} s",
        mesh.face_count(),
        start.elapsed().as_secs_f64()
    ));
    println!(
        "wrote {} ({}x{})",
        args.output.display(),
        image.width(),
        image.height()
    );
    Ok(())
}
