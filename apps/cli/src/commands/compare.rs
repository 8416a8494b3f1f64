//! `tvf compare`: discretizations side by side on one mesh — per entry its sizes, mass
//! non-zeros, assembly and basis times (as ratios to the reference, same run), peak memory,
//! family counts, its eigenvalues against the reference's per family, and the principal angles
//! between the eigenspaces of clusters of near-equal eigenvalues
//! ([`tvf_spectral::ComparisonReport`]); with `-o DIR` the tables (Markdown, CSV, JSON) and
//! side-by-side pictures of corresponding eigenfields ([`super::compare_pictures`]).
//! `--corpus FOLDER` runs every mesh × entry instead ([`super::compare_corpus`]).

use super::compare_corpus::{run_corpus_comparison, CorpusOptions};
use super::compare_entries::{build_entry, entry_names, measure_entry, reference_position};
use super::compare_pictures::{write_pictures, PictureRequest};
use crate::context::RunContext;
use crate::discretization_flags::{with_intrinsic_suffix, IntrinsicDelaunayFlag};
use crate::mesh_input::{MeshInput, OptionalMeshInput};
use crate::output_rules::{check_output, commit, stage};
use crate::picture_options::{parse_size, parse_view};
use anyhow::{bail, Context, Result};
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tvf_core::discretization::BoundaryCondition;
use tvf_core::SurfaceMesh;
use tvf_discretizations::parse_boundary_condition;
use tvf_spectral::eigenspace_angles::DEFAULT_CLUSTER_TOLERANCE;
use tvf_spectral::{write_folder_bytes, ComparisonReport, ResidentPeak};

const AFTER_HELP: &str = "Examples:
  tvf compare bunny-closed.obj -k 60 --discretization conforming-barycentric \\
      --discretization whitney-galerkin --discretization dec-circumcentric+intrinsic-delaunay -o cmp/
  tvf compare --example genus2 -k 60 --discretization dec-circumcentric --complex my-dec/ --json
  tvf compare --corpus meshes/ -k 50 --discretization conforming-barycentric \\
      --discretization whitney-galerkin [--scheduler tcp://HOST:8786]

The reference is the first entry unless --reference names another. Per entry: n0, n1, n2; the
non-zeros of M0, M1, M2 as stored; the seconds to assemble the matrices and to compute the
basis, each also as a ratio to the reference's in the same run; peak memory (the resident bytes
added at the peak while the entry ran: Linux VmHWM, reset per entry); the harmonic, integrable
and co-integrable fields among the K lowest; per family the relative eigenvalue differences
|la - lb| / max(la, lb) to the reference position by position (median / largest); and the
principal angles (radians) between eigenspaces: the reference's eigenvalues of each family are
grouped into clusters (consecutive eigenvalues whose relative gap is at most
--cluster-tolerance), and each cluster's span is compared with the other entry's fields at the
same positions of the family, so that degenerate eigenvalues do not produce noise. Fields are
compared as one tangent vector per face at its centroid with the area-weighted inner product,
so entries with different field spaces compare. A cluster cut by K (marked 'basis ends') may be
incomplete.

