//! `--intrinsic-delaunay[=flip|refine]`: DEC on meshes that are not Delaunay, through every
//! subcommand that builds a complex, with field files of one vector per input face; `tvf info`
//! counting the non-Delaunay edges and the DEC refusal suggesting the flag; ids, basis files and
//! complex folders carrying the modifier.

use crate::common::{run_quiet, stdout_json, tvf, write_field_and_constraints};
use serde_json::Value;
use std::path::Path;
use tvf_core::generate::{jitter, torus};
use tvf_core::io::write_obj;
use tvf_core::TriangleMesh;

/// A torus of genus 1 whose quad cells, cut by diagonals and jittered, make many edges
/// non-Delaunay (`cot α + cot β < 0`) and none cocircular.
fn jittered_torus() -> TriangleMesh {
    jitter(&torus(1.0, 0.4, 18, 9).unwrap(), 0.3, 11).unwrap()
}

/// The number of rows of a `.npy` array of shape `(rows, 3)`.
fn npy_rows(path: &Path) -> usize {
    let bytes = std::fs::read(path).unwrap();
    let header = String::from_utf8_lossy(&bytes[..bytes.len().min(200)]).to_string();
    let shape = header.split("'shape': (").nth(1).unwrap();
    shape.split(',').next().unwrap().trim().parse().unwrap()
}

#[test]
fn info_counts_the_edges_dec_refuses_and_dec_suggests_the_flag() {
    let temp = tempfile::tempdir().unwrap();
    let dir = temp.path();
    write_obj(dir.join("torus.obj"), &jittered_torus()).unwrap();
    let info = stdout_json(&run_quiet(dir, &["info", "torus.obj", "--json"]));
    let count = info["non_delaunay_edges"].as_u64().unwrap();
    assert!(count > 0, "{info}");
    let text = run_quiet(dir, &["info", "torus.obj"]);
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains(&format!("delaunay       no: {count} edges"))
            && text.contains("--intrinsic-delaunay"),
        "{text}"
    );
    let refused = tvf()
        .current_dir(dir)
        .args([
            "spectrum",
            "torus.obj",
            "-k",
            "4",
            "--discretization",
            "dec-circumcentric",
        ])
        .output()
        .unwrap();
    assert!(!refused.status.success());
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains(&format!("{count} edges")) && stderr.contains("--intrinsic-delaunay"),
        "{stderr}"
    );
    // With the flag, info builds the intrinsic triangulation: it flips, and after refinement
    // no edge is left that DEC refuses.
    for (mode, inserted) in [("flip", false), ("refine", true)] {
        let flag = format!("--intrinsic-delaunay={mode}");
        let info = stdout_json(&run_quiet(dir, &["info", "torus.obj", "--json", &flag]));
        let summary = &info["intrinsic_delaunay"];
        assert_eq!(summary["mode"], mode);
        assert!(summary["flips"].as_u64().unwrap() > 0, "{summary}");
        assert!(summary["cells"].as_u64().unwrap() >= info["faces"].as_u64().unwrap());
        if inserted {
            assert_eq!(summary["not_positive_edges"], 0, "{summary}");
        }
    }
    // A Delaunay mesh says so.
    write_obj(dir.join("sphere.obj"), &tvf_core::generate::icosphere(2)).unwrap();
    let info = stdout_json(&run_quiet(dir, &["info", "sphere.obj", "--json"]));
    assert_eq!(info["non_delaunay_edges"], 0);
}

