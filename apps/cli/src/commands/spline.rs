//! `tvf spline`: a tangential vector field spline (hard constraints, Section 7) from a JSON
//! constraint file, in a loaded or freshly computed eigenbasis; and the flags and steps it
//! shares with `tvf design` ([`DesignOutputArgs`]). The problem, the solves and their reports
//! are `tvf_design::DesignProblem`'s.

use super::spectral_inputs::{open_basis_blocks, readable_in_blocks};
use crate::basis_source::BasisSource;
use crate::context::RunContext;
use crate::mesh_input::MeshInput;
use crate::output_rules::check_file_output;
use crate::report::Report;
use anyhow::Result;
use clap::Args;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_design::{CompiledConstraint, DesignProblem, ReducedBasis, ResidualReport};
use tvf_discretizations::{BoxedComplex, Catalog};
use tvf_spectral::{write_tangent_field, FieldBasis};

/// Arguments of `tvf spline`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf spline bunny.obj --constraints constraints.json -k 1000 -o spline.npy\n  \
tvf spline bunny.obj --constraints constraints.json --basis bunny.tvfb -o spline.npy\n  \
tvf render bunny.obj spline.npy --constraints constraints.json -o spline.png   (look at it)\n\n\
The spline lives in the basis of the K lowest eigenfields (-k K, the paper's d; computed once and cached, \
K ≥ n1 (the field dimension: 2F for face fields, E for DEC/Whitney): the complete basis) or of a --basis file; constraints are met exactly in that basis."
)]
pub struct SplineArgs {
    #[command(flatten)]
    input: MeshInput,
    /// The constraint file (JSON, see README "Constraint files").
    #[arg(long, value_name = "C.json")]
    constraints: PathBuf,
    #[command(flatten)]
    design: DesignOutputArgs,
}

/// The flags `tvf spline` and `tvf design` end with: the basis, the output field and `--json`.
#[derive(Args)]
pub struct DesignOutputArgs {
    #[command(flatten)]
    pub basis: BasisSource,
    /// Output field: one 3D vector per face (.npy F×3, or text by extension).
    #[arg(short, long, value_name = "FIELD")]
    pub output: PathBuf,
    /// Print the report (sizes, times in ms, residuals) as one JSON object on stdout.
    #[arg(long)]
    pub json: bool,
}

impl DesignOutputArgs {
    /// Applies the output rules, loads the mesh of `input` and the `constraints` file (and
    /// reports them), builds the discretization (the basis file's or the flags') and compiles
    /// the constraints for it, without the basis: the constraints are checked before an
    /// expensive basis computation.
    pub fn load(
        &self,
        catalog: &Catalog,
        input: &MeshInput,
        constraints: &Path,
        report: &mut Report,
    ) -> Result<(DesignProblem, BoxedComplex, Vec<CompiledConstraint>)> {
        let basis_file = self.basis.options.basis.as_deref();
        check_file_output(&self.output, input, &[Some(constraints), basis_file])?;
        let problem = DesignProblem::load(input.load()?.mesh, input.label(), constraints)?;
        let summary = problem.summary();
        report.add(summary.lines(), &summary);
        let complex = self
            .basis
            .options
            .discretization(catalog, &problem.mesh, input)?;
        let compiled = problem.compile(complex.as_ref())?;
        Ok((problem, complex, compiled))
    }

    /// The basis (loaded, cached or computed; see [`crate::basis_source`]), row-major for the
    /// solvers; a `--basis` file of eigenfunctions is read in blocks instead, only the rows of
    /// `U` the `constraints` touch held in memory ([`ReducedBasis::from_field_basis`]).
    pub fn reduced_basis(
        &self,
        catalog: &Catalog,
        problem: &DesignProblem,
        input: &MeshInput,
        constraints: &[CompiledConstraint],
        report: &mut Report,
    ) -> Result<ReducedBasis> {
        let start = Instant::now();
        let (basis, how, discretization) = match self.basis.options.basis.as_deref() {
            Some(path) if readable_in_blocks(path)? => {
                let complex = self
                    .basis
                    .options
                    .discretization(catalog, &problem.mesh, input)?;
                let blocks = open_basis_blocks(path, &problem.mesh, complex)?;
                let discretization = blocks.complex().id().to_string();
                let blocks: Arc<dyn FieldBasis> = Arc::new(blocks);
                let reduced = ReducedBasis::from_field_basis(blocks, constraints)?;
                (reduced, " (read in blocks)", discretization)
            }
            _ => {
                let resolved = self.basis.resolve(catalog, &problem.mesh, input)?;
                let reduced = ReducedBasis::from_spectral(&resolved.basis)?;
                (reduced, "", resolved.discretization.id().to_string())
            }
        };
        let seconds = start.elapsed().as_secs_f64();
        report.line(format!(
            "basis           {} fields of {discretization} ready in {seconds:.3} s{how}",
            basis.len(),
        ));
        report.set("basis_fields", basis.len());
        report.set("discretization", discretization);
        report.set("basis_seconds", seconds);
        Ok(basis)
    }

    /// Reports the `residuals`, writes the solved `field` of `complex` and prints the report.
    pub fn finish(
        &self,
        complex: &dyn HodgeComplex,
        field: &[f64],
        residuals: &ResidualReport,
        mut report: Report,
    ) -> Result<()> {
        report.add(residuals.lines(), residuals);
        write_tangent_field(&self.output, complex.require_sampling()?, field)?;
        report.line(format!("wrote {}", self.output.display()));
        report.set("output", self.output.display().to_string());
        report.finish()
    }
}

/// Runs `tvf spline`.
pub fn run(args: SplineArgs, context: &RunContext) -> Result<()> {
    let mut report = Report::new(args.design.json);
    let catalog = context.catalog();
    let (problem, complex, constraints) =
        args.design
            .load(catalog, &args.input, &args.constraints, &mut report)?;
    let basis =
        args.design
            .reduced_basis(catalog, &problem, &args.input, &constraints, &mut report)?;
    let solved = problem.spline(&basis, &constraints)?;
    report.add(solved.spline_lines(constraints.len(), basis.len()), &solved);
    let residuals = problem.residuals(&solved.field, &constraints)?;
    args.design
        .finish(complex.as_ref(), &solved.field, &residuals, report)
}
