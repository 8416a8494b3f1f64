//! Criterion benchmarks: factorization and the 500 lowest eigenpairs of the cotan (P1) and
//! Crouzeix–Raviart stiffness / lumped-mass pairs of bunny-closed and armadillo-x4
//! (from `../shared/meshes`; skipped with a message when absent), the potential pencils
//! `(d0ᵀ M1 d0, M0)` of the catalog's `conforming-barycentric` and `nonconforming-barycentric`.
//! `TVF_BENCH_K` overrides the number of eigenpairs (default 500).
//! Run: `cargo bench -p tvf-benches --bench eigen`.

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use sprs::CsMat;
use std::time::Duration;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};
use tvf_solvers::{convert::shifted_upper_triangle, lowest_eigenpairs, EigenOptions, SparseLdlt};

/// A scalar stiffness matrix (`n × n`) with its diagonal (lumped) mass (`n` values).
struct StiffnessMass {
    stiffness: CsMat<f64>,
    mass: Vec<f64>,
}

/// The potential pencil of `complex`, whose `M0` is diagonal.
fn potential_pencil(complex: &dyn HodgeComplex) -> StiffnessMass {
    StiffnessMass {
        stiffness: complex.potential_stiffness().clone(),
        mass: complex
            .m0()
            .diagonal_values()
            .expect("a lumped potential mass")
            .to_vec(),
    }
}

fn solver_benches(c: &mut Criterion) {
    let k: usize = std::env::var("TVF_BENCH_K")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(500);
    for mesh in ["bunny-closed.obj", "armadillo-x4.obj"] {
        let Some(path) = tvf_test_support::shared_mesh(mesh) else {
            continue;
        };
        let loaded = tvf_core::io::load_mesh(&path).map(|loaded| loaded.mesh.into_triangles().ok());
        let Ok(Some(triangles)) = loaded else {
            println!("skipping {mesh}: not a triangle mesh that loads");
            continue;
        };
        let (Ok(cotan), Ok(crouzeix_raviart)) = (
            Conforming::new(&triangles, MassLumping::Barycentric),
            Nonconforming::new(&triangles, MassLumping::Barycentric),
        ) else {
            println!("skipping {mesh}: the complexes do not assemble");
            continue;
        };
        let pairs = [
            ("cotan", potential_pencil(&cotan)),
            ("crouzeix-raviart", potential_pencil(&crouzeix_raviart)),
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
