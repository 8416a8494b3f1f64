//! `tvf compare --corpus FOLDER`: every mesh file of a folder × every entry, on local threads
//! (one mesh per task) or on a Dask cluster ([`super::compare_scheduler`]): for each entry its
//! success rate with the reason of every failure (a mesh that does not load, an entry that
//! refuses it, a basis that cannot be computed), its basis times, and its eigenvalues against
//! the reference's on the meshes where both succeeded (relative difference
//! `|λa − λb| / max(λa, λb)`, index by index).

use super::compare_scheduler::runs_on_cluster;
use crate::context::RunContext;
use crate::error_message;
use crate::mesh_input::MeshInput;
use crate::output_rules::{commit, stage};
use crate::progress::Progress;
use anyhow::{bail, Context, Result};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use serde_json::json;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;
use tvf_core::discretization::{BoundaryCondition, HodgeOperators};
use tvf_discretizations::Catalog;
use tvf_spectral::{compute_basis, write_folder_bytes, BasisRequest};

/// What `tvf compare --corpus` was asked.
pub struct CorpusOptions<'a> {
    /// The folder of mesh files.
    pub folder: &'a Path,
    /// Catalog ids.
    pub ids: &'a [String],
    /// The id the others are compared with (one of `ids`).
    pub reference: &'a str,
    /// Boundary condition on meshes with boundary.
    pub boundary: BoundaryCondition,
    /// Basis size.
    pub count: usize,
    /// Split polygons into triangles after loading.
    pub triangulate: bool,
    /// Local worker threads (`None`: one per core).
    pub threads: Option<usize>,
    /// A Dask scheduler's address: the runs go to its cluster instead of local threads.
    pub scheduler: Option<&'a str>,
    /// A folder for `corpus.md` and `corpus.json`.
    pub output: Option<&'a Path>,
    /// Print JSON instead of the table.
    pub json: bool,
}

/// Runs the corpus comparison of `options` and reports it.
pub fn run_corpus_comparison(options: &CorpusOptions, context: &RunContext) -> Result<()> {
    if options.threads == Some(0) {
        bail!("--threads 0: give at least one thread");
    }
    if let Some(out) = options.output {
        tvf_core::io::check_output(out, &[options.folder])?;
    }
    for id in options.ids {
        context.catalog().get(id)?;
    }
    let runs = match options.scheduler {
        Some(address) => runs_on_cluster(options, address)?,
        None => {
            let request = CorpusRequest {
                folder: options.folder,
                ids: options.ids,
                boundary: options.boundary,
                count: options.count,
                triangulate: options.triangulate,
                threads: options.threads,
            };
            run_corpus(&request, context.catalog())?
        }
    };
    let summaries = summarize(options.ids, options.reference, &runs);
    let report = json!({
        "corpus": options.folder.display().to_string(),
        "fields": options.count,
        "reference": options.reference,
        "scheduler": options.scheduler,
        "entries": summaries,
        "runs": runs,
    });
    let json = serde_json::to_string_pretty(&report)?;
    let mut text = format!(
        "corpus {} ({} meshes), K = {} fields{}\n",
        options.folder.display(),
        runs.len() / options.ids.len().max(1),
        options.count,
        options
            .scheduler
            .map_or(String::new(), |a| format!(", on the Dask cluster at {a}"))
    );
    for line in summary_lines(&summaries, options.reference) {
        text.push_str(&line);
        text.push('\n');
    }
    if let Some(out) = options.output {
        let staged = stage(out)?;
        write_folder_bytes(&staged, "corpus.md", text.as_bytes())?;
        write_folder_bytes(&staged, "corpus.json", format!("{json}\n").as_bytes())?;
        commit(staged)?;
    }
    if options.json {
        println!("{json}");
    } else {
        print!("{text}");
    }
    Ok(())
}

/// What a corpus comparison runs.
pub struct CorpusRequest<'a> {
    /// The folder of mesh files (`.obj`, `.off`, `.ply`; not recursive).
    pub folder: &'a Path,
    /// Catalog ids, the first the reference.
    pub ids: &'a [String],
    /// Boundary condition on meshes with boundary.
    pub boundary: BoundaryCondition,
    /// Basis size.
    pub count: usize,
    /// Split polygons into triangles after loading.
    pub triangulate: bool,
    /// Worker threads (`None`: one per core).
    pub threads: Option<usize>,
}