#[test]
fn dec_with_the_flag_runs_through_every_command_on_a_non_delaunay_torus() {
    let temp = tempfile::tempdir().unwrap();
    let dir = temp.path();
    let mesh = jittered_torus();
    write_obj(dir.join("torus.obj"), &mesh).unwrap();
    write_field_and_constraints(&mesh, dir);
    let dec = [
        "--discretization",
        "dec-circumcentric",
        "--intrinsic-delaunay",
    ];
    let with =
        |args: &[&str]| -> Vec<String> { args.iter().chain(&dec).map(|s| s.to_string()).collect() };
    let go = |args: &[&str]| {
        let args = with(args);
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        run_quiet(dir, &refs)
    };

    // Genus 1: two harmonic fields, then positive eigenvalues.
    let spectrum = stdout_json(&go(&["spectrum", "torus.obj", "-k", "8", "--json"]));
    assert_eq!(
        spectrum["discretization"],
        "dec-circumcentric+intrinsic-delaunay"
    );
    let labels: Vec<&str> = spectrum["labels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap())
        .collect();
    assert_eq!(
        labels.iter().filter(|&&l| l == "harmonic").count(),
        2,
        "{spectrum}"
    );
    let values: Vec<f64> = spectrum["eigenvalues"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(values[2] > 1e-3, "{values:?}");

    go(&["basis", "torus.obj", "-k", "30", "-o", "b.tvfb"]);
    // The basis of the intrinsic complex is never taken for one of the input's.
    let other = tvf()
        .current_dir(dir)
        .args([
            "coefficients",
            "torus.obj",
            "field.txt",
            "--basis",
            "b.tvfb",
            "--discretization",
            "dec-circumcentric",
            "--json",
        ])
        .output()
        .unwrap();
    assert!(!other.status.success());
    let stderr = String::from_utf8_lossy(&other.stderr);
    assert!(
        stderr.contains("dec-circumcentric+intrinsic-delaunay"),
        "{stderr}"
    );
    let coefficients = stdout_json(&run_quiet(
        dir,
        &[
            "coefficients",
            "torus.obj",
            "field.txt",
            "--basis",
            "b.tvfb",
            "--json",
        ],
    ));
    assert_eq!(
        coefficients["discretization"],
        "dec-circumcentric+intrinsic-delaunay"
    );

    go(&["decompose", "torus.obj", "field.txt", "-o", "parts"]);
    assert_eq!(
        npy_rows(&dir.join("parts/integrable.npy")),
        mesh.face_count()
    );
    go(&[
        "filter",
        "torus.obj",
        "field.txt",
        "-k",
        "30",
        "-o",
        "smooth.npy",
    ]);
    assert_eq!(npy_rows(&dir.join("smooth.npy")), mesh.face_count());
    go(&[
        "analyze",
        "torus.obj",
        "field.txt",
        "-k",
        "30",
        "-o",
        "analysis",
    ]);
    go(&[
        "compress",
        "torus.obj",
        "field.txt",
        "--pairs",
        "10",
        "-o",
        "f.tvfc",
    ]);
    go(&["decompress", "torus.obj", "f.tvfc", "-o", "back.npy"]);
    assert_eq!(npy_rows(&dir.join("back.npy")), mesh.face_count());
    go(&[
        "rate-distortion",
        "torus.obj",
        "field.txt",
        "--pairs",
        "5,10",
        "-o",
        "rd",
    ]);
    let spline = stdout_json(&go(&[
        "spline",
        "torus.obj",
        "--constraints",
        "c.json",
        "-k",
        "40",
        "-o",
        "spline.npy",
        "--json",
    ]));
    assert_eq!(
        spline["discretization"],
        "dec-circumcentric+intrinsic-delaunay"
    );
    assert_eq!(npy_rows(&dir.join("spline.npy")), mesh.face_count());
    go(&[
        "design",
        "torus.obj",
        "--constraints",
        "c.json",
        "--reduced",
        "-k",
        "40",
        "-o",
        "reduced.npy",
    ]);
    go(&[
        "design",
        "torus.obj",
        "--constraints",
        "c.json",
        "--full",
        "-o",
        "full.npy",
    ]);
    go(&[
        "render",
        "torus.obj",
        "spline.npy",
        "--color",
        "curl",
        "-o",
        "spline.png",
        "--size",
        "160x120",
    ]);
    go(&[
        "export",
        "torus.obj",
        "spline.npy",
        "--format",
        "vtk",
        "-o",
        "spline.vtk",
    ]);
    go(&["operators", "torus.obj", "-o", "matrices"]);
    let info: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("matrices/info.json")).unwrap())
            .unwrap();
    assert_eq!(
        info["discretization"],
        "dec-circumcentric+intrinsic-delaunay"
    );
    go(&["demo", "--quick", "--mesh", "torus.obj", "-o", "demo"]);
    for file in [
        "analysis",
        "rd",
        "reduced.npy",
        "full.npy",
        "spline.png",
        "spline.vtk",
        "matrices/d0.mtx",
        "demo/index.html",
    ] {
        assert!(dir.join(file).exists(), "{file} was not written");
    }
}

#[test]
fn refinement_runs_dec_on_an_open_mesh_with_both_boundary_conditions() {
    let temp = tempfile::tempdir().unwrap();
    let dir = temp.path();
    // A jittered, squashed hemisphere: boundary edges opposite obtuse angles, which flips never
    // cure.
    let mesh = jitter(&tvf_core::generate::hemisphere(4), 0.3, 5).unwrap();
    let positions = mesh
        .positions()
        .iter()
        .map(|p| [p[0], p[1], 0.3 * p[2]])
        .collect();
    let mesh = TriangleMesh::new(positions, mesh.faces().to_vec()).unwrap();
    write_obj(dir.join("cap.obj"), &mesh).unwrap();
    for boundary in ["tangential", "normal"] {
        let spectrum = stdout_json(&run_quiet(
            dir,
            &[
                "spectrum",
                "cap.obj",
                "-k",
                "6",
                "--json",
                "--discretization",
                "dec-barycentric",
                "--intrinsic-delaunay=refine",
                "--boundary",
                boundary,
            ],
        ));
        assert_eq!(
            spectrum["discretization"],
            format!("dec-barycentric+intrinsic-delaunay-refine+{boundary}")
        );
        // A disk: 2g + b − 1 = 0 harmonic fields.
        let labels = spectrum["labels"].as_array().unwrap();
        assert!(labels.iter().all(|l| l != "harmonic"), "{spectrum}");
    }
}
