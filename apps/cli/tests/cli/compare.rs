//! `tvf compare`: discretizations side by side. Entries compared with themselves (a catalog
//! entry and its own matrices as a folder) agree exactly; two discretizations of the sphere
//! agree on the eigenvalues to their discretization error and share their eigenspaces (small
//! principal angles of the degenerate clusters); `-o DIR` holds the tables and pictures; too
//! few or repeated entries, an unknown reference and a missing Python driver are refused.

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
    assert_eq!(report["reference"], "conforming-barycentric");
    assert_eq!(entries[0]["basis_ratio"], 1.0);
    assert_eq!(entries[0]["principal_angles"].as_array().unwrap().len(), 16);
    let dec = &entries[1];
    assert_eq!(dec["discretization"], "dec-circumcentric");
    let differences = values(&dec["relative_difference"]);
    assert_eq!(differences.len(), 16);
    let worst = differences.iter().fold(0.0f64, |m, &x| m.max(x));
    assert!(worst > 0.0 && worst < 0.02, "{differences:?}");
    for key in ["in_reference_span", "reference_in_span"] {
        let shares = values(&dec[key]);
        assert!(
            shares.iter().all(|&x| x > 0.97 && x < 1.0 + 1e-9),
            "{key}: {shares:?}"
        );
    }
    // The icosphere's l = 1 and l = 2 eigenspaces are exactly degenerate (3 and 5 fields per
    // family): four clusters, compared as subspaces, with small angles.
    let clusters = dec["clusters"].as_array().unwrap();
    let sizes: Vec<u64> = clusters
        .iter()
        .map(|c| c["size"].as_u64().unwrap())
        .collect();
    assert_eq!(sizes, [3, 5, 3, 5], "{clusters:?}");
    let angles = values(&dec["principal_angles"]);
    assert_eq!(angles.len(), 16);
    assert!(
        angles.iter().all(|&a| (0.0..0.1).contains(&a)),
        "{angles:?}"
    );
    // Sizes and masses: DEC has diagonal masses (one non-zero per node).
    assert_eq!(dec["n1"].as_u64(), dec["mass_nonzeros"][1].as_u64());
    assert!(dec["basis_seconds"].as_f64().unwrap() > 0.0);
    if cfg!(target_os = "linux") {
        assert!(dec["peak_bytes"].as_u64().is_some(), "{dec}");
    }
    // The folder holds dec-circumcentric's own matrices: compared with conforming-barycentric
    // it gives what dec-circumcentric gives.
    let folder = &entries[2];
    assert_eq!(folder["discretization"], "dec");
    for key in [
        "relative_difference",
        "principal_angles",
        "in_reference_span",
        "reference_in_span",
    ] {
        let (a, b) = (values(&dec[key]), values(&folder[key]));
        assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-9), "{key}");
    }
    // With the folder as the reference, dec-circumcentric agrees with it to round-off.
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
            "--reference",
            "dec",
        ],
    );
    assert_eq!(report["reference"], "dec");
    let dec = &report["entries"][1];
    assert!(values(&dec["relative_difference"])
        .iter()
        .all(|&x| x < 1e-9));
    assert!(values(&dec["principal_angles"]).iter().all(|&x| x < 1e-6));
}

