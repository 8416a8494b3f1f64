//! Timed runs of the eigensolver on the benchmark meshes (numbers for the report): each mesh
//! and kind of pencil solved in `--runs` processes of their own; the first run's report (sizes,
//! factorizations, solves, accuracy, phases) and the median wall and processor seconds of the
//! solve over the runs, with the machine's load before and after.
//!
//! `cargo run --release -p tvf-solvers --example eigen_bench -- [MESH.obj ...] [--k K] [--kind cotan|cr|both]`
//! `[--runs N] [--block B] [--tol T] [--interval I] [--concurrent C (intervals at a time)] [--threads T]`
//! Without mesh arguments it uses bunny-closed.obj and armadillo-x4.obj from ../shared/meshes;
//! 3 runs by default.

#[allow(dead_code)]
mod bench_runs;
#[allow(dead_code)]
mod mesh_matrices;

use bench_runs::{median, range, run_child, Timing};
use std::path::PathBuf;
use std::time::Instant;
use tvf_solvers::{
    convert::shifted_upper_triangle, lowest_eigenpairs, process_cpu_seconds, EigenOptions,
    SparseLdlt,
};

/// The internal flag of a child process: solve the given meshes and kind once, here.
const CHILD: &str = "--child";

/// The command line: meshes, `--k`, `--kind`, `--runs`, the child flag, the solver options and
/// the options as given (for the child processes).
struct Arguments {
    meshes: Vec<PathBuf>,
    k: usize,
    kind: String,
    runs: usize,
    child: bool,
    passed: Vec<String>,
    options: EigenOptions<'static>,
}

fn parse_arguments() -> Arguments {
    let mut args = std::env::args().skip(1);
    let mut meshes: Vec<PathBuf> = Vec::new();
    let mut k = 500;
    let mut kind = String::from("both");
    let mut runs = 3;
    let mut child = false;
    // The options as given, for the child processes.
    let mut passed: Vec<String> = Vec::new();
    let mut options = EigenOptions::default();
    while let Some(arg) = args.next() {
        let mut value = || passed_value(&mut args, &arg, &mut passed);
        match arg.as_str() {
            "--k" => k = value().and_then(|v| v.parse().ok()).unwrap_or(k),
            "--kind" => kind = args.next().unwrap_or(kind),
            "--runs" => runs = args.next().and_then(|s| s.parse().ok()).unwrap_or(runs),
            CHILD => child = true,
            "--block" => {
                options.block_size = value()
                    .and_then(|v| v.parse().ok())
                    .unwrap_or(options.block_size)
            }
            "--threads" => {
                let threads: usize = value().and_then(|v| v.parse().ok()).unwrap_or(1);
                options.parallelism = if threads > 1 {
                    faer::Par::rayon(threads)
                } else {
                    faer::Par::Seq
                };
            }
            "--concurrent" => {
                options.threads = value()
                    .and_then(|v| v.parse().ok())
                    .unwrap_or(options.threads)
            }
            "--interval" => {
                options.interval_size = value()
                    .and_then(|v| v.parse().ok())
                    .unwrap_or(options.interval_size)
            }
            "--tol" => {
                options.tolerance = value()
                    .and_then(|v| v.parse().ok())
                    .unwrap_or(options.tolerance)
            }
            other => meshes.push(PathBuf::from(other)),
        }
    }
    Arguments {
        meshes,
        k,
        kind,
        runs,
        child,
        passed,
        options,
    }
}

fn main() {
    let Arguments {
        mut meshes,
        k,
        kind,
        runs,
        child,
        passed,
        options,
    } = parse_arguments();
    if meshes.is_empty() {
        meshes = ["bunny-closed.obj", "armadillo-x4.obj"]
            .iter()
            .filter_map(|m| mesh_matrices::shared_mesh(m))
            .collect();
        if meshes.is_empty() {
            println!("eigen_bench: ../shared/meshes not found, nothing to do");
            return;
        }
    }
    if !child {
        for mesh in &meshes {
            let kinds: &[&str] = match kind.as_str() {
                "both" => &["cotan", "cr"],
                "cr" => &["cr"],
                _ => &["cotan"],
            };
            for name in kinds {
                if let Err(e) = timed_runs(mesh, name, &passed, runs.max(1)) {
                    eprintln!("eigen_bench: {e}");
                }
            }
        }
        return;
    }
    for mesh in &meshes {
        solve_mesh(mesh, &kind, k, &options);
    }
}

