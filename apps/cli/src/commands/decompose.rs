//! `tvf decompose`: the discrete Hodge decomposition of a field into integrable, co-integrable and
//! harmonic parts, with the potentials.

use super::spectral_inputs::read_field;
use crate::context::RunContext;
use crate::discretization_flags::DiscretizationFlags;
use crate::mesh_input::MeshInput;
use crate::output_rules::{check_output, commit, stage};
use crate::report::Report;
use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;
use tvf_core::discretization::HodgeOperators;
use tvf_discretizations::HodgeDecomposer;
use tvf_spectral::write_hodge_parts;

/// Arguments of `tvf decompose`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf decompose bunny.obj field.npy -o parts/\n  tvf decompose bunny.obj field.txt --decomposition nonconforming -o parts/\n\nWrites DIR/integrable.npy, DIR/cointegrable.npy, DIR/harmonic.npy (F×3: one \
3D vector per face) and DIR/potential.npy, DIR/co_potential.npy (one value per node: vertices and \
edges for the conforming decomposition, edges and vertices for the nonconforming one; zero mean)."
)]
pub struct DecomposeArgs {
    #[command(flatten)]
    input: MeshInput,
    /// The field: one 3D vector per face (.npy F×3, or text `x y z` per line).
    #[arg(value_name = "FIELD", required_unless_present = "example")]
    field: Option<PathBuf>,
    /// Output folder (created if missing).
    #[arg(short, long = "output", value_name = "DIR", visible_alias = "out")]
    out: PathBuf,
    #[command(flatten)]
    discretization: DiscretizationFlags,
    /// Print the energies of the parts as one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// Decomposes the field and writes the parts.
pub fn run(mut args: DecomposeArgs, context: &RunContext) -> Result<()> {
    let field = args.input.required_second(args.field.take(), "FIELD");
    check_output(&args.out, &args.input, &[Some(&field)])?;
    let mesh = args.input.load()?.mesh;
    let discretization = args
        .discretization
        .build(context.catalog(), &mesh, &args.input)?;
    let field_path = field;
    let field = read_field(&field_path, discretization.require_sampling()?)?;
    let mut report = Report::new(args.json);
    report.set("discretization", discretization.id());
    let staged = stage(&args.out)?;
    let c = discretization.as_ref();
    let parts = HodgeDecomposer::new(c)
        .and_then(|d| d.decompose(&field))
        .with_context(|| format!("{}: cannot decompose the field", args.input.label()))?;
    let total = c.field_inner(&field, &field);
    if !total.is_finite() {
        anyhow::bail!(
            "{}: the field's energy ‖·‖² is not finite ({total:e}): its vectors are too large \
             for f64 arithmetic",
            field_path.display()
        );
    }
    report.set("field_energy", total);
    write_hodge_parts(&staged, c, &parts, &mut |name, energy| {
        let share = if total > 0.0 {
            100.0 * energy / total
        } else {
            0.0
        };
        report.line(format!(
            "{name:<13} ‖·‖² = {energy:.6e}  ({share:.2} % of the field)"
        ));
        report.set(&format!("{name}_energy"), energy);
    })?;
    commit(staged)?;
    report.line(format!(
        "wrote the parts and potentials to {}",
        args.out.display()
    ));
    report.set("output", args.out.display().to_string());
    report.finish()
}
