//! `tvf-papers`: regenerate a paper's tables and figures with one command.
//!
//! ```text
//! cargo run --release -p tvf-papers -- brandt2017 --meshes ../shared/meshes --out DIR [--large] [--quiet]
//! ```
#![forbid(unsafe_code)]

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;
use tvf_papers::brandt2017::{self, report::RunInfo, Config, Sizes};
use tvf_papers::step_log::StepLog;

/// Reproduce papers' tables and figures with tvf.
#[derive(Debug, Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    paper: Paper,
}

#[derive(Debug, Subcommand)]
enum Paper {
    /// Brandt et al. 2017, "Spectral Processing of Tangential Vector Fields": Table 1,
    /// Figures 1 and 7–11, the sequence compression and the discretization comparison.
    ///
    /// Example: tvf-papers brandt2017 --meshes ../shared/meshes --out papers/brandt2017
    Brandt2017 {
        /// Folder with the paper's meshes (hand.obj, rocker-arm.obj, bunny-closed.obj,
        /// bumpy-torus.obj, bumpy-torus-x4.obj; with --large also armadillo-x4.obj).
        /// Missing meshes are reported and skipped.
        #[arg(long)]
        meshes: PathBuf,
        /// Output folder for RESULTS.md, README.md and the pictures.
        #[arg(long)]
        out: PathBuf,
        /// Also run the largest paper-scale mesh (armadillo-x4): Table 1 only, long.
        #[arg(long)]
        large: bool,
        /// No progress lines on stderr.
        #[arg(long, short)]
        quiet: bool,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.paper {
        Paper::Brandt2017 {
            meshes,
            out,
            large,
            quiet,
        } => {
            let progress = StepLog::new(quiet);
            let config = Config {
                meshes: meshes.clone(),
                out: out.clone(),
                large,
                sizes: Sizes::paper(),
            };
            let command = format!(
                "cargo run --release -p tvf-papers -- brandt2017 --meshes {} --out {}{}",
                meshes.display(),
                out.display(),
                if large { " --large" } else { "" }
            );
            let info = RunInfo {
                command,
                threads: rayon::current_num_threads(),
            };
            let outcome = brandt2017::run(&config, &progress)
                .and_then(|results| brandt2017::report::write(&out, &results, &info));
            match outcome {
                Ok(()) => {
                    progress.note(format!("done: {}", out.join("RESULTS.md").display()));
                    ExitCode::SUCCESS
                }
                Err(error) => {
                    eprintln!("error: {error}");
                    ExitCode::FAILURE
                }
            }
        }
    }
}
