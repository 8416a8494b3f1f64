//! `tvf compare`: discretizations side by side on one mesh — the time each takes for a basis of
//! K fields (as a ratio to the first, same run), their eigenvalues index by index, and how much
//! of each one's eigenfields lies in the span of the first's and back
//! ([`tvf_spectral::BasisComparison`]).

use super::compare_corpus::{run_corpus, summarize, summary_lines, CorpusRequest};
use crate::context::RunContext;
use crate::mesh_input::MeshInput;
use crate::progress::Progress;
use anyhow::{bail, Context, Result};
use clap::builder::PossibleValuesParser;
use clap::Args;
use serde_json::json;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tvf_core::discretization::{BoundaryCondition, HodgeOperators};
use tvf_core::generate::EXAMPLE_NAMES;
use tvf_core::SurfaceMesh;
use tvf_discretizations::{parse_boundary_condition, BoxedComplex};
use tvf_spectral::{compute_basis, BasisComparison, BasisRequest, SampledBasis};

/// Arguments of `tvf compare`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf compare bunny-closed.obj -k 100 --discretization \
conforming-barycentric --discretization dec-circumcentric --discretization whitney-galerkin\n  \
tvf compare --example genus2 -k 60 --discretization dec-circumcentric --complex my-dec/\n  \
tvf compare --corpus meshes/ -k 50 --discretization conforming-barycentric --discretization \
whitney-galerkin --json\n\n\
The first entry is the reference. For each other entry the report gives the relative \
eigenvalue difference |λa − λb| / max(λa, λb) index by index (median and largest), and the \
fraction of each eigenfield's squared norm that lies in the span of the other's K fields (mean \
and smallest, both ways): fields are compared as one tangent vector per face at its centroid \
with the area-weighted inner product, so entries with different field spaces compare. Choose K \
at a gap of the spectrum: where K cuts through a multiple eigenvalue (e.g. on a sphere), the \
entries may keep different fields of that eigenspace, which then lie partly outside each \
other's span. Times \
are the basis computation of each entry, as a ratio to the first's in the same run. With \
--json, prints all of it (per index) as one JSON object."
)]
pub struct CompareArgs {
    /// Mesh file (.obj, .off or .ply); omit with --example or --corpus.
    #[arg(value_name = "MESH", required_unless_present_any = ["example", "corpus"])]
    mesh: Option<PathBuf>,
    /// A built-in example mesh instead of a file.
    #[arg(
        long,
        value_name = "NAME",
        conflicts_with = "mesh",
        value_parser = PossibleValuesParser::new(EXAMPLE_NAMES)
    )]
    example: Option<String>,
    /// Split every polygon into triangles after loading (as for other commands' --triangulate).
    #[arg(long)]
    triangulate: bool,
    /// Every mesh file (.obj, .off, .ply) of FOLDER instead of one mesh: each entry on each mesh
    /// on local threads, reported as the entry's success rate with the reason of every failure,
    /// its median basis time and its eigenvalues against the first entry's (catalog ids only:
    /// a --complex folder belongs to one mesh).
    #[arg(long, value_name = "FOLDER", conflicts_with_all = ["mesh", "example", "complexes"])]
    corpus: Option<PathBuf>,
    /// With --corpus: worker threads [default: one per core].
    #[arg(long, value_name = "N", requires = "corpus")]
    threads: Option<usize>,
    /// A catalog id to compare; repeat the flag (the first entry given is the reference).
    #[arg(long = "discretization", value_name = "ID")]
    discretizations: Vec<String>,
    /// A folder of your own matrices (as for `--complex` of other commands), compared after
    /// the catalog ids; repeat the flag for several.
    #[arg(long = "complex", value_name = "DIR")]
    complexes: Vec<PathBuf>,
    /// Boundary condition of the catalog entries on meshes with boundary (tangential or
    /// normal) [default: tangential].
    #[arg(long, value_name = "CONDITION", value_parser = parse_boundary_condition)]
    boundary: Option<BoundaryCondition>,
    /// Basis size: the K lowest eigenfields of every entry, harmonic ones included.
    #[arg(short = 'k', value_name = "K")]
    count: usize,
    /// Print JSON to stdout instead of tables.
    #[arg(long)]
    json: bool,
}

/// One compared entry: its complex, the sampled basis and the time the basis took.
struct ComparedEntry {
    complex: BoxedComplex,
    sampled: SampledBasis,
    seconds: f64,
}

