//! End-to-end: `tvf check` on a mesh file (text and JSON, measured numbers, exit 1 naming the
//! failed check) and on generated meshes; on polygon meshes (a file, and generated ones); the
//! accuracy checks (by default; the tests of other checks pass `--no-accuracy` to stay quick).

use crate::common::{self, assert_success};
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
        "--no-accuracy",
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
    let text = tvf(&[
        "check",
        "--no-accuracy",
        &mesh,
        "--discretization",
        "conforming-barycentric",
    ]);
    assert_success(&text);
    assert!(String::from_utf8_lossy(&text.stdout).contains("cotan_formula:potential"));
}

#[test]
fn a_refused_mesh_exits_1_naming_the_check() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = quad_torus(dir.path());
    let output = tvf(&[
        "check",
        "--no-accuracy",
        &mesh,
        "--discretization",
        "dec-barycentric",
    ]);
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
        "--no-accuracy",
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

fn polygon_mesh(dir: &std::path::Path) -> String {
    let path = dir.join("cube-sphere.obj");
    let mesh = tvf_core::generate::cube_sphere(2).unwrap();
    tvf_core::io::write_obj(&path, &mesh).unwrap();
    path.display().to_string()
}

#[test]
fn a_polygon_mesh_file_gets_polygon_dec_and_the_polygon_sampling_checks() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = polygon_mesh(dir.path());
    let output = tvf(&["check", "--no-accuracy", &mesh, "--json"]);
    assert_success(&output);
    let report: Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(report["discretization"], "polygon-dec");
    assert_eq!(report["passed"], true);
    let checks = report["checks"].as_array().unwrap();
    for name in [
        "d1_d0_zero",
        "kernel dimension",
        "polygon_sampling:sharp_of_flat",
        "polygon_sampling:one_vector_per_polygon",
        "polygon_point_evaluation:linear",
    ] {
        let check = checks
            .iter()
            .find(|c| c["name"] == name)
            .unwrap_or_else(|| panic!("{name} missing: {checks:?}"));
        assert_eq!(check["status"], "passed", "{check}");
    }
    let text = tvf(&[
        "check",
        "--no-accuracy",
        &mesh,
        "--discretization",
        "polygon-dec",
    ]);
    assert_success(&text);
    assert!(String::from_utf8_lossy(&text.stdout).contains("(24 faces)"));
}

#[test]
fn a_triangle_entry_on_a_polygon_mesh_exits_1_naming_the_construction() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = polygon_mesh(dir.path());
    let output = tvf(&[
        "check",
        "--no-accuracy",
        &mesh,
        "--discretization",
        "conforming-barycentric",
    ]);
    assert_eq!(output.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("conforming-barycentric"), "{stdout}");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("failed checks: construction"), "{stderr}");
}

#[test]
fn generated_polygon_meshes_pass_for_polygon_dec_and_are_refused_to_triangle_entries() {
    let dir = tempfile::tempdir().unwrap();
    let counterexample = dir.path().join("ce.obj");
    let output = tvf(&[
        "check",
        "--no-accuracy",
        "--discretization",
        "polygon-dec",
        "--cases",
        "4",
        "--seed",
        "3",
        "--json",
        "-q",
        "-o",
        counterexample.to_str().unwrap(),
    ]);
    assert_success(&output);
    let report: Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(report["cases_passed"], 4);
    assert_eq!(report["passed"], true);
    let checks = report["checks"].as_array().unwrap();
    assert!(
        checks
            .iter()
            .any(|c| c["name"] == "polygon_sampling:sharp_of_flat" && c["status"] == "passed"),
        "{checks:?}"
    );
    assert!(!counterexample.exists());
    let refused = tvf(&[
        "check",
        "--no-accuracy",
        "--discretization",
        "dec-barycentric",
        "--meshes",
        "polygons",
        "--cases",
        "2",
    ]);
    assert_eq!(refused.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains("--meshes polygons") && stderr.contains("dec-barycentric"),
        "{stderr}"
    );
}

/// Arguments that make a generated run meaningless or lose its result are refused before any
/// mesh is checked: `--cases 0` (once "passed" with exit 0), a counterexample path in a missing
/// folder or naming a folder (once found out only when a failure was to be written).
#[test]
fn cases_and_the_counterexample_path_are_checked_first() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().display().to_string();
    let missing = dir.path().join("no/x.obj").display().to_string();
    for (args, said) in [
        (vec!["--cases", "0"], "--cases 0"),
        (vec!["--cases", "64", "-o", &missing], "does not exist"),
        (vec!["--cases", "64", "-o", &folder], "is a folder"),
    ] {
        let output = common::output_within(
            Command::new(env!("CARGO_BIN_EXE_tvf"))
                .args(["check", "--discretization", "conforming-barycentric"])
                .args(&args),
            30,
        );
        assert_eq!(output.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains(said), "{args:?}: {stderr}");
        assert!(!stderr.contains("meshes passed"), "{args:?} ran: {stderr}");
    }
}

