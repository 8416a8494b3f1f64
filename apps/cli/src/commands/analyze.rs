//! `tvf analyze`: a field's Fourier coefficients against frequency (the paper's Figure 8) and
//! the energy of each part of its Hodge decomposition.

use super::spectral_inputs::{exact_hodge_energies, read_field, FieldArgs};
use crate::context::RunContext;
use crate::output_rules::{commit, stage};
use anyhow::{Context, Result};
use clap::Args;
use serde_json::json;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use tvf_core::io::write_atomically;
use tvf_figures::spectral_plots::spectrum_plot;
use tvf_render::save_png;
use tvf_spectral::{EnergySplit, SpectralAnalysis};

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

fn split_json(split: &EnergySplit) -> serde_json::Value {
    json!({
        "integrable": split.integrable,
        "cointegrable": split.cointegrable,
        "harmonic": split.harmonic,
        "rest": split.rest,
        "total": split.total(),
    })
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
    let exact = Some(exact_hodge_energies(setup.complex.as_ref(), &field)?);
    let staged = stage(&args.output)?;

    let csv = analysis.coefficients_csv();
    let csv_path = args.output.join("coefficients.csv");
    write_atomically(&staged.path().join("coefficients.csv"), |w| {
        w.write_all(csv.as_bytes())
    })
    .with_context(|| format!("cannot write {}", csv_path.display()))?;

    let mut report = json!({
        "mesh": args.inputs.input.label(),
        "field": field_path.display().to_string(),
        "discretization": setup.discretization,
        "basis_fields": setup.basis.len(),
        "field_energy": analysis.field_energy,
        "relative_rest_norm": analysis.relative_rest_norm(),
        "represented_dirichlet_energy": analysis.represented_dirichlet_energy,
        "basis": split_json(&analysis.energy),
    });
    if let Some(exact) = &exact {
        report["hodge"] = split_json(exact);
    }
    let json_path = args.output.join("energy.json");
    let json = serde_json::to_string_pretty(&report)?;
    write_atomically(&staged.path().join("energy.json"), |w| {
        w.write_all(json.as_bytes())
    })
    .with_context(|| format!("cannot write {}", json_path.display()))?;

    let png_path = args.output.join("spectrum.png");
    plot_spectrum(&analysis, &staged.path().join("spectrum.png"))
        .with_context(|| format!("cannot write {}", png_path.display()))?;
    commit(staged)?;

    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    let e = &analysis.energy;
    println!("field energy ‖v‖²     {:.6e}", analysis.field_energy);
    println!(
        "in the basis          integrable {:.6e}, co-integrable {:.6e}, harmonic {:.6e}, rest {:.6e}",
        e.integrable, e.cointegrable, e.harmonic, e.rest
    );
    if let Some(x) = &exact {
        println!(
            "Hodge decomposition   integrable {:.6e}, co-integrable {:.6e}, harmonic {:.6e}",
            x.integrable, x.cointegrable, x.harmonic
        );
    }
    println!(
        "wrote                 {}, {}, {}",
        csv_path.display(),
        png_path.display(),
        json_path.display()
    );
    Ok(())
}
/// The paper's Figure 8: |coefficient| against frequency for both families (log scale).
fn plot_spectrum(analysis: &SpectralAnalysis, path: &Path) -> Result<()> {
    let Some(plot) = spectrum_plot(analysis) else {
        anyhow::bail!("the field has no non-zero coefficient to plot");
    };
    save_png(&plot.render()?, path)?;
    Ok(())
}
