//! `tvf discretizations`: the program's catalog, one entry per line.

use crate::context::RunContext;
use anyhow::Result;
use clap::Args;
use serde_json::json;
use tvf_discretizations::{CatalogEntry, DEFAULT_DISCRETIZATION};

/// Arguments of `tvf discretizations`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf discretizations\n  tvf discretizations --json\n\nEach line begins with the id that --discretization takes, then the description and the \
preconditions on the mesh. --decomposition NAME --mass MASS is a shorthand for the id NAME-MASS."
)]
pub struct DiscretizationsArgs {
    /// Print JSON to stdout: {"default": ID, "discretizations": [{"id", "description", "preconditions", "boundary_conditions", "boundary_meanings": {CONDITION: TEXT}, "builds_on_intrinsic"}, ...]}.
    #[arg(long)]
    json: bool,
}

/// Prints the catalog of `context`.
pub fn run(args: DiscretizationsArgs, context: &RunContext) -> Result<()> {
    if args.json {
        let entries: Vec<_> = context
            .catalog()
            .iter()
            .map(|e| {
                json!({
                    "id": e.id(),
                    "description": e.description(),
                    "preconditions": e.preconditions(),
                    "boundary_conditions": boundary_names(e),
                    "boundary_meanings": e
                        .boundary_conditions()
                        .iter()
                        .map(|&b| (b.name().to_string(), json!(e.boundary_meaning(b))))
                        .collect::<serde_json::Map<_, _>>(),
                    "builds_on_intrinsic": e.builds_on_intrinsic(),
                })
            })
            .collect();
        println!(
            "{}",
            json!({"default": DEFAULT_DISCRETIZATION, "discretizations": entries})
        );
        return Ok(());
    }
    for entry in context.catalog() {
        let default = if entry.id() == DEFAULT_DISCRETIZATION {
            " (default)"
        } else {
            ""
        };
        let intrinsic = if entry.builds_on_intrinsic() {
            " Builds on the intrinsic Delaunay triangulation of any mesh (--intrinsic-delaunay)."
        } else {
            ""
        };
        println!(
            "{}{default} — {}. Preconditions: {}. Boundary conditions on meshes with boundary: {}.{intrinsic}",
            entry.id(),
            entry.description(),
            entry.preconditions(),
            boundary_listing(entry)
        );
    }
    Ok(())
}

/// The boundary conditions an entry offers with what each fixes, the default first (`none` for
/// an entry that builds on closed meshes only).
fn boundary_listing(entry: &CatalogEntry) -> String {
    if entry.boundary_conditions().is_empty() {
        return "none (closed meshes only)".to_string();
    }
    entry
        .boundary_conditions()
        .iter()
        .map(|&b| {
            let fixes = entry.boundary_meaning(b).unwrap_or_default();
            format!("{} ({fixes})", b.name())
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The `--boundary` values an entry offers, the default first.
fn boundary_names(entry: &CatalogEntry) -> Vec<&'static str> {
    entry
        .boundary_conditions()
        .iter()
        .map(|b| b.name())
        .collect()
}
