//! End-to-end: `tvf basis` writes a basis file that loads for its mesh and matches the library.

use crate::common::{assert_success, tvf};
use tvf_core::generate::genus_surface;
use tvf_core::io::{load_mesh, write_obj};
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};
use tvf_spectral::{
    compute_basis, load_basis, read_basis_header, BasisFileKey, BasisFileLayout, BasisRequest,
    FieldFamily,
};

#[test]
fn basis_file_matches_the_library_and_belongs_to_its_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let mesh_path = dir.path().join("genus1.obj");
    write_obj(&mesh_path, &genus_surface(1, 4)).unwrap();
    let out = dir.path().join("b.tvfb");
    let output = tvf()
        .arg("basis")
        .arg(&mesh_path)
        .args(["-k", "26", "--decomposition", "nonconforming", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert_success(&output);
    // Not a terminal: plain progress lines and a summary on stderr.
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("26 fields"), "{stderr}");
    let mesh = load_mesh(&mesh_path)
        .unwrap()
        .mesh
        .into_triangles()
        .unwrap();
    let complex = Nonconforming::new(&mesh, MassLumping::Barycentric).unwrap();
    // The file holds the eigenfunctions: E + V values per pair of fields, not 4F.
    let header = read_basis_header(&out).unwrap();
    assert_eq!(
        header.layout,
        BasisFileLayout::Eigenfunctions {
            potential_dimension: mesh.edge_count(),
            co_potential_dimension: mesh.vertex_count(),
        }
    );
    let basis = load_basis(&out, &BasisFileKey::new(&mesh, &complex), &complex).unwrap();
    assert_eq!(basis.len(), 26);
    assert_eq!(basis.count(FieldFamily::Harmonic), 2);
    let expected = compute_basis(&complex, &BasisRequest::fields(26)).unwrap();
    assert_eq!(expected.len(), 26);
    for (a, b) in basis.eigenvalues().iter().zip(expected.eigenvalues()) {
        assert!((a - b).abs() <= 1e-10 * b.max(1.0));
    }
    // The file is refused for the other decomposition.
    let conforming = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    assert!(load_basis(&out, &BasisFileKey::new(&mesh, &conforming), &conforming).is_err());
    // --quiet prints nothing.
    let quiet = tvf()
        .arg("basis")
        .arg(&mesh_path)
        .args(["-k", "3", "--quiet", "-o"])
        .arg(dir.path().join("q.tvfb"))
        .output()
        .unwrap();
    assert!(quiet.status.success());
    assert!(
        quiet.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&quiet.stderr)
    );
}

#[test]
fn bad_input_exits_with_code_1_and_a_clear_message() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.obj");
    let output = tvf()
        .arg("basis")
        .arg(&missing)
        .args(["-k", "3", "-o"])
        .arg(dir.path().join("x.tvfb"))
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("missing.obj"));
    let output = tvf()
        .args(["basis", "--example", "torus", "-k", "0", "-o"])
        .arg(dir.path().join("x.tvfb"))
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("-k 0"));
    let output = tvf()
        .args(["basis", "--example", "torus", "-k", "2", "-o"])
        .arg(dir.path().join("no/such/dir/x.tvfb"))
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("x.tvfb"));
}

/// The exact family split is reported: the eigenpairs computed per family cover the kept ones,
/// and every kept eigenvalue lies below the counted threshold.
#[test]
fn basis_reports_the_counted_family_split() {
    let dir = tempfile::tempdir().unwrap();
    let output = tvf()
        .args([
            "basis",
            "--example",
            "bumpy-torus",
            "-k",
            "120",
            "--json",
            "-o",
        ])
        .arg(dir.path().join("b.tvfb"))
        .output()
        .unwrap();
    assert_success(&output);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("eigenpairs computed:"), "{stderr}");
    let summary: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let count = |key: &str| summary[key].as_u64().unwrap();
    let computed = |key: &str| summary["computed"][key].as_u64().unwrap();
    assert_eq!(count("fields"), 120);
    assert!(computed("integrable") >= count("integrable"));
    assert!(computed("cointegrable") >= count("cointegrable"));
    assert!(
        computed("integrable") + computed("cointegrable")
            <= count("fields") - count("harmonic") + 3,
        "{summary}"
    );
    let threshold = summary["split_threshold"].as_f64().unwrap();
    let eigenvalues = summary["eigenvalues"].as_array().unwrap();
    assert!(eigenvalues.iter().all(|v| v.as_f64().unwrap() < threshold));
}