/// A complex whose eigenvalues cannot be computed (a field mass of denormal entries, `1e-310`:
/// the scaled pencil overflows) fails its spectral checks with a sentence, not a caught panic
/// and its backtrace.
#[test]
fn a_check_that_cannot_be_computed_fails_with_a_sentence() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = quad_torus(dir.path());
    let ops = dir.path().join("ops");
    let ops_text = ops.display().to_string();
    assert_success(&tvf(&["operators", &mesh, "-o", &ops_text]));
    let m1 = ops.join("M1.mtx");
    let text = std::fs::read_to_string(&m1).unwrap();
    let mut size_seen = false;
    let scaled: Vec<String> = text
        .lines()
        .map(|line| {
            if line.starts_with('%') || !size_seen {
                size_seen |= !line.starts_with('%');
                return line.to_string();
            }
            let words: Vec<&str> = line.split_whitespace().collect();
            let value: f64 = words[2].parse().unwrap();
            format!("{} {} {:e}", words[0], words[1], value * 1e-310)
        })
        .collect();
    std::fs::write(&m1, scaled.join("\n") + "\n").unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args(["check", &mesh, "--complex", &ops_text])
        .env("RUST_BACKTRACE", "1")
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    let (stdout, stderr) = (
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr),
    );
    assert!(
        !stderr.contains("panicked") && !stderr.contains("backtrace"),
        "{stderr}"
    );
    assert!(stdout.contains("cannot be computed"), "{stdout}");
    assert!(stderr.contains("failed checks"), "{stderr}");
}

/// The accuracy checks run by default and are reported with their numbers: the consistency
/// checks on the checked mesh and on the patches, the convergence orders with their tables.
#[test]
fn the_accuracy_checks_run_by_default_with_orders_and_tables() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sphere.obj");
    tvf_core::io::write_obj(&path, &tvf_core::generate::icosphere(2)).unwrap();
    let mesh = path.display().to_string();
    let output = tvf(&[
        "check",
        &mesh,
        "--discretization",
        "dec-circumcentric",
        "--json",
        "-q",
    ]);
    assert_success(&output);
    let report: Value = serde_json::from_slice(&output.stdout).unwrap();
    let checks = report["checks"].as_array().unwrap();
    let named = |name: &str| {
        checks
            .iter()
            .find(|c| c["name"] == name)
            .cloned()
            .unwrap_or_else(|| panic!("no check {name}"))
    };
    let order = named("convergence:jittered hemisphere:integrable");
    assert_eq!(order["status"], "passed");
    assert_eq!(order["comparison"], "at_least");
    assert!(order["measured"].as_f64().unwrap() >= 1.5, "{order}");
    assert!(order["detail"].as_str().unwrap().contains("1536 faces"));
    let energy = named("consistency:energy_of_linear:checked mesh");
    assert_eq!(energy["status"], "passed");
    // DEC co-potentials are 2-forms on faces: the co-potential patch test does not apply.
    let co = named("consistency:co_laplacian_of_linear:flat box");
    assert_eq!(co["status"], "not applicable");
    assert!(co["detail"].as_str().unwrap().contains("faces"), "{co}");
    let skipped = tvf(&[
        "check",
        &mesh,
        "--discretization",
        "dec-circumcentric",
        "--no-accuracy",
        "--json",
        "-q",
    ]);
    assert_success(&skipped);
    let report: Value = serde_json::from_slice(&skipped.stdout).unwrap();
    let names: Vec<&str> = report["checks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert!(!names.iter().any(|n| n.starts_with("convergence:")));
}

/// A Hodge star inverted by mistake (`M1 = primal/dual`, every entry of a DEC star replaced by
/// its reciprocal) in a `--complex` folder passes every structural check but fails the energy
/// of a linear function on the mesh; the convergence checks cannot run on a folder and say why.
#[test]
fn an_inverted_star_in_a_folder_fails_naming_the_consistency_check() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sphere.obj");
    tvf_core::io::write_obj(&path, &tvf_core::generate::icosphere(2)).unwrap();
    let mesh = path.display().to_string();
    let folder = dir.path().join("ops").display().to_string();
    let written = tvf(&[
        "operators",
        &mesh,
        "--discretization",
        "dec-barycentric",
        "--format",
        "mtx",
        "-o",
        &folder,
        "-q",
    ]);
    assert_success(&written);
    let m1 = std::path::Path::new(&folder).join("M1.mtx");
    let text = std::fs::read_to_string(&m1).unwrap();
    let mut size_seen = false;
    let inverted: Vec<String> = text
        .lines()
        .map(|line| {
            if line.starts_with('%') || !size_seen {
                size_seen |= !line.starts_with('%');
                return line.to_string();
            }
            let w: Vec<&str> = line.split_whitespace().collect();
            let value: f64 = w[2].parse().unwrap();
            format!("{} {} {:e}", w[0], w[1], 1.0 / value)
        })
        .collect();
    std::fs::write(&m1, inverted.join("\n") + "\n").unwrap();
    let output = tvf(&["check", &mesh, "--complex", &folder, "--json", "-q"]);
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("consistency:energy_of_linear:checked mesh"),
        "{stderr}"
    );
    let report: Value = serde_json::from_slice(&output.stdout).unwrap();
    let checks = report["checks"].as_array().unwrap();
    let structural_failures: Vec<&Value> = checks
        .iter()
        .filter(|c| c["status"] == "failed")
        .filter(|c| !c["name"].as_str().unwrap().starts_with("consistency:"))
        .collect();
    assert!(structural_failures.is_empty(), "{structural_failures:?}");
    let order = checks
        .iter()
        .find(|c| c["name"] == "convergence:sphere:integrable")
        .unwrap();
    assert_eq!(order["status"], "not applicable");
    assert!(order["detail"].as_str().unwrap().contains("one mesh"));
}

/// A passing property run ends its progress with `N of N meshes passed` (a failing one with
/// `K meshes passed, mesh K+1 of N failed`: `PropertyRunReport::cases_summary`).
#[test]
fn a_passing_run_counts_its_meshes() {
    let dir = tempfile::tempdir().unwrap();
    let counterexample = dir.path().join("ce.obj");
    let output = tvf(&[
        "check",
        "--discretization",
        "conforming-barycentric",
        "--cases",
        "2",
        "--no-accuracy",
        "-o",
        counterexample.to_str().unwrap(),
    ]);
    assert_success(&output);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("2 of 2 meshes passed"), "{stderr}");
}
