//! A fingerprint of the eigensolver's output bits on a fixed generated problem: the cotan
//! stiffness and lumped mass of a jittered `60 × 50` grid, its 200 lowest eigenpairs through the
//! sparse Krylov path (dense threshold 100, intervals of 40, one thread for the products).
//! Two builds that print the same hash computed the same values and vectors bit for bit.
//!
//! `cargo run --release -p tvf-solvers --example eigen_fingerprint`

#[allow(dead_code)]
mod mesh_matrices;

use std::hash::{DefaultHasher, Hasher};
use tvf_solvers::{lowest_eigenpairs, EigenOptions};

fn main() {
    let (positions, faces) = mesh_matrices::grid(60, 50, 0.3);
    let pair = mesh_matrices::cotan(&positions, &faces);
    let options = EigenOptions {
        dense_threshold: 100,
        interval_size: 40,
        parallelism: faer::Par::Seq,
        threads: 2,
        ..EigenOptions::default()
    };
    let result = lowest_eigenpairs(&pair.stiffness, &pair.mass, 200, &options)
        .expect("the grid pencil is solvable");
    let mut values = DefaultHasher::new();
    for v in &result.values {
        values.write_u64(v.to_bits());
    }
    let mut vectors = DefaultHasher::new();
    for j in 0..result.vectors.ncols() {
        for i in 0..result.vectors.nrows() {
            vectors.write_u64(result.vectors[(i, j)].to_bits());
        }
    }
    println!(
        "n = {}, k = {}, λ_1 = {:e}, λ_k = {:e}, {} solves",
        pair.mass.len(),
        result.values.len(),
        result.values[1],
        result.values[result.values.len() - 1],
        result.statistics.solves()
    );
    println!(
        "values {:016x} vectors {:016x}",
        values.finish(),
        vectors.finish()
    );
}
