//! Criterion benchmarks of the Fourier basis (Section 6): the paper's "bases setup" column of
//! Table 1 (1000 eigenfields = 500 integrable + 500 co-integrable) on bunny-closed, a smaller
//! basis on kitten, and reconstruction from the dense (f64, f32) and the eigenfunction forms.
//!
//! Meshes come from `../shared/meshes`; a missing mesh is skipped with a message.
//! Run: `cargo bench -p tvf-benches --bench basis` (bunny-closed takes minutes per sample).

use criterion::{criterion_group, criterion_main, Criterion};
use std::time::Duration;
use tvf_core::io::load_mesh;
use tvf_core::TriangleMesh;
use tvf_discretizations::{Conforming, MassLumping};
use tvf_spectral::{compute_basis, BasisRequest};

fn shared_mesh(name: &str) -> Option<TriangleMesh> {
    let path = tvf_test_support::shared_mesh(&format!("{name}.obj"))?;
    match load_mesh(&path) {
        Ok(loaded) => loaded.mesh.into_triangles().ok(),
        Err(error) => {
            eprintln!("skipping {name}: {error}");
            None
        }
    }
}

fn basis_setup(c: &mut Criterion) {
    for (name, pairs, samples) in [("kitten", 100, 10), ("bunny-closed", 500, 10)] {
        let Some(mesh) = shared_mesh(name) else {
            continue;
        };
        let complex = match Conforming::new(&mesh, MassLumping::Barycentric) {
            Ok(complex) => complex,
            Err(error) => {
                eprintln!("skipping {name}: {error}");
                continue;
            }
        };
        let mut group = c.benchmark_group("basis");
        group.sample_size(samples);
        group.measurement_time(Duration::from_secs(30));
        group.warm_up_time(Duration::from_millis(1));
        group.bench_function(
            format!("{name} ({} faces) {pairs}+{pairs}", mesh.face_count()),
            |b| b.iter(|| compute_basis(&complex, &BasisRequest::pairs(pairs))),
        );
        group.finish();
        if name == "kitten" {
            reconstruction(c, &complex, pairs);
        }
    }
}

fn reconstruction(c: &mut Criterion, complex: &Conforming, pairs: usize) {
    let Ok(basis) = compute_basis(
        complex,
        &BasisRequest::pairs(pairs)
            .keeping_eigenfunctions()
            .with_single_precision_copy(),
    ) else {
        return;
    };
    let coefficients: Vec<f64> = (0..basis.len()).map(|i| 1.0 / (1.0 + i as f64)).collect();
    let mut group = c.benchmark_group("reconstruct kitten");
    group.bench_function("dense f64", |b| b.iter(|| basis.reconstruct(&coefficients)));
    group.bench_function("dense f32 copy", |b| {
        b.iter(|| basis.reconstruct_f32(&coefficients))
    });
    if let Some(compact) = basis.eigenfunctions() {
        group.bench_function("eigenfunctions (sparse gradients)", |b| {
            b.iter(|| compact.reconstruct(complex, &coefficients))
        });
    }
    group.finish();
}

criterion_group!(benches, basis_setup);
criterion_main!(benches);
