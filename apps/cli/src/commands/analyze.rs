//! `tvf analyze`: a field's Fourier coefficients against frequency (the paper's Figure 8) and
//! the energy of each part of its Hodge decomposition.

use super::spectral_inputs::{exact_hodge_energies, read_field, FieldArgs};
use crate::context::RunContext;
use crate::output_rules::{commit, stage};
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;
use tvf_figures::spectral_folders::write_analysis_folder;
use tvf_spectral::{AnalysisReport, SpectralAnalysis};

/// Arguments of `tvf analyze`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf analyze bunny.obj field.npy --basis bunny.tvfb -o analysis/\n  tvf analyze bunny.obj field.npy -k 200 -o analysis/ --json   (basis computed once, then cached)\n\nWrites DIR/coefficients.csv (index, family, eigenvalue, frequency, coefficient), \
DIR/spectrum.png (|coefficient| against frequency √λ, integrable and co-integrable) and DIR/energy.json \
(squared M_X norms of the integrable, co-integrable, harmonic and rest parts, in the basis and in the exact \
Hodge decomposition)."
)]
pub struct AnalyzeArgs {
    #[command(flatten)]
    inputs: FieldArgs,
    /// Output folder (created if missing).
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    /// Print the energy report (the content of DIR/energy.json) to stdout as JSON instead of
    /// text.
    #[arg(long)]
    json: bool,
}

/// Runs the analysis and writes the three files.
pub fn run(mut args: AnalyzeArgs, context: &RunContext) -> Result<()> {
    let field_path = args.inputs.field_path_for(&args.output, &[])?;
    let inputs = args.inputs.load(context.catalog())?;
    let field = read_field(&field_path, inputs.fields()?)?;
    let setup = args
        .inputs
        .setup(context.catalog(), inputs, args.inputs.basis.size())?;
    let analysis = SpectralAnalysis::new(&setup.basis, &field)?;
    let hodge = exact_hodge_energies(setup.complex.as_ref(), &field)?;
    let report = AnalysisReport {
        mesh: &args.inputs.input.label(),
        field: &field_path,
        discretization: &setup.discretization,
        basis_fields: setup.basis.len(),
        analysis: &analysis,
        hodge: &hodge,
    };
    let json = serde_json::to_string_pretty(&report.to_json())?;
    let staged = stage(&args.output)?;
    write_analysis_folder(&staged, &analysis, &json)?;
    commit(staged)?;
    if args.json {
        println!("{json}");
        return Ok(());
    }
    print!("{}", report.text());
    let path = |name| args.output.join(name).display().to_string();
    println!(
        "wrote                 {}, {}, {}",
        path("coefficients.csv"),
        path("spectrum.png"),
        path("energy.json")
    );
    Ok(())
}
