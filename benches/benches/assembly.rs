//! Assembly time of the complexes and the derived operators at paper scale: a generated
//! icosphere with 327,680 faces (level 7), comparable to the paper's 331,904-face Armadillo.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use tvf_core::discretization::HodgeOperators;
use tvf_core::generate::icosphere;
use tvf_discretizations::{Conforming, HodgeDecomposer, MassLumping, Nonconforming};

fn assembly(c: &mut Criterion) {
    let mesh = icosphere(7);
    let mut group = c.benchmark_group(format!("assembly/icosphere7_{}_faces", mesh.face_count()));
    group.sample_size(10);
    for lumping in [MassLumping::Barycentric, MassLumping::Voronoi] {
        group.bench_function(format!("conforming_new/{}", lumping.name()), |b| {
            b.iter(|| black_box(Conforming::new(&mesh, lumping).expect("valid mesh")))
        });
    }
    group.bench_function("nonconforming_new/barycentric", |b| {
        b.iter(|| {
            black_box(Nonconforming::new(&mesh, MassLumping::Barycentric).expect("valid mesh"))
        })
    });
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).expect("valid mesh");
    group.bench_function("cotan_and_cr_stiffness", |b| {
        b.iter(|| {
            black_box((
                complex.potential_stiffness(),
                complex.co_potential_stiffness(),
            ))
        })
    });
    group.bench_function("dirichlet_energy_S", |b| {
        b.iter(|| black_box(complex.dirichlet_energy()))
    });
    group.bench_function("biharmonic_energy_B", |b| {
        b.iter(|| black_box(complex.biharmonic_energy()))
    });
    group.bench_function("hodge_decomposer_factor", |b| {
        b.iter(|| black_box(HodgeDecomposer::new(&complex).expect("closed mesh")))
    });
    let decomposer = HodgeDecomposer::new(&complex).expect("closed mesh");
    let field: Vec<f64> = (0..2 * mesh.face_count())
        .map(|i| (i as f64 * 0.37).sin())
        .collect();
    group.bench_function("hodge_decompose_one_field", |b| {
        b.iter(|| black_box(decomposer.decompose(&field).expect("valid field")))
    });
    group.finish();
}

criterion_group!(benches, assembly);
criterion_main!(benches);
