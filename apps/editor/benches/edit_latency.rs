//! Round-trip latency of the editor over its real HTTP path: a scripted client changes the
//! direction of one vector constraint (`POST /api/edit`, a value-only `set`) and waits for the
//! whole new field frame (`2F` f32 values), 30 constraints active, d = 1000 basis fields.
//! Prints p50 / p95 / max of the round trip and the server's solve and map times.
//!
//! Meshes: `bunny-closed.obj` and `armadillo-x4.obj` from `../shared/meshes` (skipped with a
//! message if absent) and, always, a generated icosphere. The basis is **synthetic**: `d`
//! random fields (seeded, entries uniform with unit variance, scaled by `M_X^{-1/2} / √(2F)`, so
//! `Uᵀ M_X U = I` up to `O(1/√(2F))`) with Weyl-law eigenvalues `λ_i = 4π i / area`:
//! computing 1000 real eigenfields of these meshes takes minutes, while the timing of the
//! editing path depends only on the sizes.
//!
//! Run: `cargo bench -p tvf-editor --bench edit_latency` (`TVF_LATENCY_ROUNDS` sets the number
//! of timed round trips, default 200).

use std::io::Read;
use std::path::PathBuf;
use std::time::Instant;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde_json::json;
use tvf_core::{SurfaceMesh, TriangleMesh};
use tvf_design::ReducedBasis;
use tvf_discretizations::build_complex;
use tvf_editor::{decode_field_frame, Editor, EditorServer, EditorSetup};

const D: usize = 1000;
const CONSTRAINTS: usize = 30;

fn synthetic_basis(mesh: &TriangleMesh, d: usize) -> ReducedBasis {
    let n = 2 * mesh.face_count();
    let areas = mesh.face_areas();
    let mut rows = vec![0.0f64; n * d];
    let spread = 3f64.sqrt();
    rows.par_chunks_mut(d * 1024)
        .enumerate()
        .for_each(|(block, chunk)| {
            let mut rng = ChaCha8Rng::seed_from_u64(block as u64);
            for (k, row) in chunk.chunks_mut(d).enumerate() {
                let r = block * 1024 + k;
                let scale = 1.0 / (areas[r / 2] * n as f64).sqrt();
                for x in row.iter_mut() {
                    *x = rng.random_range(-spread..spread) * scale;
                }
            }
        });
    let area = mesh.total_area();
    let eigenvalues = (1..=d)
        .map(|i| 4.0 * std::f64::consts::PI * i as f64 / area)
        .collect();
    ReducedBasis::from_row_major(rows, n, eigenvalues, vec![false; d]).expect("synthetic basis")
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    let i = ((sorted.len() - 1) as f64 * p).round() as usize;
    sorted[i]
}

fn post(agent: &ureq::Agent, url: &str, body: &serde_json::Value) -> Vec<u8> {
    let response = agent
        .post(url)
        .header("Content-Type", "application/json")
        .send(body.to_string().as_bytes())
        .expect("POST /api/edit");
    let mut bytes = Vec::new();
    response
        .into_body()
        .into_reader()
        .read_to_end(&mut bytes)
        .expect("response body");
    bytes
}

