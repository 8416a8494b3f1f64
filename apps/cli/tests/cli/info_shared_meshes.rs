//! `tvf info --json` on every mesh in `../shared/meshes` reports what `stats.json` lists.
//!
//! stats.json's `vertices` counts every vertex in the file; tvf drops unreferenced vertices
//! (bunny.obj has 1,113), so its `vertices` is compared with stats' `vertices −
//! unreferenced_vertices`, and its `file_vertices` with stats' `vertices`. The two `-x4`
//! meshes are not in stats.json; they are checked against the counts in the meshes README.
//! Skips (with a message) where `../shared/meshes` does not exist; under `CI=true` that is a
//! failure.

use serde_json::Value;
use std::path::Path;
use std::process::Command;
use tvf_test_support::{shared_mesh, shared_meshes};

fn info(path: &Path) -> Value {
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args(["info", "--json"])
        .arg(path)
        .output()
        .expect("the tvf binary runs");
    assert!(
        output.status.success(),
        "{}: {}",
        path.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).expect("JSON output")
}

#[test]
fn shared_meshes_match_stats_json() {
    let Some(dir) = shared_meshes() else {
        return;
    };
    let stats: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("stats.json")).unwrap()).unwrap();
    let stats = stats.as_object().unwrap();
    assert!(stats.len() >= 9);
    // Run the files in parallel: two at a time is all the CI machine has.
    let names: Vec<&String> = stats.keys().collect();
    let reports: Vec<(String, Value)> = std::thread::scope(|scope| {
        let handles: Vec<_> = names
            .chunks(names.len().div_ceil(2))
            .map(|chunk| {
                let dir = &dir;
                scope.spawn(move || {
                    chunk
                        .iter()
                        .map(|name| (name.to_string(), info(&dir.join(name))))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    });
    for (name, report) in reports {
        let expected = &stats[&name];
        let unreferenced = expected["unreferenced_vertices"].as_u64().unwrap();
        let file_vertices = expected["vertices"].as_u64().unwrap();
        assert_eq!(report["file_vertices"], file_vertices, "{name}");
        assert_eq!(report["unreferenced_vertices"], unreferenced, "{name}");
        assert_eq!(report["vertices"], file_vertices - unreferenced, "{name}");
        for key in ["edges", "faces", "components", "boundary_loops", "closed"] {
            assert_eq!(report[key], expected[key], "{name}: {key}");
        }
        assert_eq!(report["genus"], expected["genus_total"], "{name}: genus");
        assert_eq!(
            report["euler_characteristic"], expected["euler_characteristic"],
            "{name}"
        );
        for key in ["min_angle_deg", "max_angle_deg"] {
            let (ours, theirs) = (
                report[key].as_f64().unwrap(),
                expected[key].as_f64().unwrap(),
            );
            assert!(
                (ours - theirs).abs() < 1e-6,
                "{name}: {key} {ours} vs {theirs}"
            );
        }
        let slivers = expected["faces_with_angle_below_1deg"].as_u64().unwrap();
        let warnings = report["warnings"].as_array().unwrap();
        let sliver_warning = format!("{slivers} faces have an angle below 1°");
        assert_eq!(
            warnings
                .iter()
                .any(|w| w.as_str() == Some(sliver_warning.as_str())),
            slivers > 0,
            "{name}: {warnings:?}"
        );
    }
}

#[test]
fn shared_meshes_paper_scale_copies_load() {
    // Counts from ../shared/meshes/README.md ("Paper-scale copies for timing").
    for (name, vertices, faces, genus) in [
        ("armadillo-x4.obj", 172_966, 345_928, 0),
        ("bumpy-torus-x4.obj", 63_504, 127_008, 1),
    ] {
        let Some(path) = shared_mesh(name) else {
            continue;
        };
        let report = info(&path);
        assert_eq!(report["vertices"], vertices, "{name}");
        assert_eq!(report["faces"], faces, "{name}");
        assert_eq!(report["genus"], genus, "{name}");
        assert_eq!(report["closed"], true, "{name}");
        assert_eq!(report["components"], 1, "{name}");
    }
}
