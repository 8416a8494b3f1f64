//! `tvf basis`: compute the Fourier basis of a mesh (Section 6) and save it as a `.tvfb` file
//! and/or as numpy arrays (`--export DIR`).

use crate::basis_export::stage_basis_export;
use crate::context::RunContext;
use crate::discretization_flags::DiscretizationFlags;
use crate::mesh_input::MeshInput;
use crate::output_rules::{check_output, commit};
use crate::progress::{note, Progress};
use anyhow::{bail, Context, Result};
use clap::Args;
use std::path::PathBuf;
use std::time::Instant;
use tvf_core::discretization::HodgeOperators;
use tvf_core::io::temporaries::commit_uninterrupted;
use tvf_core::io::StagedFile;
use tvf_spectral::{
    compute_eigenfunction_basis, process_cpu_seconds, save_eigenfunction_basis, BasisFileKey,
    BasisRequest, FieldFamily, PhaseStatistics,
};

/// Arguments of `tvf basis`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf basis bunny.obj -k 1000 -o bunny.tvfb\n  tvf basis bunny.obj -k 100 --export bunny-basis/   (np.load(\"bunny-basis/fields.npy\"))\n  tvf basis --example genus2 -k 200 --decomposition nonconforming --mass voronoi -o g2.tvfb\n\nThe basis holds the K eigenfields of lowest eigenvalue of the Hodge–Laplacian (the paper's d): \
the 2g harmonic fields first, then integrable and co-integrable eigenfields mixed as their eigenvalues come, \
sorted by eigenvalue (`tvf spectrum -k K` lists the same K eigenvalues). K ≥ n1 (the field dimension: 2F for face fields, E for DEC/Whitney) gives the complete basis. The file is tied to the mesh \
(fingerprint of its vertices and faces), to the discretization and to its matrices (a hash of the five \
matrices and the fixed nodes); other commands take it with --basis."
)]
pub struct BasisArgs {
    #[command(flatten)]
    input: MeshInput,
    /// Basis size: the K lowest eigenfields of the Hodge–Laplacian, harmonic ones included (the
    /// paper's d); K ≥ n1 (the field dimension: 2F for face fields, E for DEC/Whitney) gives
    /// the complete basis.
    #[arg(short = 'k', value_name = "K")]
    fields: usize,
    #[command(flatten)]
    discretization: DiscretizationFlags,
    /// Seed of the random fields and start vectors (equal seeds give identical files).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Output basis file (.tvfb).
    #[arg(short, long, value_name = "FILE", required_unless_present = "export")]
    output: Option<PathBuf>,
    /// Also (or instead) write the basis as numpy arrays into the folder DIR: eigenvalues.npy,
    /// families.npy, coefficients.npy (n1 × K), fields.npy (F × 3 × K, at the face centroids)
    /// and frames.npy (F × 2 × 3).
    #[arg(long, value_name = "DIR")]
    export: Option<PathBuf>,
    /// Print a summary (counts, eigenvalues, labels, seconds) as one JSON object on stdout.
    #[arg(long)]
    json: bool,
}

