//! `tvf compare`: discretizations side by side on one mesh — the time each takes for a basis of
//! K fields (as a ratio to the first, same run), their eigenvalues index by index, and how much
//! of each one's eigenfields lies in the span of the first's and back
//! ([`tvf_spectral::BasisComparison`]).

use crate::context::RunContext;
use crate::mesh_input::MeshInput;
use crate::progress::Progress;
use anyhow::{bail, Context, Result};
use clap::Args;
use serde_json::json;
use std::path::PathBuf;
use std::time::Instant;
use tvf_core::discretization::{BoundaryCondition, HodgeOperators};
use tvf_core::SurfaceMesh;
use tvf_discretizations::{parse_boundary_condition, BoxedComplex};
use tvf_spectral::{compute_basis, BasisComparison, BasisRequest, SampledBasis};

/// Arguments of `tvf compare`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf compare bunny-closed.obj -k 100 --discretization \
conforming-barycentric --discretization dec-circumcentric --discretization whitney-galerkin\n  \
tvf compare --example genus2 -k 60 --discretization dec-circumcentric --complex my-dec/\n\n\
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
    #[command(flatten)]
    input: MeshInput,
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

/// Builds every entry, computes and samples its basis, and prints the comparison.
pub fn run(args: CompareArgs, context: &RunContext) -> Result<()> {
    if args.count == 0 {
        bail!("-k 0: ask for at least one field");
    }
    let names = entry_names(&args)?;
    let loaded = args.input.load()?;
    let mesh = loaded.mesh;
    let identity: Vec<usize> = (0..mesh.vertex_count()).collect();
    let original_vertex = args.input.original_vertex().unwrap_or(&identity).to_vec();
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
                .with_context(|| args.input.label())?,
            EntryName::Folder(dir) => Box::new(
                tvf_spectral::read_complex_folder(dir, &mesh, &original_vertex).with_context(
                    || format!("--complex {} on {}", dir.display(), args.input.label()),
                )?,
            ),
        };
        entries.push(compute_entry(complex, label, args.count, &args.input)?);
    }
    let comparisons = entries[1..]
        .iter()
        .map(|entry| BasisComparison::new(&mesh, &entries[0].sampled, &entry.sampled))
        .collect::<Result<Vec<_>, _>>()
        .with_context(|| args.input.label())?;
    if args.json {
        print_json(&args, &mesh, &entries, &comparisons)
    } else {
        print_tables(&args, &mesh, &entries, &comparisons);
        Ok(())
    }
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
    mesh: &SurfaceMesh,
    entries: &[ComparedEntry],
    comparisons: &[BasisComparison],
) {
    println!(
        "mesh {} ({} faces), K = {} fields",
        args.input.label(),
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
        "mesh": args.input.label(),
        "faces": mesh.face_count(),
        "fields": args.count,
        "entries": entries,
        "comparisons": comparisons,
    });
    println!("{}", serde_json::to_string_pretty(&out)?);
    Ok(())
}