fn bench(name: &str, mesh: TriangleMesh, rounds: usize) {
    let faces = mesh.face_count();
    let t = Instant::now();
    let basis = synthetic_basis(&mesh, D);
    let basis_seconds = t.elapsed().as_secs_f64();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mesh = SurfaceMesh::from(mesh);
    let complex =
        build_complex(tvf_discretizations::DEFAULT_DISCRETIZATION, None, &mesh).expect("operators");
    let editor = Editor::start(EditorSetup {
        mesh,
        basis,
        constraints: None,
        basis_size: None,
        complex,
    })
    .expect("editor");
    let server = EditorServer::start(editor, 0).expect("server");
    let url = format!(
        "http://{}/api/edit?token={}",
        server.address(),
        server.token()
    );
    let agent: ureq::Agent = ureq::Agent::config_builder()
        .http_status_as_error(true)
        .build()
        .into();
    let point = |rng: &mut ChaCha8Rng| {
        let (a, b): (f64, f64) = (rng.random(), rng.random());
        let (a, b) = if a + b > 1.0 {
            (1.0 - a, 1.0 - b)
        } else {
            (a, b)
        };
        json!([1.0 - a - b, a, b])
    };
    for k in 0..CONSTRAINTS {
        let face = rng.random_range(0..faces);
        let constraint = match k % 3 {
            0 => {
                json!({"id": format!("c{k}"), "kind": "vector", "face": face, "value": [1.0, 0.3, -0.2]})
            }
            1 => {
                json!({"id": format!("c{k}"), "kind": "divergence", "face": face, "barycentric": point(&mut rng), "value": 1.0})
            }
            _ => {
                json!({"id": format!("c{k}"), "kind": "curl", "face": face, "barycentric": point(&mut rng), "value": -1.0})
            }
        };
        post(
            &agent,
            &url,
            &json!({"op": "add", "constraint": constraint}),
        );
    }
    let moved_face = rng.random_range(0..faces);
    let (mut times, mut solve, mut map) = (Vec::new(), Vec::new(), Vec::new());
    for round in 0..rounds + 10 {
        let angle = round as f64 * 0.1;
        let op = json!({"op": "set", "constraint": {"id": "c0", "kind": "vector", "face": moved_face,
            "value": [angle.cos(), angle.sin(), 0.5 * (2.0 * angle).sin()]}});
        let start = Instant::now();
        let bytes = post(&agent, &url, &op);
        let frame = decode_field_frame(&bytes).expect("field frame");
        let elapsed = start.elapsed().as_secs_f64() * 1e3;
        assert_eq!(frame.coefficients.len(), 2 * faces);
        if round >= 10 {
            times.push(elapsed);
            solve.push(frame.status["solve_ms"].as_f64().unwrap_or(f64::NAN));
            map.push(frame.status["map_ms"].as_f64().unwrap_or(f64::NAN));
        }
    }
    // The HTTP floor: a tiny GET on the same kind of connection.
    let ping_url = format!(
        "http://{}/api/ping?token={}",
        server.address(),
        server.token()
    );
    let mut pings: Vec<f64> = (0..rounds)
        .map(|_| {
            let start = Instant::now();
            let mut body = Vec::new();
            let response = agent.get(&ping_url).call().expect("GET /api/ping");
            response
                .into_body()
                .into_reader()
                .read_to_end(&mut body)
                .expect("ping body");
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    pings.sort_by(f64::total_cmp);
    for v in [&mut times, &mut solve, &mut map] {
        v.sort_by(f64::total_cmp);
    }
    println!(
        "{name}: F = {faces}, d = {D}, {CONSTRAINTS} constraints, {rounds} round trips (basis set-up {basis_seconds:.1} s)\n  \
         round trip p50 {:.2} ms, p95 {:.2} ms, max {:.2} ms; server solve p50 {:.3} ms, map p50 {:.2} ms, frame {} KiB; \
         ping p50 {:.2} ms, p95 {:.2} ms",
        percentile(&times, 0.5),
        percentile(&times, 0.95),
        times[times.len() - 1],
        percentile(&solve, 0.5),
        percentile(&map, 0.5),
        (8 * faces + 1024) / 1024,
        percentile(&pings, 0.5),
        percentile(&pings, 0.95),
    );
    server.shutdown();
}

fn main() {
    // `cargo bench` passes `--bench`; `cargo test --benches` runs this too: keep that quick.
    let quick = !std::env::args().any(|a| a == "--bench");
    let rounds = std::env::var("TVF_LATENCY_ROUNDS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(if quick { 20 } else { 200 });
    bench("icosphere(5)", tvf_core::generate::icosphere(5), rounds);
    if quick {
        return;
    }
    let meshes = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/meshes");
    for file in ["bunny-closed.obj", "armadillo-x4.obj"] {
        let path = meshes.join(file);
        if !path.exists() {
            println!("{file}: skipped, {} not found", path.display());
            continue;
        }
        let mesh = tvf_core::io::load_mesh(&path).expect("mesh").mesh;
        bench(
            file,
            mesh.into_triangles().expect("a triangle mesh"),
            rounds,
        );
    }
}
