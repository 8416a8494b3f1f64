//! `tvf coefficients`: the Fourier coefficients α, β, γ of a field in a saved basis, and the rest
//! field's share.

use super::spectral_inputs::{read_field, FieldArgs};
use crate::context::RunContext;
use anyhow::Result;
use clap::Args;
use serde_json::json;
use tvf_spectral::FourierAnalysis;

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
    let setup =
        args.inputs
            .projection_basis(context.catalog(), inputs, args.inputs.basis.size())?;
    let analysis = FourierAnalysis::new(setup.basis(), &field)?;
    if args.json {
        let mut out = analysis.to_json(setup.basis());
        out["mesh"] = json!(args.inputs.input.label());
        out["discretization"] = json!(setup.discretization());
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        print!("{}", analysis.table(setup.basis()));
    }
    Ok(())
}
