//! Times the intrinsic Delaunay triangulation of a mesh, with its correspondence, against
//! loading and validating the same mesh (`tvf_core::io::load_mesh`, what `tvf info` does), in
//! the same process, alternating the two `--runs` times and reporting medians:
//!
//! - `load`: read, parse and validate the file;
//! - `flip`: build the intrinsic triangulation and flip it to Delaunay (the integer coordinates,
//!   i.e. the correspondence, are kept up to date by every flip);
//! - `overlay`: extract the common subdivision (trace every input edge, build the cells, the
//!   per-input-face overlap areas and the point-location index);
//! - `refine`: intrinsic Delaunay refinement, from the input (flips included).
//!
//! `cargo run --release -p tvf-core --example intrinsic_bench -- [MESH] [--runs N]` (default:
//! `../shared/meshes/armadillo-x4.obj`, 7 runs).

use std::path::PathBuf;
use std::time::Instant;
use tvf_core::intrinsic::{IntrinsicTriangulation, RefineOptions};

fn main() {
    let mut args = std::env::args().skip(1);
    let mut mesh: Option<PathBuf> = None;
    let mut runs = 7;
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--runs" => runs = args.next().and_then(|s| s.parse().ok()).unwrap_or(runs),
            other => mesh = Some(PathBuf::from(other)),
        }
    }
    let path = mesh.unwrap_or_else(|| {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/meshes/armadillo-x4.obj")
    });
    let mut times: [Vec<f64>; 4] = Default::default();
    let mut counts = String::new();
    for _ in 0..runs.max(1) {
        let start = Instant::now();
        let loaded = match tvf_core::io::load_mesh(&path) {
            Ok(loaded) => loaded,
            Err(error) => {
                eprintln!("intrinsic_bench: {error}");
                std::process::exit(1);
            }
        };
        let Ok(mesh) = loaded.mesh.into_triangles() else {
            eprintln!(
                "intrinsic_bench: {} has polygons; it needs triangles",
                path.display()
            );
            std::process::exit(1);
        };
        times[0].push(start.elapsed().as_secs_f64());

        let start = Instant::now();
        let flipped = IntrinsicTriangulation::new(&mesh).and_then(|mut tri| {
            let flips = tri.flip_to_delaunay()?;
            Ok((tri, flips))
        });
        times[1].push(start.elapsed().as_secs_f64());
        let (tri, flips) = flipped.unwrap_or_else(|error| fail(error));

        let start = Instant::now();
        let overlay = tri
            .common_subdivision(&mesh)
            .unwrap_or_else(|error| fail(error));
        times[2].push(start.elapsed().as_secs_f64());

        let start = Instant::now();
        let refined = IntrinsicTriangulation::new(&mesh).and_then(|mut tri| {
            let report = tri.refine(&mesh, RefineOptions::default())?;
            Ok(report)
        });
        times[3].push(start.elapsed().as_secs_f64());
        let report = refined.unwrap_or_else(|error| fail(error));
        counts = format!(
            "{} faces; {flips} flips; {} cells; refinement: {} flips, {} vertices inserted",
            mesh.face_count(),
            overlay.cell_count(),
            report.flips,
            report.inserted
        );
    }
    let [load, flip, overlay, refine] = times.map(median);
    println!("{}: {counts}", path.display());
    println!("medians over {runs} runs (seconds):");
    println!("  load + validate        {load:.4}");
    println!(
        "  intrinsic Delaunay     {flip:.4}   ratio to load {:.3}",
        flip / load
    );
    println!(
        "  + common subdivision   {:.4}   ratio to load {:.3}",
        flip + overlay,
        (flip + overlay) / load
    );
    println!(
        "  refine (from input)    {refine:.4}   ratio to load {:.3}",
        refine / load
    );
}

fn fail(error: tvf_core::intrinsic::IntrinsicError) -> ! {
    eprintln!("intrinsic_bench: {error}");
    std::process::exit(1);
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}
