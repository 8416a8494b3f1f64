//! `tvf info`: a mesh report (counts, topology, angles, validation findings).

use crate::discretization_flags::IntrinsicDelaunayFlag;
use crate::mesh_input::MeshInput;
use anyhow::{bail, Context, Result};
use clap::Args;
use serde_json::{json, Value};
use std::time::Instant;
use tvf_core::discretization::BoundaryCondition;
use tvf_core::{SurfaceMesh, TriangleMesh};
use tvf_discretizations::face_geometry::FaceGeometry;
use tvf_discretizations::{
    edge_hodge_star, mesh_topology, IntrinsicDelaunay, IntrinsicInput, DELAUNAY_TOLERANCE,
};

/// What `--intrinsic-delaunay` ([`IntrinsicDelaunayFlag`]) does for `tvf info`: its help text.
const INTRINSIC_DELAUNAY_HELP: &str = "Also build the intrinsic Delaunay triangulation of the (triangle) mesh with its correspondence \
    — `flip` (the default) or `refine`, as --intrinsic-delaunay of the commands that build a \
    complex — and report it: flips, inserted vertices, edges, the edges still with cot α + cot β ≤ \
    1e-12, cells of the common subdivision, seconds";

/// Arguments of `tvf info`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf info bunny.obj\n  tvf info --example genus2 --json\n  tvf info bunny.obj --intrinsic-delaunay=refine",
    mut_arg("intrinsic_delaunay", |arg| arg.help(INTRINSIC_DELAUNAY_HELP))
)]
pub struct InfoArgs {
    #[command(flatten)]
    input: MeshInput,
    /// Print the report as one JSON object instead of text.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    intrinsic: IntrinsicDelaunayFlag,
}

/// Prints the report. JSON keys: `vertices` (referenced vertices, after dropping unreferenced
/// ones), `edges`, `faces`, `components`, `boundary_loops`, `genus`, `closed`, `min_angle_deg`,
/// `max_angle_deg`, `warnings` (messages), plus `source`, `file_vertices` (all vertices the
/// file lists), `unreferenced_vertices`, `duplicate_vertices`, `euler_characteristic`,
/// `component_genera`, `component_boundary_loops`, `harmonic_dimension` (per boundary condition,
/// `{"tangential": h, "normal": h}`: `2g` per closed component, `2g + b − 1` per component with
/// `b ≥ 1` boundary loops), `total_area`, `signed_volume`, `mesh_kind` (`triangles` or
/// `polygons`), `face_sizes` (faces per number of corners, `{"4": 96}`) and
/// `non_delaunay_edges` (triangle meshes: edges with `cot α + cot β ≤ 1e-12`, where DEC's `⋆1`
/// is refused and `--intrinsic-delaunay` helps; `null` on polygon meshes) and, with
/// `--intrinsic-delaunay`, `intrinsic_delaunay` (see [`intrinsic_summary`]; `null` without).
pub fn run(args: InfoArgs) -> Result<()> {
    let loaded = args.input.load()?;
    let (mesh, report) = (&loaded.mesh, &loaded.report);
    let non_delaunay = mesh.as_triangles().and_then(non_delaunay_edges);
    let intrinsic = intrinsic_report(&args, mesh)?;
    let face_sizes = mesh.face_size_counts();
    let warnings: Vec<String> = report.warnings.iter().map(|w| w.to_string()).collect();
    let loops = tvf_discretizations::component_boundary_loops(mesh);
    let harmonic: Vec<(BoundaryCondition, usize)> = BoundaryCondition::ALL
        .into_iter()
        .map(|b| (b, mesh_topology(mesh, b).harmonic_dimension))
        .collect();
    if args.json {
        let value = json!({
            "source": args.input.label(),
            "vertices": mesh.vertex_count(),
            "edges": mesh.edge_count(),
            "faces": mesh.face_count(),
            "mesh_kind": mesh.kind_name(),
            "face_sizes": face_sizes
                .iter()
                .map(|(size, count)| (size.to_string(), json!(count)))
                .collect::<serde_json::Map<_, _>>(),
            "components": mesh.component_count(),
            "boundary_loops": mesh.boundary_loops().len(),
            "genus": mesh.genus(),
            "closed": mesh.is_closed(),
            "min_angle_deg": report.min_angle_deg,
            "max_angle_deg": report.max_angle_deg,
            "warnings": warnings,
            "file_vertices": report.input_vertex_count,
            "unreferenced_vertices": report.unreferenced_vertices(),
            "duplicate_vertices": report.duplicate_vertices(),
            "euler_characteristic": mesh.euler_characteristic(),
            "component_genera": mesh.component_genera(),
            "component_boundary_loops": loops,
            "harmonic_dimension": harmonic
                .iter()
                .map(|(b, h)| (b.name().to_string(), json!(h)))
                .collect::<serde_json::Map<_, _>>(),
            "total_area": mesh.total_area(),
            "signed_volume": mesh.signed_volume(),
            "non_delaunay_edges": non_delaunay,
            "intrinsic_delaunay": intrinsic,
        });
        println!("{}", serde_json::to_string_pretty(&value)?);
        return Ok(());
    }
    println!("mesh           {}", args.input.label());
    println!("vertices       {}", mesh.vertex_count());
    println!("edges          {}", mesh.edge_count());
    if mesh.is_triangle_mesh() {
        println!("faces          {}", mesh.face_count());
    } else {
        let sizes: Vec<String> = face_sizes
            .iter()
            .map(|&(size, count)| format!("{} {count}", polygon_name(size)))
            .collect();
        println!(
            "faces          {} ({})",
            mesh.face_count(),
            sizes.join(", ")
        );
    }
    println!("components     {}", mesh.component_count());
    println!("boundary loops {}", mesh.boundary_loops().len());
    println!("genus          {}", mesh.genus());
    if mesh.is_closed() {
        println!("harmonic       {} (2g)", harmonic[0].1);
    } else {
        let per_condition: Vec<String> = harmonic
            .iter()
            .map(|(b, h)| format!("{h} ({})", b.name()))
            .collect();
        println!(
            "harmonic       {} (2g + b − 1 per component with boundary; loops per component {loops:?})",
            per_condition.join(", ")
        );
    }
    println!(
        "closed         {}",
        if mesh.is_closed() { "yes" } else { "no" }
    );
    println!(
        "angles         {:.3}° .. {:.3}°",
        report.min_angle_deg, report.max_angle_deg
    );
    print_delaunay_lines(non_delaunay, intrinsic.as_ref());
    if warnings.is_empty() {
        println!("warnings       none");
    }
    for warning in &warnings {
        println!("warning        {warning}");
    }
    Ok(())
}

