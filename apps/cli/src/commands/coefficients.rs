//! `tvf coefficients`: the Fourier coefficients α, β, γ of a field in a saved basis, and the rest
//! field's share.

use super::spectral_inputs::{read_field, FieldArgs};
use crate::context::RunContext;
use anyhow::Result;
use clap::Args;
use serde_json::json;
use tvf_spectral::{FieldFamily, FourierAnalysis};

/// Arguments of `tvf coefficients`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf coefficients bunny.obj field.npy --basis bunny.tvfb --json\n  tvf coefficients bunny.obj field.npy -k 100\n\nCoefficients are M_X inner products with the M_X-orthonormal basis fields \
(α: integrable, β: co-integrable, γ: harmonic). With --json, prints {\"coefficients\": [{index, \
family, eigenvalue, frequency, coefficient}...], \"alpha\", \"beta\", \"gamma\", \"norm\", \
\"relative_rest_norm\"} to stdout."
)]
pub struct CoefficientsArgs {
    #[command(flatten)]
    inputs: FieldArgs,
    /// Print JSON to stdout instead of a table.
    #[arg(long)]
    json: bool,
}

/// Computes and prints the coefficients.
pub fn run(mut args: CoefficientsArgs, context: &RunContext) -> Result<()> {
    let field = args.inputs.field_path();
    let inputs = args.inputs.load(context.catalog())?;
    let field = read_field(&field, inputs.fields()?)?;
    let setup = args
        .inputs
        .setup(context.catalog(), inputs, args.inputs.basis.size())?;
    let analysis = FourierAnalysis::new(&setup.basis, &field)?;
    let basis = &setup.basis;
    if args.json {
        let entries: Vec<_> = analysis
            .coefficients
            .iter()
            .zip(basis.eigenvalues())
            .zip(basis.families())
            .enumerate()
            .map(|(index, ((&c, &lambda), family))| {
                json!({
                    "index": index,
                    "family": family.name(),
                    "eigenvalue": lambda,
                    "frequency": lambda.sqrt(),
                    "coefficient": c,
                })
            })
            .collect();
        let pairs = |list: &[(f64, f64)]| list.iter().map(|&(_, c)| c).collect::<Vec<_>>();
        let out = json!({
            "mesh": args.inputs.input.label(),
            "discretization": setup.discretization,
            "coefficients": entries,
            "alpha": pairs(&analysis.alpha),
            "beta": pairs(&analysis.beta),
            "gamma": analysis.gamma,
            "norm": analysis.norm,
            "relative_rest_norm": analysis.relative_rest_norm,
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        println!(
            "{:>6}  {:<12}  {:>14}  {:>14}  {:>22}",
            "index", "family", "eigenvalue", "frequency", "coefficient"
        );
        for (index, ((&c, &lambda), family)) in analysis
            .coefficients
            .iter()
            .zip(basis.eigenvalues())
            .zip(basis.families())
            .enumerate()
        {
            println!(
                "{index:>6}  {:<12}  {lambda:>14.6e}  {:>14.6e}  {c:>22.15e}",
                family.name(),
                lambda.sqrt()
            );
        }
        let norm2 = analysis.norm * analysis.norm;
        for family in [
            FieldFamily::Integrable,
            FieldFamily::Cointegrable,
            FieldFamily::Harmonic,
        ] {
            let energy = analysis.family_energy(family);
            println!(
                "{:<12} energy {energy:.6e} ({:.2} %)",
                family.name(),
                if norm2 > 0.0 {
                    100.0 * energy / norm2
                } else {
                    0.0
                }
            );
        }
        println!(
            "rest field: relative L2 norm {:.6e}",
            analysis.relative_rest_norm
        );
    }
    Ok(())
}
