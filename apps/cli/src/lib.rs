//! `tvf` as a library: [`run`] parses the command line and runs a subcommand with the
//! discretizations of a [`Catalog`]. The `tvf` binary is `tvf_cli::run(Catalog::builtin())`; a
//! crate of your own adds its entries first and gets every subcommand for them (see
//! `examples/own-discretization`):
//!
//! ```no_run
//! use tvf_discretizations::Catalog;
//!
//! fn main() -> std::process::ExitCode {
//!     tvf_cli::run(Catalog::builtin())
//! }
//! ```
//!
//! Exit codes: 0 success, 1 bad input or failed computation, 2 usage error (clap; an id that is
//! not in the catalog is one).

mod basis_file_progress;
mod basis_source;
mod commands;
mod context;
mod discretization_flags;
mod interrupt;
mod mesh_input;
mod output_rules;
mod picture_options;
mod progress;
mod report;
mod test_faults;

use clap::{CommandFactory, FromArgMatches, Subcommand};
use std::process::ExitCode;
use tvf_discretizations::Catalog;

use context::RunContext;

/// Spectral processing of tangential vector fields on triangle and polygon meshes.
#[derive(clap::Parser)]
#[command(name = "tvf", version, about, long_about = None)]
struct Cli {
    /// No progress bars and no notes on stderr (warnings and errors are still shown).
    #[arg(short, long, global = true)]
    quiet: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Report a mesh's counts, topology, angles and validation findings.
    Info(commands::info::InfoArgs),
    /// Split every polygon of a mesh into triangles by its own corners and write it (.obj, .ply).
    Triangulate(commands::triangulate::TriangulateArgs),
    /// List the discretizations of the catalog (ids for --discretization).
    Discretizations(commands::discretizations::DiscretizationsArgs),
    /// Check a discretization: the conformance checks on a mesh, or on generated meshes with the minimal failing one written as OBJ.
    Check(commands::check::CheckArgs),
    /// Compute the Fourier basis (harmonic fields + K pairs of eigenfields) and save it (.tvfb).
    Basis(commands::basis::BasisArgs),
    /// The lowest K eigenvalues of the Hodge–Laplacian on tangent fields, labelled by family.
    Spectrum(commands::spectrum::SpectrumArgs),
    /// Discretizations side by side on one mesh: basis times, eigenvalues, shared eigenfields.
    Compare(commands::compare::CompareArgs),
    /// Hodge decomposition of a field: integrable, co-integrable and harmonic parts, potentials.
    Decompose(commands::decompose::DecomposeArgs),
    /// Fourier coefficients of a field in a basis file, and the rest field's share.
    Coefficients(commands::coefficients::CoefficientsArgs),
    /// Write a discretization's matrices (d0, d1, M0, M1, M2, S0, S2, S, B, J) as Matrix Market files.
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
    /// A tangential vector field spline (hard constraints) from a JSON constraint file.
    Spline(commands::spline::SplineArgs),
    /// Soft-constrained field design (Fisher et al.), full or reduced, from a JSON constraint file.
    Design(commands::design::DesignArgs),
    /// Convergence against exact spectra (unit sphere, hemisphere): errors, orders, times, plot.
    Convergence(commands::convergence::ConvergenceArgs),
    /// Render a mesh and a field to PNG (colour map, arrows, streamlines or LIC, constraints).
    Render(commands::render::RenderArgs),
    /// Export a mesh and a field as VTK, PLY (per-face data) or OBJ (streamlines as polylines).
    Export(commands::export::ExportArgs),
    /// The tour: a web page of pictures and numbers on a generated bumpy torus (no input needed).
    Demo(commands::demo::DemoArgs),
    /// The interactive spline editor in the browser: a local server on 127.0.0.1 serving a WebGL2 page.
    Edit(commands::edit::EditArgs),
}