/// One child's work on `mesh`: the factorization's times and `lowest_eigenpairs` of the `kind`
/// pencils ("cotan", "cr" or "both"), with their statistics and accuracy, then the timing line.
fn solve_mesh(mesh: &std::path::Path, kind: &str, k: usize, options: &EigenOptions<'_>) {
    let (positions, faces) = match mesh_matrices::read_obj(mesh) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("eigen_bench: {e}");
            return;
        }
    };
    let mut pairs = Vec::new();
    if kind == "cotan" || kind == "both" {
        pairs.push(("cotan", mesh_matrices::cotan(&positions, &faces)));
    }
    if kind == "cr" || kind == "both" {
        pairs.push((
            "crouzeix-raviart",
            mesh_matrices::crouzeix_raviart(&positions, &faces),
        ));
    }
    for (name, pair) in pairs {
        let n = pair.mass.len();
        let upper = shifted_upper_triangle(&pair.stiffness, &pair.mass, -1e-6)
            .expect("assembled matrix is valid");
        let start = Instant::now();
        let ldlt = SparseLdlt::new(upper.as_ref()).expect("shifted Laplacian factors");
        let analyse = start.elapsed().as_secs_f64();
        let mut ldlt = ldlt;
        let start = Instant::now();
        ldlt.refactor(upper.as_ref()).expect("refactor");
        let numeric = start.elapsed().as_secs_f64();
        let (start, cpu) = (Instant::now(), process_cpu_seconds());
        let result =
            lowest_eigenpairs(&pair.stiffness, &pair.mass, k, options).expect("eigensolver");
        let seconds = start.elapsed().as_secs_f64();
        let timing = Timing {
            wall: seconds,
            cpu: process_cpu_seconds() - cpu,
        };
        let worst = result.residuals.iter().fold(0.0f64, |m, r| m.max(*r));
        // M-orthonormality across slices/intervals (outside the timed region)
        let x = &result.vectors;
        let mx = faer::Mat::from_fn(n, x.ncols(), |i, j| pair.mass[i] * x[(i, j)]);
        let gram = x.transpose() * &mx;
        let mut gram_error = 0.0f64;
        for j in 0..gram.ncols() {
            for i in 0..gram.nrows() {
                let target = if i == j { 1.0 } else { 0.0 };
                gram_error = gram_error.max((gram[(i, j)] - target).abs());
            }
        }
        println!(
            "{} {name}: n = {n}, nnz(L) = {}, analyse+factor {analyse:.3} s, refactor {numeric:.3} s | k = {k}: {seconds:.2} s, {} factorizations, {} solves, λ ∈ [{:.3e}, {:.3e}], max residual {worst:.1e}, max |XᵀMX − I| {gram_error:.1e}",
            mesh.file_name().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
            ldlt.factor_len(),
            result.statistics.factorizations(),
            result.statistics.solves(),
            result.values.first().copied().unwrap_or(0.0),
            result.values.last().copied().unwrap_or(0.0),
        );
        let statistics = result.statistics;
        let max_field = result.field_residuals.iter().fold(0.0f64, |m, r| m.max(*r));
        print!("{}", statistics.phase_table());
        println!(
            "  refined pairs {}, max relative field residual {max_field:.1e}",
            statistics.refined_pairs
        );
        bench_runs::report_child(timing);
    }
}

/// `runs` child processes solving `kind` ("cotan" or "cr") on `mesh` with the options `passed`:
/// the first one's report, then the medians.
fn timed_runs(
    mesh: &std::path::Path,
    kind: &str,
    passed: &[String],
    runs: usize,
) -> Result<(), String> {
    let load_before = bench_runs::load();
    let mut args = vec![
        mesh.display().to_string(),
        "--kind".into(),
        kind.into(),
        CHILD.into(),
    ];
    args.extend(passed.iter().cloned());
    let mut timings: Vec<Timing> = Vec::new();
    for run in 0..runs {
        let (timing, output) = run_child(&args)?;
        if run == 0 {
            print!("{output}");
        }
        timings.push(timing);
    }
    let walls: Vec<f64> = timings.iter().map(|t| t.wall).collect();
    let cpus: Vec<f64> = timings.iter().map(|t| t.cpu).collect();
    let (lo, hi) = range(&walls);
    println!(
        "  {kind}, {runs} processes: median {:.2} s wall ({lo:.2}–{hi:.2}), {:.2} s processor; \
         load {load_before} → {}",
        median(&walls),
        median(&cpus),
        bench_runs::load()
    );
    Ok(())
}

/// The value after option `option`, recorded with it in `passed` (for the child processes).
fn passed_value(
    args: &mut impl Iterator<Item = String>,
    option: &str,
    passed: &mut Vec<String>,
) -> Option<String> {
    let value = args.next()?;
    passed.extend([option.to_owned(), value.clone()]);
    Some(value)
}