/// The one mesh of the arguments (a file or an example).
fn mesh_input(args: &CompareArgs) -> MeshInput {
    let mut input = match (&args.mesh, &args.example) {
        (Some(path), _) => MeshInput::file(path.clone()),
        (None, Some(name)) => MeshInput::example(name),
        (None, None) => MeshInput::file(PathBuf::new()),
    };
    input.triangulate = args.triangulate;
    input
}

/// Builds every entry, computes and samples its basis, and prints the comparison.
pub fn run(args: CompareArgs, context: &RunContext) -> Result<()> {
    if args.count == 0 {
        bail!("-k 0: ask for at least one field");
    }
    let names = entry_names(&args)?;
    if let Some(folder) = &args.corpus {
        return run_corpus_comparison(&args, folder, context);
    }
    let input = mesh_input(&args);
    let loaded = input.load()?;
    let mesh = loaded.mesh;
    let identity: Vec<usize> = (0..mesh.vertex_count()).collect();
    let original_vertex = input.original_vertex().unwrap_or(&identity).to_vec();
    let mut entries = Vec::with_capacity(names.len());
    for name in &names {
        let label = match name {
            EntryName::Catalog(id) => id.clone(),
            EntryName::Folder(dir) => dir.display().to_string(),
        };
        let complex = match name {
            EntryName::Catalog(id) => context
                .catalog()
                .build_complex(id, Some(args.boundary.unwrap_or_default()), &mesh)
                .with_context(|| input.label())?,
            EntryName::Folder(dir) => Box::new(
                tvf_spectral::read_complex_folder(dir, &mesh, &original_vertex)
                    .with_context(|| format!("--complex {} on {}", dir.display(), input.label()))?,
            ),
        };
        entries.push(compute_entry(complex, label, args.count, &input)?);
    }
    let comparisons = entries[1..]
        .iter()
        .map(|entry| BasisComparison::new(&mesh, &entries[0].sampled, &entry.sampled))
        .collect::<Result<Vec<_>, _>>()
        .with_context(|| input.label())?;
    if args.json {
        print_json(&args, &input, &mesh, &entries, &comparisons)
    } else {
        print_tables(&args, &input, &mesh, &entries, &comparisons);
        Ok(())
    }
}