/// The `--intrinsic-delaunay` summary of `mesh` ([`intrinsic_summary`]), `None` without the
/// flag; an error on a polygon mesh.
fn intrinsic_report(args: &InfoArgs, mesh: &SurfaceMesh) -> Result<Option<Value>> {
    match (args.intrinsic.intrinsic_delaunay, mesh.as_triangles()) {
        (Some(mode), Some(triangles)) => Ok(Some(
            intrinsic_summary(triangles, mode)
                .with_context(|| format!("{}: --intrinsic-delaunay", args.input.label()))?,
        )),
        (Some(_), None) => bail!(
            "{}: --intrinsic-delaunay needs a triangle mesh (triangulate it first: tvf \
             triangulate MESH -o OUT)",
            args.input.label()
        ),
        (None, _) => Ok(None),
    }
}

/// The report's `delaunay` line (triangle meshes) and `intrinsic` line (with the flag).
fn print_delaunay_lines(non_delaunay: Option<usize>, intrinsic: Option<&Value>) {
    match non_delaunay {
        Some(0) => println!("delaunay       yes (cot α + cot β > 0 on every edge)"),
        Some(count) => println!(
            "delaunay       no: {count} edges have cot α + cot β ≤ {DELAUNAY_TOLERANCE:e} (DEC \
             refuses them; --intrinsic-delaunay builds on the intrinsic Delaunay triangulation)"
        ),
        None => {}
    }
    if let Some(summary) = intrinsic {
        println!(
            "intrinsic      {} flips, {} inserted vertices, {} edges, {} with cot α + cot β ≤ 1e-12, {} cells of the common subdivision ({:.3} s)",
            summary["flips"], summary["inserted_vertices"], summary["edges"],
            summary["not_positive_edges"], summary["cells"], summary["seconds"].as_f64().unwrap_or(0.0)
        );
    }
}

/// Number of edges of `mesh` with `cot α + cot β ≤` [`DELAUNAY_TOLERANCE`] (DEC's test);
/// `None` if a face is degenerate.
fn non_delaunay_edges(mesh: &TriangleMesh) -> Option<usize> {
    let geometry = FaceGeometry::new(mesh).ok()?;
    let star = edge_hodge_star(mesh, &geometry);
    Some(
        star.iter()
            .filter(|&&s| 2.0 * s <= DELAUNAY_TOLERANCE)
            .count(),
    )
}

/// The intrinsic Delaunay triangulation of `mesh` made by `mode`, with its common subdivision,
/// as JSON: `mode`, `flips`, `inserted_vertices`, `vertices`, `edges`, `faces`,
/// `not_positive_edges` (cot α + cot β ≤ [`DELAUNAY_TOLERANCE`]: cocircular or boundary edges
/// that DEC refuses under `flip`), `cells` and `seconds` (building both).
fn intrinsic_summary(mesh: &TriangleMesh, mode: IntrinsicDelaunay) -> Result<Value> {
    let start = Instant::now();
    let input = IntrinsicInput::new(mesh, mode)?;
    let seconds = start.elapsed().as_secs_f64();
    let tri = &input.triangulation;
    let not_positive = tri
        .cotan_sums()
        .iter()
        .filter(|&&s| s <= DELAUNAY_TOLERANCE)
        .count();
    Ok(json!({
        "mode": mode.name(),
        "flips": tri.flip_count(),
        "inserted_vertices": tri.inserted_vertex_count(),
        "vertices": tri.vertex_count(),
        "edges": tri.edge_count(),
        "faces": tri.face_count(),
        "not_positive_edges": not_positive,
        "cells": input.overlay.cell_count(),
        "seconds": seconds,
    }))
}

/// The plural name of polygons with `corners` corners: `triangles`, `quads`, `pentagons`,
/// `hexagons`, then `7-gons`, `8-gons` ….
fn polygon_name(corners: usize) -> String {
    match corners {
        3 => "triangles".to_string(),
        4 => "quads".to_string(),
        5 => "pentagons".to_string(),
        6 => "hexagons".to_string(),
        n => format!("{n}-gons"),
    }
}
