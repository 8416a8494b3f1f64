//! Criterion benchmarks: factorization and the 500 lowest eigenpairs of the cotan (P1) and
//! Crouzeix–Raviart stiffness/mass pairs of bunny-closed and armadillo-x4
//! (from `../shared/meshes`; skipped with a message when absent).
//! `TVF_BENCH_K` overrides the number of eigenpairs (default 500).

#[allow(dead_code)]
mod mesh_matrices;

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use std::time::Duration;
use tvf_solvers::{convert::shifted_upper_triangle, lowest_eigenpairs, EigenOptions, SparseLdlt};

fn solver_benches(c: &mut Criterion) {
    let k: usize = std::env::var("TVF_BENCH_K")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(500);
    for mesh in ["bunny-closed.obj", "armadillo-x4.obj"] {
        let Some(path) = mesh_matrices::shared_mesh(mesh) else {
            println!("skipping {mesh}: ../shared/meshes/{mesh} not found");
            continue;
        };
        let (positions, faces) = match mesh_matrices::read_obj(&path) {
            Ok(m) => m,
            Err(e) => {
                println!("skipping {mesh}: {e}");
                continue;
            }
        };
        let pairs = [
            ("cotan", mesh_matrices::cotan(&positions, &faces)),
            (
                "crouzeix-raviart",
                mesh_matrices::crouzeix_raviart(&positions, &faces),
            ),
        ];
        for (kind, pair) in &pairs {
            let mut group = c.benchmark_group(format!("{mesh}/{kind}"));
            group
                .sample_size(10)
                .warm_up_time(Duration::from_millis(500))
                .measurement_time(Duration::from_secs(3));
            let Ok(upper) = shifted_upper_triangle(&pair.stiffness, &pair.mass, -1e-6) else {
                println!("skipping {mesh}/{kind}: invalid matrix");
                continue;
            };
            group.bench_function("symbolic+numeric factorization", |b| {
                b.iter(|| SparseLdlt::new(upper.as_ref()).map(|f| f.factor_len()))
            });
            if let Ok(mut ldlt) = SparseLdlt::new(upper.as_ref()) {
                group.bench_function("numeric refactorization", |b| {
                    b.iter(|| ldlt.refactor(upper.as_ref()))
                });
            }
            // One solve takes seconds: flat sampling runs one iteration per sample (10 in all)
            // instead of criterion's linear 1 + 2 + … + 10 iterations.
            group
                .sampling_mode(SamplingMode::Flat)
                .measurement_time(Duration::from_secs(20));
            group.bench_function(format!("{k} lowest eigenpairs"), |b| {
                b.iter(|| {
                    lowest_eigenpairs(&pair.stiffness, &pair.mass, k, &EigenOptions::default())
                        .map(|r| r.statistics.solves())
                })
            });
            group.finish();
        }
    }
}

criterion_group!(benches, solver_benches);
criterion_main!(benches);
