//! `tvf discretizations`: the catalog, one entry per line.

use anyhow::Result;
use clap::Args;
use serde_json::json;
use tvf_discretizations::{catalog, DEFAULT_DISCRETIZATION};

/// Arguments of `tvf discretizations`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf discretizations\n  tvf discretizations --json\n\nEach line begins with the id that --discretization takes, then the description and the \
preconditions on the mesh. --decomposition NAME --mass MASS is a shorthand for the id NAME-MASS."
)]
pub struct DiscretizationsArgs {
    /// Print JSON to stdout: {"default": ID, "discretizations": [{"id", "description", "preconditions", "boundary_conditions", "boundary_meanings": {CONDITION: TEXT}}, ...]}.
    #[arg(long)]
    json: bool,
}

/// Prints the catalog.
pub fn run(args: DiscretizationsArgs) -> Result<()> {
    if args.json {
        let entries: Vec<_> = catalog()
            .iter()
            .map(|e| {
                json!({
                    "id": e.id,
                    "description": e.description,
                    "preconditions": e.preconditions,
                    "boundary_conditions": boundary_names(e),
                    "boundary_meanings": e
                        .boundary_conditions
                        .iter()
                        .map(|&b| (b.name().to_string(), json!(e.boundary_meaning(b))))
                        .collect::<serde_json::Map<_, _>>(),
                })
            })
            .collect();
        println!(
            "{}",
            json!({"default": DEFAULT_DISCRETIZATION, "discretizations": entries})
        );
        return Ok(());
    }
    for entry in catalog() {
        let default = if entry.id == DEFAULT_DISCRETIZATION {
            " (default)"
        } else {
            ""
        };
        println!(
            "{}{default} — {}. Preconditions: {}. Boundary conditions on meshes with boundary: {}.",
            entry.id,
            entry.description,
            entry.preconditions,
            entry
                .boundary_conditions
                .iter()
                .map(|&b| format!("{} ({})", b.name(), entry.boundary_meaning(b)))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(())
}

/// The `--boundary` values an entry offers, the default first.
fn boundary_names(entry: &tvf_discretizations::CatalogEntry) -> Vec<&'static str> {
    entry.boundary_conditions.iter().map(|b| b.name()).collect()
}
