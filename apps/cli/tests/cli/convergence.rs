//! `tvf convergence`: the table, the JSON of rows and orders, the plot, refused arguments, and
//! the quad surfaces.

use crate::common::{self, assert_success, tvf};

#[test]
fn json_has_rows_and_orders_and_the_plot_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("convergence.png");
    let output = tvf()
        .args([
            "convergence",
            "--discretization",
            "conforming-barycentric",
            "--discretization",
            "dec-circumcentric",
            "--min-level",
            "2",
            "--max-level",
            "4",
            "-n",
            "8",
            "--json",
            "-o",
        ])
        .arg(&png)
        .output()
        .unwrap();
    assert_success(&output);
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let rows = json["rows"].as_array().unwrap();
    // Two entries, three surfaces, three levels.
    assert_eq!(rows.len(), 2 * 3 * 3);
    assert_eq!(rows[0]["discretization"], "conforming-barycentric");
    assert_eq!(rows[0]["surface"], "sphere");
    assert!(rows[0]["boundary"].is_null());
    let orders = json["orders"].as_array().unwrap();
    assert_eq!(orders.len(), 2 * 3 * 2);
    for order in orders {
        let family = order["family"].as_str().unwrap();
        assert!(family == "integrable" || family == "cointegrable");
        let value = order["order"].as_f64().unwrap();
        assert!((value - 2.0).abs() <= 0.2, "{order}");
    }
    assert!(orders
        .iter()
        .any(|o| o["surface"] == "hemisphere" && o["boundary"] == "normal"));
    let image = image::open(&png).unwrap();
    // Three surfaces side by side.
    assert_eq!((image.width(), image.height()), (3 * 640, 480));
}

#[test]
fn the_table_names_every_level_and_the_orders() {
    let output = tvf()
        .args([
            "convergence",
            "--discretization",
            "nonconforming-voronoi",
            "--surface",
            "sphere",
            "--max-level",
            "2",
            "-n",
            "3",
        ])
        .output()
        .unwrap();
    assert_success(&output);
    let text = String::from_utf8(output.stdout).unwrap();
    assert_eq!(
        text.lines().filter(|l| l.contains("| sphere")).count(),
        2,
        "{text}"
    );
    assert!(
        text.contains("nonconforming-voronoi on the sphere, integrable: order"),
        "{text}"
    );
}

#[test]
fn bad_arguments_are_refused_with_a_reason() {
    for (args, expected) in [
        (
            vec!["--discretization", "nope"],
            "unknown discretization 'nope'",
        ),
        (
            vec!["--min-level", "3", "--max-level", "2"],
            "above --max-level",
        ),
        (vec!["-n", "0"], "at least one eigenvalue"),
        (vec!["--max-level", "9"], "at most 7"),
    ] {
        let output = tvf().arg("convergence").args(&args).output().unwrap();
        assert_eq!(output.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
}

#[test]
fn the_quad_surfaces_run_the_entries_that_accept_polygons_and_refuse_triangle_entries() {
    let output = tvf()
        .args([
            "convergence",
            "--surface",
            "quads",
            "--min-level",
            "1",
            "--max-level",
            "3",
            "-n",
            "4",
            "--json",
        ])
        .output()
        .unwrap();
    assert_success(&output);
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let rows = json["rows"].as_array().unwrap();
    // polygon-dec alone (the entries that accept polygons), three surfaces, three levels.
    assert_eq!(rows.len(), 3 * 3);
    assert!(rows.iter().all(|r| r["discretization"] == "polygon-dec"));
    assert_eq!(rows[0]["surface"], "quad-sphere");
    assert_eq!(rows[0]["faces"], 96);
    assert_eq!(rows[3]["surface"], "quad-hemisphere");
    assert_eq!(rows[3]["faces"], 48);
    for order in json["orders"].as_array().unwrap() {
        let order = order["order"].as_f64().unwrap();
        assert!(order > 1.5, "{order}");
    }
    let refused = tvf()
        .args([
            "convergence",
            "--surface",
            "quad-sphere",
            "--discretization",
            "dec-barycentric",
        ])
        .output()
        .unwrap();
    assert_eq!(refused.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains("quad-sphere") && stderr.contains("dec-barycentric"),
        "{stderr}"
    );
}

/// A discretization given twice (once: duplicate rows and NaN orders, exit 0) and a plot path
/// that is a folder (once refused only after computing) are refused before any basis; a single
/// level says that it fits no order instead of printing "order NaN".
#[test]
fn duplicates_folders_and_single_levels_are_handled_up_front() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().display().to_string();
    let id = "conforming-barycentric";
    for (args, expected) in [
        (
            vec!["--discretization", id, "--discretization", id],
            "given twice",
        ),
        (vec!["-o", &folder], "is a folder"),
    ] {
        let output = common::output_within(tvf().arg("convergence").args(&args), 30);
        assert_eq!(output.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
        assert!(
            !stderr.contains("bases"),
            "{args:?} computed first: {stderr}"
        );
    }
    let output = tvf()
        .args(["convergence", "--discretization", id])
        .args([
            "--surface",
            "sphere",
            "--min-level",
            "1",
            "--max-level",
            "1",
        ])
        .output()
        .unwrap();
    assert_success(&output);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(!stdout.contains("NaN"), "{stdout}");
    assert!(stdout.contains("no order (it needs two levels"), "{stdout}");
}

/// Irregular refinements: `--surface jittered` runs the jittered sphere and hemisphere (both
/// conditions), and a consistent entry still converges at second order there; the plot is
/// written.
#[test]
fn jittered_refinements_converge_for_a_consistent_entry() {
    let dir = tempfile::tempdir().unwrap();
    let plot = dir.path().join("jittered.png");
    let output = tvf()
        .args([
            "convergence",
            "--surface",
            "jittered",
            "--discretization",
            "conforming-barycentric",
            "--min-level",
            "1",
            "--max-level",
            "3",
            "-n",
            "6",
            "--json",
            "-o",
        ])
        .arg(&plot)
        .output()
        .unwrap();
    assert_success(&output);
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 3 * 3);
    assert_eq!(rows[0]["surface"], "jittered-sphere");
    assert_eq!(rows[3]["surface"], "jittered-hemisphere");
    for order in json["orders"].as_array().unwrap() {
        let value = order["order"].as_f64().unwrap();
        assert!(value > 1.5, "{order}");
    }
    assert!(image::open(&plot).is_ok());
}
