//! `tvf compare`: discretizations side by side. Entries compared with themselves (a catalog
//! entry and its own matrices as a folder) agree exactly; two discretizations of the sphere
//! agree on the eigenvalues to their discretization error and share their eigenspaces when K
//! ends at a gap of the spectrum; too few or repeated entries are refused.

use crate::common::{assert_success, tvf};

fn compare_json(dir: &std::path::Path, extra: &[&str]) -> serde_json::Value {
    let output = tvf()
        .current_dir(dir)
        .args(["compare", "--example", "icosphere", "--json", "--quiet"])
        .args(extra)
        .output()
        .unwrap();
    assert_success(&output);
    serde_json::from_slice(&output.stdout).unwrap()
}

fn values(value: &serde_json::Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn an_entry_agrees_with_its_own_matrices_and_two_entries_share_the_spheres_eigenspaces() {
    let dir = tempfile::tempdir().unwrap();
    let output = tvf()
        .current_dir(dir.path())
        .args(["operators", "--example", "icosphere", "--quiet"])
        .args(["--discretization", "dec-circumcentric", "-o", "dec"])
        .output()
        .unwrap();
    assert_success(&output);
    // The lowest 16 fields of the sphere: the eigenspaces l = 1 (6 fields) and l = 2 (10).
    let report = compare_json(
        dir.path(),
        &[
            "-k",
            "16",
            "--discretization",
            "conforming-barycentric",
            "--discretization",
            "dec-circumcentric",
            "--complex",
            "dec",
        ],
    );
    let entries = report["entries"].as_array().unwrap();
    assert_eq!(entries.len(), 3);
    assert_eq!(entries[0]["time_ratio_to_first"], 1.0);
    let comparisons = report["comparisons"].as_array().unwrap();
    assert_eq!(comparisons.len(), 2);
    let dec = &comparisons[0];
    assert_eq!(dec["second"], "dec-circumcentric");
    let differences = values(&dec["eigenvalue_differences"]);
    assert_eq!(differences.len(), 16);
    let worst = differences.iter().fold(0.0f64, |m, &x| m.max(x));
    assert!(worst > 0.0 && worst < 0.02, "{differences:?}");
    for key in ["first_in_second", "second_in_first"] {
        let shares = values(&dec[key]);
        assert!(
            shares.iter().all(|&x| x > 0.97 && x < 1.0 + 1e-9),
            "{key}: {shares:?}"
        );
    }
    // The folder holds dec-circumcentric's own matrices: compared with conforming-barycentric
    // it gives what dec-circumcentric gives.
    let folder = &comparisons[1];
    assert_eq!(folder["second"], "dec");
    for key in [
        "eigenvalue_differences",
        "first_in_second",
        "second_in_first",
    ] {
        let (a, b) = (values(&dec[key]), values(&folder[key]));
        assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-9), "{key}");
    }
}

#[test]
fn fewer_than_two_or_repeated_entries_and_k_zero_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (args, expected) in [
        (
            vec!["-k", "8", "--discretization", "dec-circumcentric"],
            "at least two entries",
        ),
        (
            vec![
                "-k",
                "8",
                "--discretization",
                "whitney-galerkin",
                "--discretization",
                "whitney-galerkin",
            ],
            "given twice",
        ),
        (
            vec![
                "-k",
                "0",
                "--discretization",
                "whitney-galerkin",
                "--discretization",
                "polygon-dec",
            ],
            "-k 0",
        ),
    ] {
        let output = tvf()
            .current_dir(dir.path())
            .args(["compare", "--example", "icosphere", "--quiet"])
            .args(&args)
            .output()
            .unwrap();
        let message = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {message}");
        assert!(message.contains(expected), "{args:?}: {message}");
    }
}

/// `--corpus FOLDER`: every mesh × entry; the success rate of each entry with the reason of each
/// failure (a mesh that does not load, DEC refusing a mesh that is not Delaunay), and the
/// eigenvalues against the first entry where both succeeded. K = 6 ends at the sphere's first
/// gap (its l = 1 eigenspaces).
#[test]
fn a_corpus_gives_success_rates_and_failure_reasons() {
    let dir = tempfile::tempdir().unwrap();
    let corpus = dir.path().join("corpus");
    std::fs::create_dir(&corpus).unwrap();
    tvf_core::io::write_obj(
        corpus.join("a-sphere.obj"),
        &tvf_core::generate::icosphere(2),
    )
    .unwrap();
    // Rectangles split by a diagonal: cot α + cot β = 0, refused by DEC.
    let torus = tvf_core::generate::torus(1.0, 0.4, 8, 5).unwrap();
    tvf_core::io::write_obj(corpus.join("b-torus.obj"), &torus).unwrap();
    std::fs::write(corpus.join("c-broken.obj"), "v 0 0 0\nf 1 2 3\n").unwrap();
    std::fs::write(corpus.join("notes.txt"), "not a mesh").unwrap();
    let output = tvf()
        .args(["compare", "--corpus"])
        .arg(&corpus)
        .args([
            "-k",
            "6",
            "--discretization",
            "conforming-barycentric",
            "--discretization",
            "dec-circumcentric",
            "--threads",
            "2",
            "--json",
            "--quiet",
        ])
        .output()
        .unwrap();
    assert_success(&output);
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(report["reference"], "conforming-barycentric");
    let entries = report["entries"].as_array().unwrap();
    assert_eq!(
        entries[0]["meshes"], 3,
        "three mesh files, the text file left out"
    );
    assert_eq!(entries[0]["succeeded"], 2);
    assert_eq!(entries[1]["succeeded"], 1);
    let failures = entries[1]["failures"].as_array().unwrap();
    let reasons: Vec<String> = failures
        .iter()
        .map(|f| format!("{} {}", f[0].as_str().unwrap(), f[1].as_str().unwrap()))
        .collect();
    assert!(
        reasons
            .iter()
            .any(|r| r.contains("b-torus.obj") && r.contains("Delaunay")),
        "{reasons:?}"
    );
    assert!(
        reasons
            .iter()
            .any(|r| r.contains("c-broken.obj") && r.contains("cannot load")),
        "{reasons:?}"
    );
    let difference = entries[1]["median_relative_difference"].as_f64().unwrap();
    assert!(difference > 0.0 && difference < 0.05, "{difference}");
    let text = tvf()
        .args(["compare", "--corpus"])
        .arg(&corpus)
        .args([
            "-k",
            "6",
            "--discretization",
            "conforming-barycentric",
            "--discretization",
            "dec-circumcentric",
            "--quiet",
        ])
        .output()
        .unwrap();
    assert_success(&text);
    let stdout = String::from_utf8_lossy(&text.stdout);
    assert!(
        stdout.contains("1/3") && stdout.contains("33.3%"),
        "{stdout}"
    );
}