/// One mesh × entry. Serialized with the keys of its fields (`eigenvalues` empty and `reason`
/// set on a failure); the Dask driver (`python -m tvf.corpus`) prints rows with these keys.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CorpusRun {
    /// The mesh file.
    pub mesh: String,
    /// Its faces (0 if it did not load).
    pub faces: usize,
    /// The catalog id.
    pub discretization: String,
    /// Whether the basis was computed.
    pub succeeded: bool,
    /// Why not, if it was not.
    pub reason: Option<String>,
    /// Seconds to build the complex and compute the basis.
    pub seconds: f64,
    /// The basis's eigenvalues (`K`, ascending).
    pub eigenvalues: Vec<f64>,
}

/// One entry over the corpus. Serialized with the keys of its fields.
#[derive(Debug, Clone, Serialize)]
pub struct EntrySummary {
    /// The catalog id.
    pub discretization: String,
    /// Meshes tried.
    pub meshes: usize,
    /// Meshes whose basis was computed.
    pub succeeded: usize,
    /// `succeeded / meshes`.
    pub success_rate: f64,
    /// `(mesh, reason)` of every failure.
    pub failures: Vec<(String, String)>,
    /// Median over the meshes where both succeeded of the largest relative eigenvalue
    /// difference to the reference (`None` for the reference, or without such a mesh).
    pub median_relative_difference: Option<f64>,
    /// Median basis seconds over its successes.
    pub median_seconds: Option<f64>,
}

/// The mesh files of `folder`, sorted by name.
fn mesh_files(folder: &Path) -> Result<Vec<PathBuf>> {
    let entries = std::fs::read_dir(folder)
        .with_context(|| format!("--corpus {}: cannot read the folder", folder.display()))?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file())
        .filter(|p| {
            p.extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| ["obj", "off", "ply"].contains(&e.to_ascii_lowercase().as_str()))
        })
        .collect();
    files.sort();
    if files.is_empty() {
        bail!(
            "--corpus {}: no mesh file (.obj, .off, .ply) in the folder",
            folder.display()
        );
    }
    Ok(files)
}

/// Every entry of `request` on `path`, one run each.
fn runs_on_mesh(path: &Path, request: &CorpusRequest, catalog: &Catalog) -> Vec<CorpusRun> {
    let name = path.display().to_string();
    let mut input = MeshInput::file(path.to_path_buf());
    input.triangulate = request.triangulate;
    let loaded = input.load();
    request
        .ids
        .iter()
        .map(|id| {
            let start = Instant::now();
            let run = |mesh: &tvf_core::SurfaceMesh| -> Result<Vec<f64>> {
                let complex = catalog.build_complex(id, Some(request.boundary), mesh)?;
                let basis_request = BasisRequest::lowest(request.count, complex.field_dimension());
                let basis = compute_basis(complex.as_ref(), &basis_request)?;
                Ok(basis.eigenvalues().to_vec())
            };
            let (faces, result) = match &loaded {
                Ok(loaded) => (loaded.mesh.face_count(), run(&loaded.mesh)),
                Err(error) => (
                    0,
                    Err(anyhow::anyhow!("cannot load: {}", error_message(error))),
                ),
            };
            let seconds = start.elapsed().as_secs_f64();
            match result {
                Ok(eigenvalues) => CorpusRun {
                    mesh: name.clone(),
                    faces,
                    discretization: id.clone(),
                    succeeded: true,
                    reason: None,
                    seconds,
                    eigenvalues,
                },
                Err(error) => CorpusRun {
                    mesh: name.clone(),
                    faces,
                    discretization: id.clone(),
                    succeeded: false,
                    reason: Some(error_message(&error)),
                    seconds,
                    eigenvalues: Vec::new(),
                },
            }
        })
        .collect()
}

/// Runs every mesh × entry of `request` (meshes in parallel on `request.threads` threads).
pub fn run_corpus(request: &CorpusRequest, catalog: &Catalog) -> Result<Vec<CorpusRun>> {
    let files = mesh_files(request.folder)?;
    let progress = Progress::new("compare corpus");
    let done = AtomicUsize::new(0);
    let work = || -> Vec<CorpusRun> {
        files
            .par_iter()
            .flat_map_iter(|path| {
                let runs = runs_on_mesh(path, request, catalog);
                let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
                progress.update("meshes", finished, files.len());
                runs
            })
            .collect()
    };
    // Always a pool of its own: the meshes' eigensolvers hand work to rayon's global pool and
    // wait for it, which deadlocks when the meshes themselves occupy every global worker.
    let threads = request
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let runs = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .context("--threads: cannot start the worker threads")?
        .install(work);
    let failed = runs.iter().filter(|r| !r.succeeded).count();
    progress.finish(format!(
        "{} runs on {} meshes, {failed} failed",
        runs.len(),
        files.len()
    ));
    Ok(runs)
}

