//! `tvf`: spectral processing of tangential vector fields on triangle meshes.
//!
//! Exit codes: 0 success, 1 bad input or failed computation, 2 usage error (clap).

mod commands;
mod examples;
mod mesh_input;

use clap::{Parser, Subcommand};

/// Spectral processing of tangential vector fields on triangle meshes.
#[derive(Parser)]
#[command(name = "tvf", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Report a mesh's counts, topology, angles and validation findings.
    Info(commands::info::InfoArgs),
    /// Write the paper's matrices (G, G*, M, M*, M_X, J, cotan, CR, S, B) as Matrix Market files.
    Operators(commands::operators::OperatorsArgs),
}

fn main() {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Info(args) => commands::info::run(args),
        Command::Operators(args) => commands::operators::run(args),
    };
    if let Err(error) = result {
        eprintln!("error: {error:#}");
        std::process::exit(1);
    }
}
