//! End-to-end: `tvf check` on a mesh file (text and JSON, measured numbers, exit 1 naming the
//! failed check) and on generated meshes.

use crate::common::assert_success;
use serde_json::Value;
use std::process::{Command, Output};

fn tvf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args(args)
        .output()
        .expect("the tvf binary runs")
}

fn quad_torus(dir: &std::path::Path) -> String {
    let path = dir.join("torus.obj");
    let mesh = tvf_core::generate::torus(1.0, 0.4, 8, 5).unwrap();
    tvf_core::io::write_obj(&path, &mesh).unwrap();
    path.display().to_string()
}

#[test]
fn a_mesh_file_gets_every_check_with_its_measured_number() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = quad_torus(dir.path());
    let output = tvf(&[
        "check",
        &mesh,
        "--discretization",
        "conforming-barycentric",
        "--json",
    ]);
    assert_success(&output);
    let report: Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(report["passed"], true);
    let checks = report["checks"].as_array().unwrap();
    let named = |name: &str| checks.iter().find(|c| c["name"] == name).cloned();
    let j2 = named("rotation:J_squared").expect("a reference check of the entry");
    assert_eq!(j2["measured"], 0.0);
    let d1d0 = named("d1_d0_zero").expect("a core check");
    assert!(d1d0["measured"].as_f64().unwrap() <= d1d0["limit"].as_f64().unwrap());
    let text = tvf(&["check", &mesh, "--discretization", "conforming-barycentric"]);
    assert_success(&text);
    assert!(String::from_utf8_lossy(&text.stdout).contains("cotan_formula:potential"));
}

#[test]
fn a_refused_mesh_exits_1_naming_the_check() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = quad_torus(dir.path());
    let output = tvf(&["check", &mesh, "--discretization", "dec-barycentric"]);
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("failed checks: construction"), "{stderr}");
}

#[test]
fn generated_meshes_pass_and_write_no_counterexample() {
    let dir = tempfile::tempdir().unwrap();
    let counterexample = dir.path().join("ce.obj");
    let output = tvf(&[
        "check",
        "--discretization",
        "dec-circumcentric",
        "--cases",
        "3",
        "--seed",
        "5",
        "--json",
        "-q",
        "-o",
        counterexample.to_str().unwrap(),
    ]);
    assert_success(&output);
    let report: Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(report["cases_passed"], 3);
    assert_eq!(report["passed"], true);
    assert!(!counterexample.exists());
}