/// The largest relative difference of two spectra, index by index (the shorter length).
fn largest_relative_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            let scale = x.abs().max(y.abs());
            if scale > 0.0 {
                (x - y).abs() / scale
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max)
}

/// The median of `values` (`None` if empty).
fn median(mut values: Vec<f64>) -> Option<f64> {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied()
}

/// Per entry of `ids`, its summary over `runs`, compared with the entry `reference`.
pub fn summarize(ids: &[String], reference: &str, runs: &[CorpusRun]) -> Vec<EntrySummary> {
    ids.iter()
        .map(|id| {
            let own: Vec<&CorpusRun> = runs.iter().filter(|r| &r.discretization == id).collect();
            let succeeded = own.iter().filter(|r| r.succeeded).count();
            let differences: Vec<f64> = if id == reference {
                Vec::new()
            } else {
                own.iter()
                    .filter(|r| r.succeeded)
                    .filter_map(|r| {
                        runs.iter()
                            .find(|o| o.discretization == reference && o.mesh == r.mesh)
                            .filter(|o| o.succeeded)
                            .map(|o| largest_relative_difference(&o.eigenvalues, &r.eigenvalues))
                    })
                    .collect()
            };
            EntrySummary {
                discretization: id.clone(),
                meshes: own.len(),
                succeeded,
                success_rate: succeeded as f64 / own.len().max(1) as f64,
                failures: own
                    .iter()
                    .filter(|r| !r.succeeded)
                    .map(|r| (r.mesh.clone(), r.reason.clone().unwrap_or_default()))
                    .collect(),
                median_relative_difference: median(differences),
                median_seconds: median(
                    own.iter()
                        .filter(|r| r.succeeded)
                        .map(|r| r.seconds)
                        .collect(),
                ),
            }
        })
        .collect()
}

/// The summaries as text: one line per entry, then its failures.
pub fn summary_lines(summaries: &[EntrySummary], reference: &str) -> Vec<String> {
    let mut lines = vec![format!(
        "{:<34} {:>12} {:>8} {:>14} {:>22}",
        "entry", "succeeded", "rate", "median time", "eigenvalues vs ref."
    )];
    for s in summaries {
        let difference = match s.median_relative_difference {
            Some(d) => format!("{d:.2e}"),
            None if s.discretization == reference => "(reference)".to_string(),
            None => "-".to_string(),
        };
        lines.push(format!(
            "{:<34} {:>12} {:>7.1}% {:>12} {:>22}",
            s.discretization,
            format!("{}/{}", s.succeeded, s.meshes),
            100.0 * s.success_rate,
            s.median_seconds
                .map_or("-".to_string(), |t| format!("{t:.2} s")),
            difference
        ));
    }
    for s in summaries.iter().filter(|s| !s.failures.is_empty()) {
        lines.push(format!("failures of {}:", s.discretization));
        for (mesh, reason) in &s.failures {
            lines.push(format!("  {mesh}: {reason}"));
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(mesh: &str, id: &str, eigenvalues: Option<Vec<f64>>) -> CorpusRun {
        CorpusRun {
            mesh: mesh.into(),
            faces: 10,
            discretization: id.into(),
            succeeded: eigenvalues.is_some(),
            reason: eigenvalues.is_none().then(|| "refused".to_string()),
            seconds: 1.0,
            eigenvalues: eigenvalues.unwrap_or_default(),
        }
    }

    #[test]
    fn summaries_count_successes_and_compare_with_the_reference() {
        let ids = vec!["a".to_string(), "b".to_string()];
        let runs = vec![
            run("m1", "a", Some(vec![1.0, 2.0])),
            run("m1", "b", Some(vec![1.1, 2.0])),
            run("m2", "a", Some(vec![1.0])),
            run("m2", "b", None),
        ];
        let summaries = summarize(&ids, "a", &runs);
        assert_eq!(summaries[0].succeeded, 2);
        assert_eq!(summaries[0].median_relative_difference, None);
        assert_eq!(summaries[1].succeeded, 1);
        assert_eq!(summaries[1].success_rate, 0.5);
        assert_eq!(
            summaries[1].failures,
            vec![("m2".to_string(), "refused".to_string())]
        );
        let d = summaries[1].median_relative_difference.unwrap();
        assert!((d - 0.1 / 1.1).abs() < 1e-12);
        let lines = summary_lines(&summaries, "a");
        assert!(
            lines[2].contains("1/2") && lines[2].contains("50.0%"),
            "{lines:?}"
        );
        assert!(lines.iter().any(|l| l == "  m2: refused"), "{lines:?}");
    }
}