/// `-o DIR`: the tables and the pictures, written whole into a new folder; the table's columns
/// as the docs name them; the Markdown printed is the file's.
#[test]
fn an_output_folder_holds_the_tables_and_side_by_side_pictures() {
    let dir = tempfile::tempdir().unwrap();
    let output = tvf()
        .current_dir(dir.path())
        .args([
            "compare",
            "--example",
            "torus",
            "-k",
            "12",
            "--quiet",
            "-o",
            "cmp",
        ])
        .args(["--discretization", "conforming-barycentric"])
        .args(["--discretization", "whitney-galerkin", "--size", "160x120"])
        .output()
        .unwrap();
    assert_success(&output);
    let folder = dir.path().join("cmp");
    let mut names: Vec<String> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "clusters.csv",
            "compare.csv",
            "compare.json",
            "compare.md",
            "eigenfield-cointegrable-0.png",
            "eigenfield-cointegrable-1.png",
            "eigenfield-harmonic-0.png",
            "eigenfield-harmonic-1.png",
            "eigenfield-integrable-0.png",
            "eigenfield-integrable-1.png",
            "eigenvalues.csv",
        ]
    );
    let markdown = std::fs::read_to_string(folder.join("compare.md")).unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.starts_with(&markdown), "{stdout}");
    assert!(markdown.contains("| whitney-galerkin |"), "{markdown}");
    let csv = std::fs::read_to_string(folder.join("compare.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 3);
    let columns = lines[0].split(',').count();
    assert!(
        lines.iter().all(|l| l.split(',').count() == columns),
        "{csv}"
    );
    assert!(lines[0].starts_with("entry,id,n0,n1,n2,nnz_m0,nnz_m1,nnz_m2,"));
    // Two panels side by side, 160 × 120 each.
    let picture = image::open(folder.join("eigenfield-integrable-0.png")).unwrap();
    assert_eq!((picture.width(), picture.height()), (320, 120));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(folder.join("compare.json")).unwrap()).unwrap();
    assert_eq!(
        json["entries"][1]["harmonic"], 2,
        "a torus has two harmonic fields"
    );
    // No temporary folder is left beside the output.
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(left.len(), 1);
}

#[test]
fn an_unknown_reference_or_an_unreachable_python_driver_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let output = tvf()
        .current_dir(dir.path())
        .args(["compare", "--example", "icosphere", "-k", "4", "--quiet"])
        .args(["--discretization", "conforming-barycentric"])
        .args(["--discretization", "whitney-galerkin", "--reference", "dec"])
        .output()
        .unwrap();
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("--reference dec: not one of the compared entries"),
        "{message}"
    );
    tvf_core::io::write_obj(dir.path().join("s.obj"), &tvf_core::generate::icosphere(1)).unwrap();
    let output = tvf()
        .current_dir(dir.path())
        .env("TVF_PYTHON", dir.path().join("no-python"))
        .args(["compare", "--corpus", ".", "-k", "4", "--quiet"])
        .args(["--discretization", "conforming-barycentric"])
        .args(["--discretization", "whitney-galerkin"])
        .args(["--scheduler", "tcp://127.0.0.1:1"])
        .output()
        .unwrap();
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("cannot start") && message.contains("tvf.corpus"),
        "{message}"
    );
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
    // Each cause is said once (a typed error that prints its source is not followed by it).
    for failure in failures {
        let reason = failure[1].as_str().unwrap();
        let chars: Vec<char> = reason.chars().collect();
        for start in 0..chars.len().saturating_sub(30) {
            let piece: String = chars[start..start + 30].iter().collect();
            assert_eq!(
                reason.matches(&piece).count(),
                1,
                "'{piece}' twice in {reason}"
            );
        }
    }
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

#[test]
fn the_intrinsic_flag_suffixes_every_catalog_id_without_one_and_the_reference() {
    let dir = tempfile::tempdir().unwrap();
    let report = compare_json(
        dir.path(),
        &[
            "-k",
            "6",
            "--discretization",
            "conforming-barycentric",
            "--discretization",
            "dec-circumcentric+intrinsic-delaunay-refine",
            "--intrinsic-delaunay",
            "--reference",
            "conforming-barycentric",
        ],
    );
    assert_eq!(
        report["reference"],
        "conforming-barycentric+intrinsic-delaunay"
    );
    let ids: Vec<&str> = report["entries"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["discretization"].as_str().unwrap())
        .collect();
    assert_eq!(
        ids,
        [
            "conforming-barycentric+intrinsic-delaunay",
            "dec-circumcentric+intrinsic-delaunay-refine"
        ]
    );
}