With -o DIR: compare.md, compare.csv (one line per entry), eigenvalues.csv (every family
eigenvalue of every entry), clusters.csv (every cluster's largest angle per entry),
compare.json (what --json prints) and eigenfield-FAMILY-N.png: the reference's N-th field of a
family beside each entry's nearest field of the matching eigenspace (its projection onto that
cluster's span), for the --pictures lowest of each family. The folder appears whole at the end.";

/// What `--intrinsic-delaunay` ([`IntrinsicDelaunayFlag`]) does for `tvf compare`: its help text.
const INTRINSIC_DELAUNAY_HELP: &str = "Every catalog entry on the intrinsic Delaunay triangulation of the mesh (`flip`, the default, \
    or `refine`, as for other commands): each id without an intrinsic suffix of its own gets \
    `+intrinsic-delaunay` (or `-refine`). To compare an entry on the input with the same entry on \
    the intrinsic triangulation, give the suffixed id instead";

/// Arguments of `tvf compare`.
#[derive(Args)]
#[command(
    after_help = AFTER_HELP,
    mut_arg("intrinsic_delaunay", |arg| arg.help(INTRINSIC_DELAUNAY_HELP)),
    mut_arg("mesh", |arg| arg
        .help("Mesh file (.obj, .off or .ply); omit with --example or --corpus")
        .required_unless_present_any(["example", "corpus"]))
)]
pub struct CompareArgs {
    #[command(flatten)]
    mesh: OptionalMeshInput,
    /// Split every polygon into triangles after loading (as for other commands' --triangulate).
    #[arg(long)]
    triangulate: bool,
    /// Every mesh file (.obj, .off, .ply) of FOLDER instead of one mesh: each entry on each mesh,
    /// reported as the entry's success rate with the reason of every failure, its median basis
    /// time and its eigenvalues against the reference's (catalog ids only: a --complex folder
    /// belongs to one mesh).
    #[arg(long, value_name = "FOLDER", conflicts_with_all = ["mesh", "example", "complexes"])]
    corpus: Option<PathBuf>,
    /// With --corpus: worker threads [default: one per core].
    #[arg(
        long,
        value_name = "N",
        requires = "corpus",
        conflicts_with = "scheduler"
    )]
    threads: Option<usize>,
    /// With --corpus: run the mesh × entry tasks on the Dask cluster whose scheduler is at
    /// ADDRESS (e.g. tcp://HOST:8786) instead of local threads. Runs the Python package's
    /// driver (`python3 -m tvf.corpus`; TVF_PYTHON names another interpreter): the workers need
    /// the package and the mesh folder at the same path, and know tvf's own catalog ids.
    #[arg(long, value_name = "ADDRESS", requires = "corpus")]
    scheduler: Option<String>,
    /// A catalog id to compare (with its modifiers, e.g. dec-circumcentric+intrinsic-delaunay);
    /// repeat the flag.
    #[arg(long = "discretization", value_name = "ID")]
    pub(super) discretizations: Vec<String>,
    /// A folder of your own matrices (as for `--complex` of other commands), compared after
    /// the catalog ids; repeat the flag for several.
    #[arg(long = "complex", value_name = "DIR")]
    pub(super) complexes: Vec<PathBuf>,
    /// The entry the others are compared with: one of the --discretization ids or --complex
    /// folders as given [default: the first entry].
    #[arg(long, value_name = "ID")]
    pub(super) reference: Option<String>,
    /// Boundary condition of the catalog entries on meshes with boundary (tangential or
    /// normal) [default: tangential].
    #[arg(long, value_name = "CONDITION", value_parser = parse_boundary_condition)]
    pub(super) boundary: Option<BoundaryCondition>,
    #[command(flatten)]
    intrinsic: IntrinsicDelaunayFlag,
    /// Basis size: the K lowest eigenfields of every entry, harmonic ones included.
    #[arg(short = 'k', value_name = "K")]
    count: usize,
    /// Largest relative gap (λ_next − λ) / λ_next between consecutive eigenvalues of one family
    /// inside one eigenspace cluster.
    #[arg(long, value_name = "GAP", default_value_t = DEFAULT_CLUSTER_TOLERANCE)]
    cluster_tolerance: f64,
    /// Output folder: the tables (Markdown, CSV, JSON) and the pictures; with --corpus, the
    /// corpus report (corpus.md, corpus.json).
    #[arg(short, long, value_name = "DIR")]
    output: Option<PathBuf>,
    /// With -o: pictures of the N lowest fields of each family (0: none).
    #[arg(long, value_name = "N", default_value_t = 2)]
    pictures: usize,
    /// With -o: size of one panel of a picture.
    #[arg(long, value_name = "WxH", default_value = "480x360")]
    size: String,
    /// With -o: the camera of the pictures, as `tvf render --view`.
    #[arg(
        long,
        value_name = "YAW,PITCH",
        default_value = "30,20",
        allow_hyphen_values = true
    )]
    view: String,
    /// Print JSON to stdout instead of tables.
    #[arg(long)]
    json: bool,
}

/// The one mesh of the arguments (a file or an example).
fn mesh_input(args: &CompareArgs) -> MeshInput {
    let mut input = args
        .mesh
        .input()
        .unwrap_or_else(|| MeshInput::file(PathBuf::new()));
    input.triangulate = args.triangulate;
    input
}

