//! AMD against nested dissection for the full soft-design system on the Table 1 meshes:
//! fill (`nnz(L)` of the augmented `4F × 4F` factor), ordering + symbolic analysis, numeric
//! factorization, assembly, solve (with PCG refinement) and the final relative residual.
//! Medians over `--runs N` (default 3).
//!
//! ```text
//! cargo run --release -p tvf-papers --example full_soft_orderings -- [--runs N] [--seq] [--parallelism auto|seq|par] [--ordering amd|nd] [MESH ...]
//! ```
//! MESH names a file `../shared/meshes/MESH.obj` (default: papers/'s Table 1 meshes, the
//! constraints papers/'s 30 seeded ones); `--seq`
//! sets faer's global parallelism to one thread (its default is all threads); `--parallelism`
//! chooses the design's own [`FactorParallelism`] (default `auto`: one thread for small
//! factors). The `threads` column says which the factorization used.

use std::time::{Duration, Instant};
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::io::load_mesh;
use tvf_design::{
    default_regularization, CompiledConstraint, ConstraintAssembler, FactorParallelism,
    FillOrdering, FullSoftDesign, SoftOptions, SolveReport,
};
use tvf_discretizations::{catalog_entry, DEFAULT_DISCRETIZATION};
use tvf_figures::seeded_constraints::seeded_constraints;
use tvf_papers::brandt2017::MESHES;

const OMEGA: f64 = 0.1;

fn median(mut values: Vec<Duration>) -> f64 {
    values.sort();
    values[values.len() / 2].as_secs_f64()
}

/// What the command line asks for.
struct Settings {
    runs: usize,
    names: Vec<String>,
    parallelism: FactorParallelism,
    orderings: Vec<FillOrdering>,
}

/// The settings from the command line (see the module documentation).
fn settings() -> Result<Settings, Box<dyn std::error::Error>> {
    let mut settings = Settings {
        runs: 3,
        names: Vec::new(),
        parallelism: FactorParallelism::default(),
        orderings: vec![FillOrdering::Amd, FillOrdering::NestedDissection],
    };
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--seq" {
            faer::set_global_parallelism(faer::Par::Seq);
        } else if arg == "--parallelism" {
            settings.parallelism = match args.next().as_deref() {
                Some("auto") => FactorParallelism::default(),
                Some("seq") => FactorParallelism::Sequential,
                Some("par") => FactorParallelism::Parallel,
                _ => return Err("--parallelism: auto, seq or par".into()),
            };
        } else if arg == "--ordering" {
            let name = args.next().ok_or("--ordering needs amd or nd")?;
            settings.orderings =
                vec![FillOrdering::from_name(&name).ok_or("--ordering: amd or nd")?];
        } else if arg == "--runs" {
            settings.runs = args.next().ok_or("--runs needs a number")?.parse()?;
        } else {
            settings.names.push(arg);
        }
    }
    if settings.names.is_empty() {
        settings.names = MESHES
            .iter()
            .filter(|m| m.paper.is_some())
            .map(|m| m.file.to_string())
            .collect();
    }
    Ok(settings)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let settings = settings()?;
    println!(
        "| mesh | faces | ordering | threads | nnz(L) | flops | assembly S | assembly aug. | ordering+symbolic | numeric | factor total | solve | steps | residual | floor |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for name in &settings.names {
        let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../../shared/meshes")
            .join(format!("{name}.obj"));
        let mesh = match load_mesh(&path) {
            Ok(loaded) => loaded.mesh,
            Err(e) => {
                eprintln!("skipping {name}: {e}");
                continue;
            }
        };
        let complex = catalog_entry(DEFAULT_DISCRETIZATION)?.build(&mesh)?;
        let start = Instant::now();
        complex.dirichlet_energy();
        let assembly_s = start.elapsed().as_secs_f64();
        let assembler = ConstraintAssembler::new(complex.as_ref(), &mesh);
        let problem = Problem {
            complex: complex.as_ref(),
            compiled: assembler.compile_all(&seeded_constraints(&mesh, complex.as_ref(), 30, 1))?,
            other: assembler.compile_all(&seeded_constraints(&mesh, complex.as_ref(), 30, 2))?,
            options: SoftOptions {
                omega: OMEGA,
                regularization: default_regularization(complex.as_ref()),
            },
        };
        for &ordering in &settings.orderings {
            let row = problem.measure(ordering, &settings)?;
            println!(
                "| {name} | {} | {} | {} | {:.1}M | {:.1} G | {:.3} s | {:.3} s | {:.3} s | {:.3} s | {:.3} s | {:.0} ms | {} | {:.1e} | {:.1e} |",
                mesh.face_count(),
                ordering.name(),
                row.threads,
                row.entries as f64 / 1e6,
                row.flops / 1e9,
                assembly_s,
                row.assembly,
                row.first - row.numeric,
                row.numeric,
                row.total,
                row.solve * 1e3,
                row.report.residuals.len() - 1,
                row.report.final_residual(),
                row.report.rounding_floor,
            );
        }
    }
    Ok(())
}

/// One mesh's full soft design: its complex, the 30 seeded constraints it is solved with, 30
/// others to refactor with, and the weights.
struct Problem<'c> {
    complex: &'c dyn HodgeComplex,
    compiled: Vec<CompiledConstraint>,
    other: Vec<CompiledConstraint>,
    options: SoftOptions,
}

/// One row of the table: medians over the runs (seconds), the factor's size and threads, and
/// the last solve's report.
struct Row {
    threads: &'static str,
    entries: usize,
    flops: f64,
    assembly: f64,
    first: f64,
    numeric: f64,
    total: f64,
    solve: f64,
    report: SolveReport,
}

impl Problem<'_> {
    /// Builds, refactors and solves the design with `ordering`, `settings.runs` times.
    fn measure(
        &self,
        ordering: FillOrdering,
        settings: &Settings,
    ) -> Result<Row, Box<dyn std::error::Error>> {
        let (mut total, mut assembly, mut first, mut numeric, mut solve) =
            (vec![], vec![], vec![], vec![], vec![]);
        let (mut entries, mut threads, mut flops) = (0, "", 0.0);
        let mut report = None;
        for _ in 0..settings.runs {
            let start = Instant::now();
            let mut design = FullSoftDesign::of_complex(
                self.complex,
                self.options,
                self.compiled.clone(),
                ordering,
                settings.parallelism,
            )?;
            threads = if design.is_parallel() { "all" } else { "one" };
            total.push(start.elapsed());
            assembly.push(design.timings().assembly);
            first.push(design.timings().factorization);
            entries = design.factor_entries();
            flops = design.factor_flop_count();
            design.set_constraints(self.other.clone())?;
            numeric.push(design.timings().factorization);
            design.set_constraints(self.compiled.clone())?;
            let start = Instant::now();
            let (_, r) = design.solve();
            solve.push(start.elapsed());
            report = Some(r);
        }
        Ok(Row {
            threads,
            entries,
            flops,
            assembly: median(assembly),
            first: median(first),
            numeric: median(numeric),
            total: median(total),
            solve: median(solve),
            report: report.ok_or("no runs")?,
        })
    }
}
