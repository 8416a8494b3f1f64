//! End-to-end: `tvf info` on built-in examples and files, text and JSON, and its errors.

use crate::common::assert_success;
use serde_json::Value;
use std::process::{Command, Output};

fn tvf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args(args)
        .output()
        .expect("the tvf binary runs")
}

fn info_json(args: &[&str]) -> Value {
    let mut all = vec!["info", "--json"];
    all.extend_from_slice(args);
    let output = tvf(&all);
    assert_success(&output);
    serde_json::from_slice(&output.stdout).expect("info --json prints JSON")
}

#[test]
fn every_example_reports_its_topology() {
    let expected = [
        ("icosphere", 0, 1280),
        ("torus", 1, 2304),
        ("bumpy-torus", 1, 9216),
        ("genus0", 0, 448),
        ("genus1", 1, 640),
        ("genus2", 2, 1184),
        ("genus3", 3, 1728),
        ("genus4", 4, 2272),
    ];
    for (name, genus, faces) in expected {
        let report = info_json(&["--example", name]);
        assert_eq!(report["genus"], genus, "{name}");
        assert_eq!(report["faces"], faces, "{name}");
        assert_eq!(report["closed"], true);
        assert_eq!(report["components"], 1);
        assert_eq!(report["boundary_loops"], 0);
        assert_eq!(report["warnings"].as_array().unwrap().len(), 0);
        let (v, e, f) = (
            report["vertices"].as_i64().unwrap(),
            report["edges"].as_i64().unwrap(),
            report["faces"].as_i64().unwrap(),
        );
        assert_eq!(v - e + f, 2 - 2 * genus, "{name}: Euler");
        let min = report["min_angle_deg"].as_f64().unwrap();
        let max = report["max_angle_deg"].as_f64().unwrap();
        assert!(0.0 < min && min <= 60.0 && (60.0..180.0).contains(&max));
        assert!(report["signed_volume"].as_f64().unwrap() > 0.0);
    }
}

#[test]
fn file_report_in_text_lists_warnings() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("open.obj");
    // A square with an unreferenced vertex: one boundary loop, one warning.
    std::fs::write(
        &path,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nf 1 2 3 4\n",
    )
    .unwrap();
    let output = tvf(&["info", path.to_str().unwrap()]);
    assert!(output.status.success());
    let text = String::from_utf8(output.stdout).unwrap();
    assert!(text.contains("boundary loops 1"), "{text}");
    assert!(text.contains("closed         no"), "{text}");
    assert!(text.contains("1 unreferenced vertices dropped"), "{text}");
    let report = info_json(&[path.to_str().unwrap()]);
    assert_eq!(report["vertices"], 4);
    assert_eq!(report["file_vertices"], 5);
    assert_eq!(report["unreferenced_vertices"], 1);
    assert_eq!(report["max_angle_deg"], 90.0);
}

#[test]
fn bad_input_exits_1_with_the_file_named_on_stderr() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bowtie.off");
    std::fs::write(
        &path,
        "OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n3 0 1 2\n3 0 3 4\n",
    )
    .unwrap();
    for args in [
        vec!["info", path.to_str().unwrap()],
        vec!["info", "--json", "/no/such/mesh.ply"],
        vec!["info", "mesh.stl"],
    ] {
        let output = tvf(&args);
        assert_eq!(output.status.code(), Some(1), "{args:?}");
        assert!(output.stdout.is_empty());
        let stderr = String::from_utf8(output.stderr).unwrap();
        let file = std::path::Path::new(args.last().unwrap())
            .file_name()
            .unwrap();
        assert!(stderr.contains(file.to_str().unwrap()), "{stderr}");
    }
    let stderr = String::from_utf8(tvf(&["info", path.to_str().unwrap()]).stderr).unwrap();
    assert!(stderr.contains("vertex 0 is non-manifold"), "{stderr}");
}

#[test]
fn usage_errors_exit_2() {
    assert_eq!(tvf(&["info"]).status.code(), Some(2));
    assert_eq!(tvf(&["info", "--example", "teapot"]).status.code(), Some(2));
    assert_eq!(
        tvf(&["info", "x.obj", "--example", "torus"]).status.code(),
        Some(2)
    );
}
