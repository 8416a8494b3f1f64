//! What a second thread gives one slice's block solve: the Crouzeix–Raviart pencil of a mesh
//! (`n` = its edges, the size of the co-potential slices' Krylov vectors) factored once at a
//! shift inside its spectrum, then `--solves` solves of eight right-hand sides in elimination
//! order, either as one block on one thread (`--mode whole`, the packed loops) or as two
//! halves of four columns on two threads (`--mode halves`,
//! `SparseLdlt::solve_in_elimination_order_in_halves`). The solve is memory-bound, so instruction
//! counts do not tell; run each mode under `perf stat -e task-clock` and compare task-clock
//! (processor time) with the elapsed time. Prints the factor's size, the solves' median wall
//! time and the processor seconds of the solve phase, and checks that both modes give the same
//! solutions bit for bit.
//!
//! `cargo run --release -p tvf-solvers --example half_solve_bench -- MESH.obj [--mode whole|halves] [--solves N]`

#[allow(dead_code)]
mod mesh_matrices;

use faer::Mat;
use std::time::Instant;
use tvf_solvers::{convert::shifted_upper_triangle, process_cpu_seconds, SparseLdlt};

fn main() {
    let mut args = std::env::args().skip(1);
    let (mut mesh, mut mode, mut solves) = (None, String::from("whole"), 20usize);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--mode" => mode = args.next().unwrap_or(mode),
            "--solves" => solves = args.next().and_then(|s| s.parse().ok()).unwrap_or(solves),
            _ => mesh = Some(std::path::PathBuf::from(arg)),
        }
    }
    let Some(mesh) = mesh else {
        eprintln!("usage: half_solve_bench MESH.obj [--mode whole|halves] [--solves N]");
        std::process::exit(2);
    };
    if mode != "whole" && mode != "halves" {
        eprintln!("half_solve_bench: --mode must be whole or halves, not {mode}");
        std::process::exit(2);
    }
    let (positions, faces) = match mesh_matrices::read_obj(&mesh) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("half_solve_bench: {e}");
            std::process::exit(1);
        }
    };
    let pair = mesh_matrices::crouzeix_raviart(&positions, &faces);
    let n = pair.mass.len();
    // A shift inside the low spectrum (the factor's fill does not depend on it).
    let upper = shifted_upper_triangle(&pair.stiffness, &pair.mass, 10.0).expect("valid matrix");
    let start = Instant::now();
    let ldlt = SparseLdlt::new(upper.as_ref()).expect("the shifted pencil factors");
    println!(
        "n = {n}, nnz(L) = {} ({:.0} MB), factored in {:.1} s",
        ldlt.factor_len(),
        ldlt.factor_len() as f64 * 8e-6,
        start.elapsed().as_secs_f64()
    );
    let rhs = Mat::from_fn(n, 8, |i, j| ((i * 7 + j * 13) % 29) as f64 / 14.0 - 1.0);
    let solve = |block: &mut Mat<f64>| match mode.as_str() {
        "halves" => ldlt.solve_in_elimination_order_in_halves(block.as_mut()),
        _ => ldlt.solve_in_elimination_order(block.as_mut()),
    };
    let mut reference = rhs.clone();
    ldlt.solve_in_elimination_order(reference.as_mut());
    let mut walls = Vec::with_capacity(solves);
    let cpu = process_cpu_seconds();
    let mut block = rhs.clone();
    for _ in 0..solves {
        block.copy_from(&rhs);
        let start = Instant::now();
        solve(&mut block);
        walls.push(start.elapsed().as_secs_f64());
    }
    let cpu = process_cpu_seconds() - cpu;
    let identical =
        (0..8).all(|j| (0..n).all(|i| block[(i, j)].to_bits() == reference[(i, j)].to_bits()));
    assert!(
        identical,
        "the {mode} solve differs from the one-thread block solve"
    );
    walls.sort_by(f64::total_cmp);
    let total: f64 = walls.iter().sum();
    println!(
        "{mode}: {solves} solves of 8 right-hand sides, median {:.4} s (min {:.4}, max {:.4}), wall {total:.2} s, processor {cpu:.2} s ({:.2} threads busy); same bits as the one-thread solve",
        walls[walls.len() / 2],
        walls[0],
        walls[walls.len() - 1],
        cpu / total
    );
}