/// Computes and saves the basis.
pub fn run(args: BasisArgs, context: &RunContext) -> Result<()> {
    if args.fields == 0 {
        bail!("-k 0: ask for at least one eigenfield");
    }
    for output in args.output.iter().chain(&args.export) {
        check_output(output, &args.input, &[])?;
    }
    let mesh = args.input.load()?.mesh;
    let discretization = args
        .discretization
        .build(context.catalog(), &mesh, &args.input)?;
    let progress = Progress::new("basis");
    let (basis, report) = {
        let callback = progress.basis_callback();
        let request = if args.fields >= discretization.field_dimension() {
            BasisRequest::complete()
        } else {
            BasisRequest::fields(args.fields)
        };
        let request = request.with_seed(args.seed).with_progress(&callback);
        compute_eigenfunction_basis(discretization.as_ref(), &request)
            .with_context(|| format!("{}: cannot compute the basis", args.input.label()))?
    };
    let key = BasisFileKey::new(&mesh, discretization.as_ref());
    // The file holds the eigenfunctions (about half the bytes of the dense fields).
    let (writing_start, writing_cpu) = (Instant::now(), process_cpu_seconds());
    // Both outputs appear together or neither: the file waits, staged, for the folder.
    let staged_file = match (&args.output, &args.export) {
        (Some(output), Some(_)) => Some(
            StagedFile::new(output)
                .with_context(|| format!("cannot write {}", output.display()))?,
        ),
        _ => None,
    };
    if let Some(output) = &args.output {
        let path = staged_file
            .as_ref()
            .map_or(output.clone(), StagedFile::path);
        save_eigenfunction_basis(&path, &basis, discretization.as_ref(), &key)
            .with_context(|| format!("cannot write {}", output.display()))?;
    }
    let staged_export = args
        .export
        .as_ref()
        .map(|dir| stage_basis_export(&basis, discretization.as_ref(), dir))
        .transpose()?;
    commit_uninterrupted(|| -> Result<()> {
        if let Some(folder) = staged_export {
            commit(folder)?;
        }
        if let (Some(file), Some(output)) = (staged_file, &args.output) {
            file.commit()
                .with_context(|| format!("cannot write {}", output.display()))?;
        }
        Ok(())
    })?;
    let writing = PhaseStatistics {
        wall_seconds: writing_start.elapsed().as_secs_f64(),
        cpu_seconds: process_cpu_seconds() - writing_cpu,
        ..PhaseStatistics::default()
    };
    let written: Vec<String> = args
        .output
        .iter()
        .chain(&args.export)
        .map(|p| p.display().to_string())
        .collect();
    let count = |family| basis.families().iter().filter(|&&f| f == family).count();
    progress.finish(format!(
        "{} fields ({} harmonic, {} integrable, {} co-integrable; {}) in {:.2} s -> {}",
        basis.len(),
        count(FieldFamily::Harmonic),
        count(FieldFamily::Integrable),
        count(FieldFamily::Cointegrable),
        key.discretization,
        report.seconds,
        written.join(" and ")
    ));
    if let Some(threshold) = report.split_threshold {
        note(format!(
            "eigenpairs computed: {} integrable + {} co-integrable, all below λ = {threshold:.6e} \
             (split counted by {} inertia factorizations in {:.2} s)",
            report.integrable_computed,
            report.cointegrable_computed,
            report.counting_factorizations,
            report.counting_seconds
        ));
    }
    if report.harmonic_dimension > 0 {
        note(format!(
            "harmonic fields: dimension {}, orthonormality error {:.1e}, ‖L Γ‖ ≤ {:.1e}",
            report.harmonic_dimension,
            report.harmonic_orthonormality_error,
            report.harmonic_kernel_residual
        ));
    }
    if args.json {
        let labels: Vec<&str> = basis.families().iter().map(|f| f.name()).collect();
        let summary = serde_json::json!({
            "mesh": args.input.label(),
            "discretization": key.discretization,
            "fields": basis.len(),
            "harmonic": count(FieldFamily::Harmonic),
            "integrable": count(FieldFamily::Integrable),
            "cointegrable": count(FieldFamily::Cointegrable),
            "eigenvalues": basis.eigenvalues(),
            "labels": labels,
            "seconds": report.seconds,
            "computed": {
                "integrable": report.integrable_computed,
                "cointegrable": report.cointegrable_computed,
            },
            "split_threshold": report.split_threshold,
            "counting_seconds": report.counting_seconds,
            "phases": {
                "counting": phase(&PhaseStatistics {
                    wall_seconds: report.counting_seconds,
                    cpu_seconds: report.counting_cpu_seconds,
                    factorizations: report.counting_factorizations,
                    solves: 0,
                }),
                "boundaries": phase(&PhaseStatistics {
                    factorizations: report.solver.counting.factorizations
                        - report.counting_factorizations,
                    ..report.solver.counting
                }),
                "solving": phase(&report.solver.solving),
                "refinement": phase(&report.solver.refinement),
                "writing": phase(&writing),
            },
            "factorizations": report.factorizations,
            "distinct_shifts": report.distinct_shifts,
            "refined_pairs": report.solver.refined_pairs,
            "max_field_residual": report.max_field_residual,
            "max_field_residual_floor": report.max_field_residual_floor,
            "output": args.output.as_ref().map(|p| p.display().to_string()),
            "export": args.export.as_ref().map(|p| p.display().to_string()),
        });
        println!("{}", serde_json::to_string_pretty(&summary)?);
    }
    Ok(())
}

/// A phase's cost as JSON: wall-clock and processor seconds, busy cores, factorizations, solves.
fn phase(statistics: &PhaseStatistics) -> serde_json::Value {
    serde_json::json!({
        "seconds": statistics.wall_seconds,
        "cpu_seconds": statistics.cpu_seconds,
        "cores_busy": statistics.utilisation(),
        "factorizations": statistics.factorizations,
        "solves": statistics.solves,
    })
}