/// `--corpus FOLDER`: every mesh × entry, the per-entry success rates and failures.
fn run_corpus_comparison(args: &CompareArgs, folder: &Path, context: &RunContext) -> Result<()> {
    if args.threads == Some(0) {
        bail!("--threads 0: give at least one thread");
    }
    let request = CorpusRequest {
        folder,
        ids: &args.discretizations,
        boundary: args.boundary.unwrap_or_default(),
        count: args.count,
        triangulate: args.triangulate,
        threads: args.threads,
    };
    let runs = run_corpus(&request, context.catalog())?;
    let summaries = summarize(&args.discretizations, &runs);
    if args.json {
        let out = json!({
            "corpus": folder.display().to_string(),
            "fields": args.count,
            "reference": args.discretizations[0],
            "entries": summaries,
            "runs": runs,
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        println!(
            "corpus {} ({} meshes), K = {} fields",
            folder.display(),
            runs.len() / args.discretizations.len().max(1),
            args.count
        );
        for line in summary_lines(&summaries, &args.discretizations[0]) {
            println!("{line}");
        }
    }
    Ok(())
}

/// What the flags name: catalog ids first, then folders.
enum EntryName {
    Catalog(String),
    Folder(PathBuf),
}

/// The entries in order, at least two, none twice.
fn entry_names(args: &CompareArgs) -> Result<Vec<EntryName>> {
    let mut names: Vec<EntryName> = args
        .discretizations
        .iter()
        .cloned()
        .map(EntryName::Catalog)
        .collect();
    names.extend(args.complexes.iter().cloned().map(EntryName::Folder));
    if names.len() < 2 {
        bail!(
            "compare needs at least two entries: give --discretization ID (and/or --complex DIR) \
             two or more times"
        );
    }
    for (i, id) in args.discretizations.iter().enumerate() {
        if args.discretizations[..i].contains(id) {
            bail!("--discretization {id} is given twice");
        }
    }
    for (i, dir) in args.complexes.iter().enumerate() {
        if args.complexes[..i].contains(dir) {
            bail!("--complex {} is given twice", dir.display());
        }
    }
    Ok(names)
}

/// Computes the basis of `count` fields of `complex` (timed, with progress) and samples it;
/// `label` names the entry in the report (the catalog id, or the folder).
fn compute_entry(
    complex: BoxedComplex,
    label: String,
    count: usize,
    input: &MeshInput,
) -> Result<ComparedEntry> {
    let progress = Progress::new(format!("compare {}", complex.id()));
    let start = Instant::now();
    let basis = {
        let callback = progress.basis_callback();
        let request =
            BasisRequest::lowest(count, complex.field_dimension()).with_progress(&callback);
        compute_basis(complex.as_ref(), &request).with_context(|| {
            format!(
                "{}: cannot compute the basis of '{}'",
                input.label(),
                complex.id()
            )
        })?
    };
    let seconds = start.elapsed().as_secs_f64();
    progress.finish(format!(
        "{} fields of {} in {seconds:.2} s",
        basis.len(),
        complex.id()
    ));
    let mut sampled = SampledBasis::new(complex.as_ref(), &basis)
        .with_context(|| format!("{}: '{}'", input.label(), complex.id()))?;
    sampled.id = label;
    Ok(ComparedEntry {
        complex,
        sampled,
        seconds,
    })
}

/// Median and largest of `values` (not empty).
fn median_and_max(values: &[f64]) -> (f64, f64) {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    (sorted[sorted.len() / 2], sorted[sorted.len() - 1])
}

/// Mean and smallest of `values` (not empty).
fn mean_and_min(values: &[f64]) -> (f64, f64) {
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    (mean, values.iter().copied().fold(f64::INFINITY, f64::min))
}

fn print_tables(
    args: &CompareArgs,
    input: &MeshInput,
    mesh: &SurfaceMesh,
    entries: &[ComparedEntry],
    comparisons: &[BasisComparison],
) {
    println!(
        "mesh {} ({} faces), K = {} fields",
        input.label(),
        mesh.face_count(),
        args.count
    );
    println!(
        "{:<34} {:>10} {:>12} {:>10}",
        "entry", "n1", "basis time", "vs first"
    );
    for entry in entries {
        println!(
            "{:<34} {:>10} {:>10.2} s {:>9.2}x",
            entry.sampled.id,
            entry.complex.field_dimension(),
            entry.seconds,
            entry.seconds / entries[0].seconds
        );
    }
    println!(
        "\ncompared with {} (relative eigenvalue difference; share of an eigenfield in the \
         other's span)",
        entries[0].sampled.id
    );
    println!(
        "{:<34} {:>21} {:>21} {:>21}",
        "entry", "eigenvalues med/max", "in first mean/min", "first in it mean/min"
    );
    for comparison in comparisons {
        let (median, max) = median_and_max(&comparison.eigenvalue_differences);
        let (in_first, in_first_min) = mean_and_min(&comparison.second_in_first);
        let (first_in, first_in_min) = mean_and_min(&comparison.first_in_second);
        println!(
            "{:<34} {:>10.2e}/{:<10.2e} {:>10.6}/{:<10.6} {:>10.6}/{:<10.6}",
            comparison.second, median, max, in_first, in_first_min, first_in, first_in_min
        );
    }
}

fn print_json(
    args: &CompareArgs,
    input: &MeshInput,
    mesh: &SurfaceMesh,
    entries: &[ComparedEntry],
    comparisons: &[BasisComparison],
) -> Result<()> {
    let entries: Vec<_> = entries
        .iter()
        .map(|entry| {
            json!({
                "entry": entry.sampled.id,
                "id": entry.complex.id(),
                "field_dimension": entry.complex.field_dimension(),
                "eigenvalues": entry.sampled.eigenvalues,
                "seconds": entry.seconds,
                "time_ratio_to_first": entry.seconds / entries[0].seconds,
            })
        })
        .collect();
    let comparisons: Vec<_> = comparisons
        .iter()
        .map(|c| {
            json!({
                "first": c.first,
                "second": c.second,
                "eigenvalue_differences": c.eigenvalue_differences,
                "second_in_first": c.second_in_first,
                "first_in_second": c.first_in_second,
            })
        })
        .collect();
    let out = json!({
        "mesh": input.label(),
        "faces": mesh.face_count(),
        "fields": args.count,
        "entries": entries,
        "comparisons": comparisons,
    });
    println!("{}", serde_json::to_string_pretty(&out)?);
    Ok(())
}