/// `--intrinsic-delaunay` applied to every catalog id without an intrinsic suffix of its own,
/// and to `--reference` where it names one of those ids.
fn with_intrinsic_flag(mut args: CompareArgs) -> CompareArgs {
    let mode = args.intrinsic.intrinsic_delaunay;
    let apply = |id: &String| with_intrinsic_suffix(id.clone(), mode);
    if let Some(reference) = &args.reference {
        if args.discretizations.contains(reference) {
            args.reference = Some(apply(reference));
        }
    }
    args.discretizations = args.discretizations.iter().map(apply).collect();
    args
}

/// Builds every entry, computes and samples its basis, and reports the comparison.
pub fn run(args: CompareArgs, context: &RunContext) -> Result<()> {
    let args = with_intrinsic_flag(args);
    if args.count == 0 {
        bail!("-k 0: ask for at least one field");
    }
    if !(args.cluster_tolerance >= 0.0 && args.cluster_tolerance < 1.0) {
        bail!(
            "--cluster-tolerance {}: give a relative gap in [0, 1)",
            args.cluster_tolerance
        );
    }
    let names = entry_names(&args)?;
    let reference = reference_position(&args, &names)?;
    if let Some(folder) = &args.corpus {
        let options = CorpusOptions {
            folder,
            ids: &args.discretizations,
            reference: &args.discretizations[reference],
            boundary: args.boundary.unwrap_or_default(),
            count: args.count,
            triangulate: args.triangulate,
            threads: args.threads,
            scheduler: args.scheduler.as_deref(),
            output: args.output.as_deref(),
            json: args.json,
        };
        return run_corpus_comparison(&options, context);
    }
    let input = mesh_input(&args);
    if let Some(out) = &args.output {
        let folders: Vec<Option<&Path>> =
            args.complexes.iter().map(|d| Some(d.as_path())).collect();
        check_output(out, &input, &folders)?;
    }
    let view = parse_view(&args.view)?;
    let size = parse_size(&args.size)?;
    let mesh = input.load()?.mesh;
    let identity: Vec<usize> = (0..mesh.vertex_count()).collect();
    let original_vertex = input.original_vertex().unwrap_or(&identity).to_vec();
    let mut entries = Vec::with_capacity(names.len());
    for name in &names {
        let peak = ResidentPeak::start();
        let start = Instant::now();
        let complex = build_entry(name, &args, context, &mesh, &original_vertex, &input)?;
        let assembly_seconds = start.elapsed().as_secs_f64();
        entries.push(measure_entry(
            complex,
            name.label(),
            assembly_seconds,
            peak,
            args.count,
            &input,
        )?);
    }
    let report = ComparisonReport::new(
        input.label(),
        &mesh,
        args.count,
        args.cluster_tolerance,
        reference,
        entries,
    )
    .with_context(|| input.label())?;
    let json = serde_json::to_string_pretty(&report.to_json())?;
    if let Some(out) = &args.output {
        let pictures = PictureRequest {
            per_family: args.pictures,
            panel: size,
            view,
        };
        write_report_folder(out, &report, &json, &mesh, &pictures)?;
    }
    if args.json {
        println!("{json}");
    } else {
        print!("{}", report.markdown());
        if let Some(out) = &args.output {
            println!("\nwrote {}", out.display());
        }
    }
    Ok(())
}

/// Writes the tables and pictures of `report` into the folder `out`, which appears whole.
fn write_report_folder(
    out: &Path,
    report: &ComparisonReport,
    json: &str,
    mesh: &SurfaceMesh,
    pictures: &PictureRequest,
) -> Result<()> {
    let staged = stage(out)?;
    for (name, text) in [
        ("compare.md", report.markdown()),
        ("compare.csv", report.entries_csv()),
        ("eigenvalues.csv", report.eigenvalues_csv()),
        ("clusters.csv", report.clusters_csv()),
        ("compare.json", format!("{json}\n")),
    ] {
        write_folder_bytes(&staged, name, text.as_bytes())?;
    }
    write_pictures(&staged, report, mesh, pictures)?;
    commit(staged)
}
