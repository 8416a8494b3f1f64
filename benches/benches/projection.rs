//! Projection of a field onto 2×1000 basis fields (`c = Uᵀ M_X v`) and reconstruction
//! (`v = U c`) on the Hand mesh (12,184 faces), beside the paper's 0.67 s and 0.06 s
//! (Section 8.6; Java, 2015 laptop).
//!
//! The basis is a stand-in: `U = M_X^{-1/2} Q` with `Q` the thin QR factor of a seeded random
//! `2F × 2000` matrix, so `Uᵀ M_X U = I` exactly as for the eigenfields. Projection and
//! reconstruction are a dense `2F × d` matrix–vector product and cost the same whatever the
//! columns are, so this measures what the eigenfield basis would cost without spending minutes
//! computing 2000 eigenfields inside the benchmark. Skipped (with a message) when
//! `../shared/meshes/hand.obj` is absent.

use criterion::{criterion_group, criterion_main, Criterion};
use faer::Mat;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::time::Duration;
use tvf_core::discretization::{HodgeComplex, Mass};
use tvf_discretizations::{Conforming, MassLumping};
use tvf_spectral::{FieldFamily, SpectralBasis};

/// Basis size of the paper's measurement: 1000 integrable + 1000 co-integrable fields.
const FIELDS: usize = 2000;

fn hand_mesh() -> Option<tvf_core::TriangleMesh> {
    let path = tvf_test_support::shared_mesh("hand.obj")?;
    match tvf_core::io::load_mesh(&path) {
        Ok(loaded) => loaded.mesh.into_triangles().ok(),
        Err(error) => {
            eprintln!("skipping projection benchmark: {error}");
            None
        }
    }
}

/// An `M_X`-orthonormal `2F × FIELDS` basis from a QR factorisation of a random matrix.
fn orthonormal_stand_in(field_mass: &Mass) -> SpectralBasis {
    let mass = field_mass.diagonal_values().expect("a lumped field mass");
    let rows = mass.len();
    let mut rng = ChaCha8Rng::seed_from_u64(2017);
    let random = Mat::from_fn(rows, FIELDS, |_, _| rng.random_range(-1.0..1.0));
    let q = random.qr().compute_thin_Q();
    let fields = Mat::from_fn(rows, FIELDS, |i, j| q[(i, j)] / mass[i].sqrt());
    let eigenvalues: Vec<f64> = (0..FIELDS).map(|j| (j / 2 + 1) as f64).collect();
    let families = (0..FIELDS)
        .map(|j| {
            if j % 2 == 0 {
                FieldFamily::Integrable
            } else {
                FieldFamily::Cointegrable
            }
        })
        .collect();
    let mut basis = SpectralBasis::new(eigenvalues, families, fields, field_mass.clone())
        .expect("consistent stand-in basis");
    basis.store_single_precision_copy();
    basis
}

fn projection(c: &mut Criterion) {
    let Some(mesh) = hand_mesh() else { return };
    let complex =
        Conforming::new(&mesh, MassLumping::Barycentric).expect("hand.obj is a valid closed mesh");
    let basis = orthonormal_stand_in(complex.m1());
    let mass = complex.m1().diagonal_values().unwrap().to_vec();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let field: Vec<f64> = (0..mass.len())
        .map(|_| rng.random_range(-1.0..1.0))
        .collect();
    let coefficients = basis.coefficients(&field).expect("field fits");
    eprintln!(
        "hand: {} faces, basis 2F × d = {} × {}; paper: projection 0.67 s, reconstruction 0.06 s",
        mesh.face_count(),
        basis.field_dimension(),
        basis.len()
    );
    let mut group = c.benchmark_group("hand_2x1000");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(8));
    group.bench_function("projection (paper 0.67 s)", |b| {
        b.iter(|| basis.coefficients(black_box(&field)).expect("field fits"))
    });
    group.bench_function("reconstruction f64 (paper 0.06 s)", |b| {
        b.iter(|| {
            basis
                .reconstruct(black_box(&coefficients))
                .expect("coefficients fit")
        })
    });
    group.bench_function("reconstruction f32 copy (paper 0.06 s)", |b| {
        b.iter(|| {
            basis
                .reconstruct_f32(black_box(&coefficients))
                .expect("coefficients fit")
        })
    });
    group.finish();
}

criterion_group!(benches, projection);
criterion_main!(benches);
