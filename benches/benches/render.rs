//! Rendering and streamline tracing at the sizes the tools meet: a 327,680-face sphere at
//! 1600×1200 (shaded, colour map, arrows / LIC) and a few thousand streamlines on 81,920 faces.

use criterion::{criterion_group, criterion_main, Criterion};
use tvf_core::generate::icosphere;
use tvf_core::geometry::cross;
use tvf_core::TriangleMesh;
use tvf_render::{
    render, trace_streamlines, ColorMap, FaceScalar, FieldLayer, FieldStyle, RenderOptions, Scene,
    StreamlineOptions,
};

fn rotation_field(mesh: &TriangleMesh) -> Vec<[f64; 3]> {
    let p = mesh.positions();
    mesh.faces()
        .iter()
        .map(|f| {
            let c = [0, 1, 2].map(|k| (p[f[0]][k] + p[f[1]][k] + p[f[2]][k]) / 3.0);
            cross([0.3, 1.0, 0.2], c)
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let big = icosphere(7);
    let field = rotation_field(&big);
    let magnitude: Vec<f64> = field.iter().map(|v| tvf_core::geometry::norm(*v)).collect();
    let options = RenderOptions {
        width: 1600,
        height: 1200,
        ..Default::default()
    };
    let mut group = c.benchmark_group("render");
    group.sample_size(10);
    let shaded = Scene::default();
    group.bench_function("shaded_327k_faces_1600x1200", |b| {
        b.iter(|| render(&big, &shaded, &options).unwrap())
    });
    let arrows = Scene {
        face_scalar: Some(FaceScalar::new(magnitude.clone(), ColorMap::Viridis, "|u|")),
        fields: vec![FieldLayer {
            vectors: field.clone(),
            style: FieldStyle::Arrows(Default::default()),
        }],
        ..Default::default()
    };
    group.bench_function("colormap_arrows_327k_faces_1600x1200", |b| {
        b.iter(|| render(&big, &arrows, &options).unwrap())
    });
    let lic = Scene {
        fields: vec![FieldLayer {
            vectors: field.clone(),
            style: FieldStyle::Lic(Default::default()),
        }],
        ..Default::default()
    };
    group.bench_function("lic_327k_faces_1600x1200", |b| {
        b.iter(|| render(&big, &lic, &options).unwrap())
    });
    group.finish();

    let medium = icosphere(6);
    let field = rotation_field(&medium);
    let mut group = c.benchmark_group("streamlines");
    group.sample_size(10);
    let opts = StreamlineOptions {
        count: 3000,
        ..Default::default()
    };
    group.bench_function("3000_lines_82k_faces", |b| {
        b.iter(|| trace_streamlines(&medium, &field, &opts).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
