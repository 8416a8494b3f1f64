//! `tvf rate-distortion`: relative L2 error against bits per vertex for several numbers of
//! pairs, with 64-bit and with quantised, range-coded coefficients (the paper's Figure 9).

use super::spectral_inputs::{read_field, FieldArgs};
use crate::context::RunContext;
use crate::output_rules::{commit, stage};
use crate::report::Report;
use anyhow::Result;
use clap::Args;
use std::path::{Path, PathBuf};
use tvf_figures::spectral_folders::write_rate_distortion_folder;
use tvf_spectral::{
    field_basis_id, rate_distortion, BasisSize, CoefficientCoding, FileStamp, RateDistortionReport,
};

/// Arguments of `tvf rate-distortion`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf rate-distortion bunny.obj field.npy --basis bunny.tvfb --pairs 50,100,200,400 -o rd/\n  tvf rate-distortion bunny.obj field.npy --pairs 25,50,100 --bits 8,12 -o rd/\n\nEvery point is a real .tvfc file (size with header and checksum; error measured on \
the decoded field). Writes DIR/rate_distortion.csv and DIR/rate_distortion.png (log–log), and prints, for \
every 64-bit point, the smallest quantised file with an error at most as large."
)]
pub struct RateDistortionArgs {
    #[command(flatten)]
    inputs: FieldArgs,
    /// Numbers of coefficient pairs P to keep, comma-separated (each point keeps the lowest P
    /// integrable and P co-integrable coefficients plus the harmonic ones).
    #[arg(
        long = "pairs",
        visible_alias = "ks",
        value_name = "P,P,...",
        value_delimiter = ',',
        required = true
    )]
    ks: Vec<usize>,
    /// Symbol sizes Q of the quantised coder, comma-separated.
    #[arg(long, value_name = "Q,Q,...", value_delimiter = ',', default_value = "8,12,16",
          value_parser = clap::value_parser!(u32).range(2..=32))]
    bits: Vec<u32>,
    /// Output folder (created if missing).
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    /// Print the points (the CSV's rows) and the equal-error comparison as one JSON object on
    /// stdout.
    #[arg(long)]
    json: bool,
}

/// Measures every point and writes the CSV and the plot.
pub fn run(mut args: RateDistortionArgs, context: &RunContext) -> Result<()> {
    let field = args.inputs.field_path_for(&args.output, &[])?;
    // Without --basis or -k, compute as many pairs as the largest P tried.
    let largest = args.ks.iter().max().copied().unwrap_or(0);
    let size = args.inputs.basis.size_or(BasisSize::Pairs(largest));
    let inputs = args.inputs.load(context.catalog())?;
    let field = read_field(&field, inputs.fields()?)?;
    let (mesh_fingerprint, vertex_count) = (inputs.mesh.fingerprint(), inputs.mesh.vertex_count());
    // A `--basis` file of eigenfunctions is read in blocks: every point projects once and
    // synthesises its decoded field a block of columns at a time.
    let setup = args
        .inputs
        .projection_basis(context.catalog(), inputs, size)?;
    let basis = setup.basis();
    let stamp = FileStamp {
        mesh_fingerprint,
        basis_id: field_basis_id(basis)?,
        vertex_count,
    };
    let mut codings = vec![CoefficientCoding::Float64];
    codings.extend(
        args.bits
            .iter()
            .map(|&bits| CoefficientCoding::Quantized { bits }),
    );
    let points = rate_distortion(basis, &field, stamp, &args.ks, &codings)?;
    let label = args.inputs.input.label();
    let mesh_name = Path::new(&label)
        .file_name()
        .map_or(label.clone(), |n| n.to_string_lossy().into_owned());
    let staged = stage(&args.output)?;
    write_rate_distortion_folder(&staged, &points, &codings, &mesh_name)?;
    commit(staged)?;

    let csv_path = args.output.join("rate_distortion.csv");
    let png_path = args.output.join("rate_distortion.png");
    let summary = RateDistortionReport { points: &points };
    let mut report = Report::new(args.json);
    summary
        .table_lines()
        .iter()
        .for_each(|line| report.line(line));
    report.set("basis_fields", basis.len());
    report.set("points", summary.points_json());
    summary
        .comparison_lines()
        .iter()
        .for_each(|line| report.line(line));
    report.set("equal_error", summary.comparison_json());
    report.line(format!(
        "wrote {}, {}",
        csv_path.display(),
        png_path.display()
    ));
    report.set("csv", csv_path.display().to_string());
    report.set("plot", png_path.display().to_string());
    report.finish()
}
