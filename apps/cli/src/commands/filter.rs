//! `tvf filter`: scale a field's Fourier coefficients by functions of frequency.

use super::spectral_inputs::{read_field, FieldArgs};
use crate::context::RunContext;
use crate::report::Report;
use anyhow::{bail, Result};
use clap::Args;
use std::path::{Path, PathBuf};
use tvf_spectral::{check_computed_field, write_tangent_field, FrequencyResponse, SpectralFilter};

const SPEC_HELP: &str = "Examples:\n  tvf filter bunny.obj noisy.npy --basis bunny.tvfb --integrable lowpass:t=0.01 --cointegrable lowpass:t=0.01 -o smooth.npy\n  tvf filter bunny.obj field.npy -k 200 --cointegrable cutoff:f=8 --rest 0 -o filtered.npy\n\nSPEC: identity | lowpass:t=T (gain e^(-t·λ)) | highpass:t=T (2 - e^(-t·λ)) | \
bandpass:lo=A,hi=B (1 for A ≤ √λ ≤ B) | cutoff:f=F (1 for √λ ≤ F) | curve:F,G;F,G;... (piecewise linear \
gain G at frequency F = √λ, constant beyond the ends) | @FILE.json ({\"points\": [[F, G], ...]})";

/// Arguments of `tvf filter`.
#[derive(Args)]
#[command(after_help = SPEC_HELP)]
pub struct FilterArgs {
    #[command(flatten)]
    inputs: FieldArgs,
    /// Gain of the integrable (curl-free) coefficients against frequency √λ.
    #[arg(long, value_name = "SPEC", default_value = "identity", value_parser = spec_syntax)]
    integrable: String,
    /// Gain of the co-integrable (divergence-free) coefficients against frequency √λ.
    #[arg(long, value_name = "SPEC", default_value = "identity", value_parser = spec_syntax)]
    cointegrable: String,
    /// Gain of the harmonic part.
    #[arg(long, value_name = "GAIN", default_value_t = 1.0)]
    harmonic: f64,
    /// Gain of the rest field (the part the truncated basis cannot represent, all above its
    /// highest frequency) [default: the filters' gain at the basis's highest frequency, the
    /// larger of the two families': 1 for identity filters, so the field comes back unchanged;
    /// near 0 for a low-pass, which removes the unrepresented high frequencies].
    #[arg(long, value_name = "GAIN")]
    rest: Option<f64>,
    /// Output field file (.npy or text, by extension).
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,
    /// Print the report (basis size, norms) as one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// Checks a SPEC's syntax while parsing the command line (a malformed SPEC is a usage error);
/// `@FILE.json` is read later, so that a missing or bad file is bad input (exit code 1).
fn spec_syntax(spec: &str) -> Result<String, String> {
    if spec.starts_with('@') {
        return Ok(spec.to_string());
    }
    spec.parse::<FrequencyResponse>()
        .map(|_| spec.to_string())
        .map_err(|e| e.to_string())
}

/// The curve file of a `@FILE.json` SPEC, if it is one.
fn curve_file(spec: &str) -> Option<&Path> {
    spec.strip_prefix('@').map(Path::new)
}

/// The response of `--{flag} SPEC`; errors name the flag (and the file of `@FILE.json`).
fn response(flag: &str, spec: &str) -> Result<FrequencyResponse> {
    spec.parse::<FrequencyResponse>()
        .map_err(|e| anyhow::anyhow!("--{flag} {spec}: {e}"))
}

/// Filters the field and writes the result.
pub fn run(mut args: FilterArgs, context: &RunContext) -> Result<()> {
    let curves = [curve_file(&args.integrable), curve_file(&args.cointegrable)];
    let field = args.inputs.field_path_for_file(&args.output, &curves)?;
    for (name, gain) in [("--harmonic", Some(args.harmonic)), ("--rest", args.rest)] {
        let Some(gain) = gain else { continue };
        if !gain.is_finite() || gain < 0.0 {
            bail!("{name} {gain}: a gain must be a finite number ≥ 0");
        }
    }
    let integrable = response("integrable", &args.integrable)?;
    let cointegrable = response("cointegrable", &args.cointegrable)?;
    let inputs = args.inputs.load(context.catalog())?;
    let field = read_field(&field, inputs.fields()?)?;
    let setup =
        args.inputs
            .projection_basis(context.catalog(), inputs, args.inputs.basis.size())?;
    let basis = setup.basis();
    let rest_gain = args
        .rest
        .unwrap_or_else(|| SpectralFilter::continued_rest_gain(&integrable, &cointegrable, basis));
    let filter = SpectralFilter {
        integrable,
        cointegrable,
        harmonic_gain: args.harmonic,
        rest_gain,
    };
    let filtered = filter.apply(basis, &field)?;
    let cause = format!(
        "the gains times the field's coefficients overflow f64 arithmetic: --integrable {}, \
         --cointegrable {}, --harmonic {}, --rest {rest_gain}",
        args.integrable, args.cointegrable, args.harmonic
    );
    check_computed_field(&filtered.field, "the filtered field", &cause)?;
    let norm = |v: &[f64]| basis.inner_product(v, v).sqrt();
    let (input_norm, output_norm) = (norm(&field), norm(&filtered.field));
    if !output_norm.is_finite() {
        bail!(
            "the norm of the filtered field overflows f64 arithmetic ({cause}); nothing was \
             written"
        );
    }
    write_tangent_field(&args.output, setup.fields()?, &filtered.field)?;
    let mut report = Report::new(args.json);
    report.line(format!(
        "basis          {} fields ({})",
        basis.len(),
        setup.discretization()
    ));
    report.line(format!("input norm     {input_norm:.6e}"));
    report.line(format!("rest norm      {:.6e}", filtered.rest_norm));
    report.line(format!(
        "rest gain      {rest_gain:.6e}{}",
        if args.rest.is_some() {
            ""
        } else {
            " (the filters' gain at the basis's highest frequency)"
        }
    ));
    report.line(format!("output norm    {output_norm:.6e}"));
    report.line(format!("wrote          {}", args.output.display()));
    report.set("basis_fields", basis.len());
    report.set("discretization", setup.discretization());
    report.set("input_norm", input_norm);
    report.set("rest_norm", filtered.rest_norm);
    report.set("rest_gain", rest_gain);
    report.set("output_norm", output_norm);
    report.set("output", args.output.display().to_string());
    report.finish()
}