/// Runs the subcommand of the process's command line with the discretizations of `catalog`
/// (every `--discretization` id is looked up there, basis files reopen through it, `tvf
/// discretizations` lists it) and returns the exit code; a usage error (clap, or an id the
/// catalog does not know) ends the process with code 2 and the usage message.
pub fn run(catalog: Catalog) -> ExitCode {
    interrupt::install();
    test_faults::install();
    let mut command = Cli::command();
    let matches = command
        .try_get_matches_from_mut(std::env::args_os())
        .unwrap_or_else(|error| match cache_flag_refusal(&error, &command) {
            Some(message) => {
                eprintln!("error: {message}");
                std::process::exit(2)
            }
            None => error.exit(),
        });
    if let Err(error) = discretization_flags::check_ids(&mut command, &matches, &catalog) {
        error.exit();
    }
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|error| error.exit());
    if !matches!(cli.command, Command::Edit(_)) {
        interrupt::end_quietly_on_closed_pipe();
    }
    progress::set_quiet(cli.quiet);
    if let Err(message) = slice_memory_from_environment() {
        eprintln!("error: {message}");
        return ExitCode::FAILURE;
    }
    let context = RunContext::new(catalog);
    let context = &context;
    let result = match cli.command {
        Command::Info(args) => commands::info::run(args),
        Command::Triangulate(args) => commands::triangulate::run(args),
        Command::Discretizations(args) => commands::discretizations::run(args, context),
        Command::Basis(args) => commands::basis::run(args, context),
        Command::Spectrum(args) => commands::spectrum::run(args, context),
        Command::Compare(args) => commands::compare::run(args, context),
        Command::Decompose(args) => commands::decompose::run(args, context),
        Command::Coefficients(args) => commands::coefficients::run(args, context),
        Command::Operators(args) => commands::operators::run(args, context),
        Command::Filter(args) => commands::filter::run(args, context),
        Command::Analyze(args) => commands::analyze::run(args, context),
        Command::Compress(args) => commands::compress::run(args, context),
        Command::Decompress(args) => commands::decompress::run(args, context),
        Command::RateDistortion(args) => commands::rate_distortion::run(args, context),
        Command::Spline(args) => commands::spline::run(args, context),
        Command::Design(args) => commands::design::run(args, context),
        Command::Check(args) => commands::check::run(args, context),
        Command::Convergence(args) => commands::convergence::run(args, context),
        Command::Render(args) => commands::render::run(args, context),
        Command::Export(args) => commands::export::run(args, context),
        Command::Demo(args) => commands::demo::run(args, context),
        Command::Edit(args) => commands::edit::run(args, context),
    };
    interrupt::yield_to_interruption();
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {}", error_message(&error));
            ExitCode::FAILURE
        }
    }
}

/// Environment variable with the memory the eigensolver's concurrent spectrum slices may take
/// (bytes, e.g. `6G`; default a sixth of the physical memory, see
/// `tvf_solvers::EigenOptions::slice_memory`).
const SLICE_MEMORY_VARIABLE: &str = "TVF_SLICE_MEMORY";

/// Makes [`SLICE_MEMORY_VARIABLE`], when set, the eigensolver's default budget; a value that is
/// not a positive number of bytes is an error naming it.
fn slice_memory_from_environment() -> Result<(), String> {
    let Some(raw) = std::env::var_os(SLICE_MEMORY_VARIABLE) else {
        return Ok(());
    };
    let value = raw.to_string_lossy();
    let bytes = tvf_spectral::parse_byte_count(&value).ok_or_else(|| {
        format!(
            "environment variable {SLICE_MEMORY_VARIABLE} = '{value}': a positive number of \
             bytes with an optional binary suffix, e.g. 6G, 512M or 1073741824"
        )
    })?;
    tvf_spectral::set_default_slice_memory(Some(bytes));
    Ok(())
}

/// For `--no-cache` or `--cache-dir` given to a subcommand that keeps no basis cache, a clear
/// refusal naming the subcommands that do (clap's own message suggests `-- --no-cache`, a
/// positional argument).
fn cache_flag_refusal(error: &clap::Error, command: &clap::Command) -> Option<String> {
    use clap::error::{ContextKind, ContextValue};
    if error.kind() != clap::error::ErrorKind::UnknownArgument {
        return None;
    }
    let Some(ContextValue::String(argument)) = error.get(ContextKind::InvalidArg) else {
        return None;
    };
    let flag = argument.split('=').next().unwrap_or_default();
    if flag != "--no-cache" && flag != "--cache-dir" {
        return None;
    }
    let given: Vec<String> = std::env::args_os()
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    let subcommand = command
        .get_subcommands()
        .find(|s| given.iter().any(|a| a == s.get_name()))
        .map_or("this subcommand".to_string(), |s| {
            format!("tvf {}", s.get_name())
        });
    let caching: Vec<&str> = command
        .get_subcommands()
        .filter(|s| s.get_arguments().any(|a| a.get_id() == "no_cache"))
        .map(|s| s.get_name())
        .collect();
    Some(format!(
        "{flag}: {subcommand} keeps no basis cache (it computes what it needs every time), so \
         there is nothing to turn off or move; leave {flag} out. The subcommands that reuse a \
         cached basis take it: {}",
        caching.join(", ")
    ))
}

/// The error and its causes, joined by `": "`, leaving out a cause whose text the message
/// already holds (typed errors often print their source themselves).
pub(crate) fn error_message(error: &anyhow::Error) -> String {
    let mut message = String::new();
    for cause in error.chain() {
        let text = cause.to_string();
        if message.contains(&text) {
            continue;
        }
        if !message.is_empty() {
            message.push_str(": ");
        }
        message.push_str(&text);
    }
    message
}
