//! Plain timed run of the eigensolver on the benchmark meshes (numbers for the report).
//!
//! `cargo run --release -p tvf-solvers --example eigen_bench -- [MESH.obj ...] [--k K] [--kind cotan|cr|both]`
//! `[--block B] [--tol T] [--interval I] [--concurrent C (intervals at a time)] [--threads T]`
//! Without mesh arguments it uses bunny-closed.obj and armadillo-x4.obj from ../shared/meshes.

#[allow(dead_code)]
mod mesh_matrices;

use std::path::PathBuf;
use std::time::Instant;
use tvf_solvers::{convert::shifted_upper_triangle, lowest_eigenpairs, EigenOptions, SparseLdlt};

fn main() {
    let mut args = std::env::args().skip(1);
    let mut meshes: Vec<PathBuf> = Vec::new();
    let mut k = 500;
    let mut kind = String::from("both");
    let mut options = EigenOptions::default();
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--k" => k = next_value(&mut args, k),
            "--kind" => kind = args.next().unwrap_or(kind),
            "--block" => options.block_size = next_value(&mut args, options.block_size),
            "--threads" => {
                let threads: usize = next_value(&mut args, 1);
                options.parallelism = if threads > 1 {
                    faer::Par::rayon(threads)
                } else {
                    faer::Par::Seq
                };
            }
            "--concurrent" => options.threads = next_value(&mut args, options.threads),
            "--interval" => options.interval_size = next_value(&mut args, options.interval_size),
            "--tol" => options.tolerance = next_value(&mut args, options.tolerance),
            other => meshes.push(PathBuf::from(other)),
        }
    }
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
    for mesh in &meshes {
        let (positions, faces) = match mesh_matrices::read_obj(mesh) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("eigen_bench: {e}");
                continue;
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
            let start = Instant::now();
            let result =
                lowest_eigenpairs(&pair.stiffness, &pair.mass, k, &options).expect("eigensolver");
            let seconds = start.elapsed().as_secs_f64();
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
        }
    }
}

/// The next argument parsed as a `T`, or `current` if it is missing or does not parse.
fn next_value<T: std::str::FromStr>(args: &mut impl Iterator<Item = String>, current: T) -> T {
    args.next().and_then(|s| s.parse().ok()).unwrap_or(current)
}
