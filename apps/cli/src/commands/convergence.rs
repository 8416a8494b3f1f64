//! `tvf convergence`: chosen discretizations on refinement sequences of surfaces with exact
//! spectra (the unit sphere, the unit hemisphere under both boundary conditions; by triangles,
//! or by quads for discretizations that accept polygon meshes); the relative
//! eigenvalue errors per level, the observed orders and the basis times as a table, JSON and a
//! log–log plot. The study itself is [`tvf_convergence`].

use crate::context::RunContext;
use crate::progress::{note, Progress};
use anyhow::{bail, Context, Result};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use tvf_convergence::study::{run_convergence, Candidate, ConvergenceConfig, Surface};
use tvf_convergence::table::{markdown_table, orders_summary};
use tvf_core::discretization::BoundaryCondition;
use tvf_figures::convergence_plot::convergence_figure;
use tvf_render::save_png;

/// Arguments of `tvf convergence`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf convergence --discretization conforming-barycentric --discretization nonconforming-barycentric\n  \
tvf convergence --surface sphere --max-level 5 -o convergence.png --json\n  \
tvf convergence --discretization polygon-dec --surface quads\n\n\
Exact spectra: on the unit sphere every l(l+1) (l ≥ 1) with multiplicity 2l+1 in each family; on the \
upper unit hemisphere the family whose potentials are fixed (normal: integrable; tangential: \
co-integrable) has the Dirichlet spectrum (l+m odd, l per degree), the other the Neumann spectrum \
(l+m even, l+1 per degree). Errors are max |λ_h − λ|/λ over the lowest N eigenvalues of a family; \
the order is the least-squares slope of log error against log h over the levels (the coarsest \
dropped when there are three or more).\n\n\
With --json, prints {\"rows\": [{\"discretization\", \"surface\", \"boundary\", \"level\", \"faces\", \
\"h\", \"integrable_error\", \"cointegrable_error\", \"seconds\"}, ...], \"orders\": \
[{\"discretization\", \"surface\", \"boundary\", \"family\": \"integrable\"|\"cointegrable\", \
\"order\"}, ...]}."
)]
pub struct ConvergenceArgs {
    /// A catalog id to study (repeatable) [default: every entry of the catalog; on the quad
    /// surfaces every entry that accepts polygon meshes].
    #[arg(long = "discretization", value_name = "ID")]
    discretizations: Vec<String>,
    /// The surfaces: the sphere, the hemisphere (both boundary conditions), or all, meshed by
    /// triangles; or quad-sphere (cube-spheres of 6n² quads, n = 2^(level+1)), quad-hemisphere
    /// (their upper halves, both boundary conditions), or quads (both), for discretizations
    /// that accept polygon meshes; or jittered (irregular refinements of the sphere and the
    /// hemisphere).
    #[arg(long, value_enum, default_value_t = SurfaceChoice::All)]
    surface: SurfaceChoice,
    /// The coarsest refinement level (icosphere level; the hemisphere has 2·2^level rings).
    #[arg(long, value_name = "LEVEL", default_value_t = 1)]
    min_level: u32,
    /// The finest refinement level (level 4: 5,120 sphere and 6,144 hemisphere faces).
    #[arg(long, value_name = "LEVEL", default_value_t = 4)]
    max_level: u32,
    /// Eigenvalues compared per family (the lowest nonzero ones).
    #[arg(short = 'n', long, value_name = "N", default_value_t = 24)]
    eigenvalues: usize,
    /// Write the log–log plot (error against the number of faces, one colour per
    /// discretization, co-integrable series as plain lines, a grey order-2 reference).
    #[arg(short, long, value_name = "PNG")]
    output: Option<PathBuf>,
    /// Print JSON to stdout instead of the table.
    #[arg(long)]
    json: bool,
}

