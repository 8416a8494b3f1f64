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
    /// Filter a field in its spectral basis (low-pass, high-pass, band-pass, cut-off, drawn curves).
    Filter(commands::filter::FilterArgs),
    /// Spectral analysis of a field: coefficients against frequency (CSV, PNG) and Hodge energies.
    Analyze(commands::analyze::AnalyzeArgs),
    /// Compress a field or a sequence of fields into a .tvfc file (64-bit or quantised coefficients).
    Compress(commands::compress::CompressArgs),
    /// Decompress a .tvfc file into fields.
    Decompress(commands::decompress::DecompressArgs),
    /// Rate–distortion curves of spectral compression (CSV and PNG plot).
    RateDistortion(commands::rate_distortion::RateDistortionArgs),
    /// The interactive spline editor in the browser: a local server on 127.0.0.1 serving a WebGL2 page.
    Edit(commands::edit::EditArgs),
}

fn main() {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Info(args) => commands::info::run(args),
        Command::Operators(args) => commands::operators::run(args),
        Command::Filter(args) => commands::filter::run(args),
        Command::Analyze(args) => commands::analyze::run(args),
        Command::Compress(args) => commands::compress::run(args),
        Command::Decompress(args) => commands::decompress::run(args),
        Command::RateDistortion(args) => commands::rate_distortion::run(args),
        Command::Edit(args) => commands::edit::run(args),
    };
    if let Err(error) = result {
        eprintln!("error: {error:#}");
        std::process::exit(1);
    }
}
