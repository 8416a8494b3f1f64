//! `tvf triangulate`: a polygon mesh written as the triangle mesh of the same vertices, every
//! polygon split by its own corners ([`tvf_core::SurfaceMesh::triangulated`]), for the entries
//! that need triangles.

use crate::mesh_input::MeshInput;
use crate::output_rules::check_output;
use crate::report::Report;
use anyhow::{bail, Context, Result};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `tvf triangulate`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf triangulate quads.obj -o triangles.obj\n  tvf triangulate --example quad-torus -o torus.ply\n\nEvery polygon of n corners becomes n − 2 triangles of its own corners (ear clipping seen \
along its vector area, orientation kept); no vertex is added, so vertex numbers and per-vertex \
data carry over (unreferenced vertices of the file are dropped, as on every load). A triangle \
mesh is written unchanged. The same split is what --triangulate does on every command."
)]
pub struct TriangulateArgs {
    #[command(flatten)]
    input: MeshInput,
    /// Output mesh (.obj or .ply), written atomically.
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,
    /// Print the counts as JSON (`source`, `output`, `vertices`, `polygons`, `triangles`).
    #[arg(long)]
    json: bool,
}

/// Loads the mesh, triangulates it and writes it.
pub fn run(args: TriangulateArgs) -> Result<()> {
    let extension = args
        .output
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if !matches!(extension.as_deref(), Some("obj" | "ply")) {
        bail!(
            "{}: unknown output format (expected .obj or .ply)",
            args.output.display()
        );
    }
    check_output(&args.output, &args.input, &[])?;
    let loaded = args.input.load()?;
    let polygons = (0..loaded.mesh.face_count())
        .filter(|&f| loaded.mesh.face_size(f) > 3)
        .count();
    let triangles = loaded
        .mesh
        .triangulated()
        .with_context(|| format!("{}: cannot triangulate", args.input.label()))?;
    tvf_core::io::save_mesh(&args.output, &triangles)?;
    let mut report = Report::new(args.json);
    report.line(format!(
        "{}: {polygons} polygons split, {} triangles on {} vertices written to {}",
        args.input.label(),
        triangles.face_count(),
        triangles.vertex_count(),
        args.output.display()
    ));
    report.set("source", args.input.label());
    report.set("output", args.output.display().to_string());
    report.set("vertices", triangles.vertex_count());
    report.set("polygons", polygons);
    report.set("triangles", triangles.face_count());
    report.finish()
}