/// Which surfaces a study runs on.
#[derive(Clone, Copy, Debug, ValueEnum)]
enum SurfaceChoice {
    /// The unit sphere.
    Sphere,
    /// The unit hemisphere, tangential and normal boundary condition.
    Hemisphere,
    /// The sphere and the hemisphere.
    All,
    /// The unit sphere by cube-spheres (quads).
    QuadSphere,
    /// The unit hemisphere by upper halves of cube-spheres (quads), both boundary conditions.
    QuadHemisphere,
    /// The quad sphere and the quad hemisphere.
    Quads,
    /// Irregular refinements: the sphere and the hemisphere (both boundary conditions) with
    /// every vertex jittered by up to 0.3 of its shortest edge, back on the surface, made
    /// Delaunay by flips (a new draw per level).
    Jittered,
}

impl SurfaceChoice {
    fn surfaces(self) -> Vec<Surface> {
        let hemispheres = BoundaryCondition::ALL.into_iter().map(Surface::Hemisphere);
        let quad_hemispheres = BoundaryCondition::ALL
            .into_iter()
            .map(Surface::QuadHemisphere);
        match self {
            SurfaceChoice::Sphere => vec![Surface::Sphere],
            SurfaceChoice::Hemisphere => hemispheres.collect(),
            SurfaceChoice::All => Surface::all(),
            SurfaceChoice::QuadSphere => vec![Surface::QuadSphere],
            SurfaceChoice::QuadHemisphere => quad_hemispheres.collect(),
            SurfaceChoice::Quads => Surface::all_quads(),
            SurfaceChoice::Jittered => Surface::all_jittered(),
        }
    }
}

/// Runs the study and reports it.
pub fn run(args: ConvergenceArgs, context: &RunContext) -> Result<()> {
    if args.min_level > args.max_level {
        bail!(
            "--min-level {} is above --max-level {}",
            args.min_level,
            args.max_level
        );
    }
    if args.max_level > 7 {
        bail!(
            "--max-level {}: at most 7 (1.3 million sphere faces)",
            args.max_level
        );
    }
    if args.eigenvalues == 0 {
        bail!("-n 0: compare at least one eigenvalue per family");
    }
    if let Some(output) = &args.output {
        tvf_core::io::check_file_output(output, &[])?;
    }
    let catalog = context.catalog();
    let surfaces = args.surface.surfaces();
    let mut entries = catalog.selected(&args.discretizations)?;
    if surfaces.iter().any(|s| s.has_quads()) {
        if args.discretizations.is_empty() {
            entries.retain(|entry| !entry.needs_triangles());
        } else if let Some(entry) = entries.iter().find(|entry| entry.needs_triangles()) {
            bail!(
                "--surface {}: the discretization '{}' needs triangle meshes; the quad surfaces \
                 are for entries that accept polygons (polygon-dec)",
                args.surface
                    .to_possible_value()
                    .map_or_else(String::new, |v| v.get_name().to_string()),
                entry.id()
            );
        }
        if entries.is_empty() {
            bail!("no entry of the catalog accepts the polygon meshes of the quad surfaces");
        }
    }
    let candidates: Vec<Candidate<'_>> = entries.into_iter().map(Candidate::from_entry).collect();
    let config = ConvergenceConfig {
        surfaces,
        levels: (args.min_level..=args.max_level).collect(),
        eigenvalues: args.eigenvalues,
    };
    let progress = Progress::new("convergence");
    let report = run_convergence(&candidates, &config, &|done, total, row| {
        progress.update(&row.summary(), done, total)
    })?;
    progress.finish(format!("{} bases", report.rows.len()));
    if let Some(output) = &args.output {
        let figure = convergence_figure(&report, 640, 480)?;
        save_png(&figure, output).with_context(|| format!("cannot write {}", output.display()))?;
        note(format!("plot: {}", output.display()));
    }
    if args.json {
        // Through a `Value`, so the keys are sorted as in every JSON report of tvf.
        let report = serde_json::to_value(&report)?;
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", markdown_table(&report));
        println!();
        print!("{}", orders_summary(&report));
    }
    Ok(())
}
