//! Meshes with boundary through the commands: a generated pair of pants (three boundary loops)
//! with both boundary conditions, for the default finite-element entry and (Delaunay-flipped) for
//! DEC; a generated plate with five loops and unreferenced vertices; and the raw `bunny.obj` of
//! `../shared/meshes` (five loops, unreferenced vertices) where it exists (under `CI=true` it
//! must), every command on it sharing one basis file.

use crate::common::{run_quiet, stdout_json, tvf, write_field};
use serde_json::Value;
use std::path::Path;
use tvf_conformance::corpus::delaunay_flips;
use tvf_core::generate::perforated_plate;
use tvf_core::io::{load_mesh, write_obj};
use tvf_core::TriangleMesh;
use tvf_test_support::shared_mesh;

/// Constraints at an interior vertex and an interior edge, or with `curl_on_faces` (DEC) face 7
/// (boundary nodes are fixed by one of the boundary conditions).
fn write_constraints(mesh: &TriangleMesh, path: &Path, curl_on_faces: bool) {
    let mut on_boundary = vec![false; mesh.vertex_count()];
    for e in mesh.boundary_edges() {
        for v in mesh.edges()[e] {
            on_boundary[v] = true;
        }
    }
    let vertex = (0..mesh.vertex_count()).find(|&v| !on_boundary[v]).unwrap();
    let edge = (0..mesh.edge_count())
        .find(|&e| !mesh.edges()[e].iter().any(|&v| on_boundary[v]))
        .unwrap();
    let curl_node = if curl_on_faces {
        r#""face": 7"#.to_string()
    } else {
        format!(r#""edge": {edge}"#)
    };
    let constraints = format!(
        r#"{{"constraints": [
        {{"id": "v", "kind": "vector", "face": 3, "value": [1.0, 0.5, 0.0]}},
        {{"id": "s", "kind": "divergence", "vertex": {vertex}, "value": 2.0}},
        {{"id": "c", "kind": "curl", {curl_node}, "value": -1.0}}
    ]}}"#
    );
    std::fs::write(path, constraints).unwrap();
}

/// How [`every_command`] runs the commands that take a basis without needing its file.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Size {
    /// A generated mesh of a few hundred faces: `spline` and `design --reduced` compute their
    /// `k` eigenfields themselves, and the quick demo runs.
    Small,
    /// A real scan of tens of thousands of faces: `spline` and `design --reduced` read the file
    /// `basis` wrote (one computed basis for every command), and the demo, which computes a
    /// basis of its own and draws every figure, is left to a small mesh of the same kind.
    Large,
}

/// basis, coefficients, decompose, filter, spline, design (reduced and full), render, analyze,
/// compress, decompress, rate-distortion, export and (on a [`Size::Small`] mesh) the quick demo
/// on `mesh` (the file `name` in `dir`) with catalog entry `discretization` and boundary
/// condition `boundary`; `k` eigenfields.
fn every_command(
    dir: &Path,
    name: &str,
    (discretization, boundary): (&str, &str),
    k: &str,
    harmonic: usize,
    size: Size,
) {
    let b = ["--boundary", boundary, "--discretization", discretization];
    let boundary = format!("{discretization}-{boundary}");
    let boundary = boundary.as_str();
    let basis_file = format!("{boundary}.tvfb");
    let basis = stdout_json(&run_quiet(
        dir,
        &[
            &["basis", name, "-k", k, "-o", &basis_file, "--json"][..],
            &b,
        ]
        .concat(),
    ));
    let expected_id = format!("{discretization}+{}", b[1]);
    assert_eq!(basis["discretization"], expected_id.as_str());
    assert_eq!(basis["harmonic"], harmonic);
    // The basis file brings its boundary condition back without the flag.
    let coefficients = stdout_json(&run_quiet(
        dir,
        &[
            "coefficients",
            name,
            "field.txt",
            "--basis",
            &basis_file,
            "--json",
        ],
    ));
    assert_eq!(coefficients["discretization"], expected_id.as_str());
    let decompose = stdout_json(&run_quiet(
        dir,
        &[
            &[
                "decompose",
                name,
                "field.txt",
                "-o",
                &format!("parts-{boundary}"),
                "--json",
            ][..],
            &b,
        ]
        .concat(),
    ));
    assert_eq!(
        decompose["discretization"],
        expected_id.as_str(),
        "{decompose}"
    );
    assert!(dir.join(format!("parts-{boundary}/harmonic.npy")).is_file());
    run_quiet(
        dir,
        &[
            "filter",
            name,
            "field.txt",
            "--basis",
            &basis_file,
            "-o",
            "smooth.npy",
        ],
    );
    // The reduced solves' basis: computed by each command, or the file of `basis` (which
    // brings its entry and boundary condition).
    let computed = [&["-k", k][..], &b].concat();
    let basis_args = match size {
        Size::Small => computed,
        Size::Large => vec!["--basis", basis_file.as_str()],
    };
    let spline = stdout_json(&run_quiet(
        dir,
        &[
            &[
                "spline",
                name,
                "--constraints",
                "c.json",
                "-o",
                "spline.npy",
                "--json",
            ][..],
            &basis_args,
        ]
        .concat(),
    ));
    assert_eq!(spline["discretization"], expected_id.as_str());
    run_quiet(
        dir,
        &[
            &[
                "design",
                name,
                "--constraints",
                "c.json",
                "--reduced",
                "-o",
                "r.npy",
            ][..],
            &basis_args,
        ]
        .concat(),
    );
    run_quiet(
        dir,
        &[
            &[
                "design",
                name,
                "--constraints",
                "c.json",
                "--full",
                "-o",
                "f.npy",
            ][..],
            &b,
        ]
        .concat(),
    );
    run_quiet(
        dir,
        &[
            &[
                "render",
                name,
                "spline.npy",
                "-o",
                "spline.png",
                "--size",
                "120x90",
            ][..],
            &b,
        ]
        .concat(),
    );
    // Analysis, compression and export with the basis file's boundary condition.
    let analysis = format!("analysis-{boundary}");
    run_quiet(
        dir,
        &[
            "analyze",
            name,
            "field.txt",
            "--basis",
            &basis_file,
            "-o",
            &analysis,
        ],
    );
    assert!(dir.join(&analysis).is_dir());
    let compressed = format!("f-{boundary}.tvfc");
    run_quiet(
        dir,
        &[
            "compress",
            name,
            "field.txt",
            "--basis",
            &basis_file,
            "--pairs",
            "5",
            "-o",
            &compressed,
        ],
    );
    run_quiet(
        dir,
        &[
            "decompress",
            name,
            &compressed,
            "--basis",
            &basis_file,
            "-o",
            "back.npy",
        ],
    );
    assert!(dir.join("back.npy").is_file());
    let curves = format!("rd-{boundary}");
    run_quiet(
        dir,
        &[
            "rate-distortion",
            name,
            "field.txt",
            "--basis",
            &basis_file,
            "--pairs",
            "3,5",
            "-o",
            &curves,
        ],
    );
    assert!(dir.join(&curves).is_dir());
    run_quiet(
        dir,
        &[
            &[
                "export",
                name,
                "spline.npy",
                "--format",
                "vtk",
                "-o",
                "spline.vtk",
            ][..],
            &b,
        ]
        .concat(),
    );
    assert!(dir.join("spline.vtk").is_file());
    if size == Size::Large {
        return;
    }
    // The demo's tour on the open mesh.
    let demo = format!("demo-{boundary}");
    run_quiet(
        dir,
        &[&["demo", "--quick", "--mesh", name, "-o", &demo][..], &b].concat(),
    );
    assert!(dir.join(&demo).join("index.html").is_file());
    assert!(dir.join(&demo).join("harmonic.png").is_file());
}

#[test]
fn a_pair_of_pants_runs_through_every_command_with_both_boundary_conditions() {
    let temp = tempfile::tempdir().unwrap();
    let dir = temp.path();
    let mesh = perforated_plate(2, 8);
    write_obj(dir.join("pants.obj"), &mesh).unwrap();
    write_field(&mesh, &dir.join("field.txt"));
    write_constraints(&mesh, &dir.join("c.json"), false);
    let info = stdout_json(&run_quiet(dir, &["info", "pants.obj", "--json"]));
    assert_eq!(info["boundary_loops"], 3);
    assert_eq!(info["harmonic_dimension"]["tangential"], 2);
    assert_eq!(info["harmonic_dimension"]["normal"], 2);
    for boundary in ["tangential", "normal"] {
        every_command(
            dir,
            "pants.obj",
            ("conforming-barycentric", boundary),
            "30",
            2,
            Size::Small,
        );
    }
    // A divergence on a boundary vertex cannot be prescribed where potentials are fixed.
    let boundary_vertex = mesh.edges()[mesh.boundary_edges()[0]][0];
    std::fs::write(
        dir.join("bad.json"),
        format!(
            r#"{{"constraints": [{{"id": "s", "kind": "divergence", "vertex": {boundary_vertex}, "value": 1.0}}]}}"#
        ),
    )
    .unwrap();
    let output = tvf()
        .current_dir(dir)
        .args(["design", "pants.obj", "--constraints", "bad.json", "--full"])
        .args(["-o", "bad.npy", "--boundary", "normal", "--quiet"])
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("lies on the boundary"), "{stderr}");
}

#[test]
fn dec_runs_through_every_command_on_a_delaunay_pair_of_pants_with_both_boundary_conditions() {
    let temp = tempfile::tempdir().unwrap();
    let dir = temp.path();
    let mesh = delaunay_flips(&perforated_plate(2, 8));
    write_obj(dir.join("pants.obj"), &mesh).unwrap();
    write_field(&mesh, &dir.join("field.txt"));
    write_constraints(&mesh, &dir.join("c.json"), true);
    for boundary in ["tangential", "normal"] {
        every_command(
            dir,
            "pants.obj",
            ("dec-circumcentric", boundary),
            "30",
            2,
            Size::Small,
        );
    }
    // The exported matrices say which nodes relative forms fix: boundary vertices and edges.
    run_quiet(
        dir,
        &[
            "operators",
            "pants.obj",
            "--discretization",
            "dec-circumcentric",
            "--boundary",
            "normal",
            "-o",
            "ops",
        ],
    );
    let info: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("ops/info.json")).unwrap()).unwrap();
    let boundary_edges = mesh.boundary_edges().len();
    let fixed = |space: &str| info["fixed_nodes"][space].as_array().unwrap().len();
    assert_eq!(fixed("fields"), boundary_edges, "{info}");
    // On a boundary loop there are as many vertices as edges.
    assert_eq!(fixed("potentials"), boundary_edges, "{info}");
    assert_eq!(fixed("co_potentials"), 0, "{info}");
    // Relative forms (normal) fix the 0-forms at boundary vertices: a divergence there is refused.
    let boundary_vertex = mesh.edges()[mesh.boundary_edges()[0]][0];
    std::fs::write(
        dir.join("bad.json"),
        format!(
            r#"{{"constraints": [{{"id": "s", "kind": "divergence", "vertex": {boundary_vertex}, "value": 1.0}}]}}"#
        ),
    )
    .unwrap();
    let output = tvf()
        .current_dir(dir)
        .args(["design", "pants.obj", "--constraints", "bad.json", "--full"])
        .args(["-o", "bad.npy", "--boundary", "normal", "--quiet"])
        .args(["--discretization", "dec-circumcentric"])
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("lies on the boundary"), "{stderr}");
}

/// The raw `bunny.obj` (69,451 faces, five boundary loops, 1,113 unreferenced vertices) through
/// every command that reads or writes a field on it, the reduced solves on the one basis file
/// `basis` writes; the demo runs on [`bunny_like_plate`].
#[test]
fn the_raw_bunny_runs_through_every_command() {
    let Some(path) = shared_mesh("bunny.obj") else {
        return;
    };
    let temp = tempfile::tempdir().unwrap();
    let dir = temp.path();
    std::fs::copy(&path, dir.join("bunny.obj")).unwrap();
    let mesh = load_mesh(&path).unwrap().mesh.into_triangles().unwrap();
    write_field(&mesh, &dir.join("field.txt"));
    write_constraints(&mesh, &dir.join("c.json"), false);
    let info = stdout_json(&run_quiet(dir, &["info", "bunny.obj", "--json"]));
    assert_eq!(info["boundary_loops"], 5);
    assert_eq!(info["harmonic_dimension"]["tangential"], 4);
    every_command(
        dir,
        "bunny.obj",
        ("conforming-barycentric", "tangential"),
        "20",
        4,
        Size::Large,
    );
}

/// Writes a flat plate with four holes (five boundary loops, as the raw bunny has) to `path` as
/// OBJ with an unreferenced vertex before every seventh vertex (scattered through the file, as
/// in a raw scan, so that reading drops them and renumbers the rest); returns how many.
fn bunny_like_plate(path: &Path) -> usize {
    let mesh = perforated_plate(4, 8);
    let mut text = String::new();
    let mut file_vertex = Vec::with_capacity(mesh.vertex_count());
    let mut written = 0;
    let mut unreferenced = 0;
    for (v, p) in mesh.positions().iter().enumerate() {
        if v % 7 == 0 {
            text += &format!("v {} {} 1\n", p[0] + 0.1, p[1] - 0.1);
            written += 1;
            unreferenced += 1;
        }
        text += &format!("v {} {} {}\n", p[0], p[1], p[2]);
        written += 1;
        file_vertex.push(written);
    }
    for f in mesh.faces() {
        let [a, b, c] = f.map(|v| file_vertex[v]);
        text += &format!("f {a} {b} {c}\n");
    }
    std::fs::write(path, text).unwrap();
    unreferenced
}

/// What the raw bunny runs, and the demo, on [`bunny_like_plate`]: each command computes its
/// own basis.
#[test]
fn a_plate_with_the_raw_bunnys_loops_and_unreferenced_vertices_runs_through_every_command() {
    let temp = tempfile::tempdir().unwrap();
    let dir = temp.path();
    let unreferenced = bunny_like_plate(&dir.join("plate.obj"));
    let mesh = load_mesh(dir.join("plate.obj"))
        .unwrap()
        .mesh
        .into_triangles()
        .unwrap();
    write_field(&mesh, &dir.join("field.txt"));
    write_constraints(&mesh, &dir.join("c.json"), false);
    let info = stdout_json(&run_quiet(dir, &["info", "plate.obj", "--json"]));
    assert_eq!(info["unreferenced_vertices"], unreferenced, "{info}");
    assert_eq!(info["boundary_loops"], 5);
    assert_eq!(info["harmonic_dimension"]["tangential"], 4);
    every_command(
        dir,
        "plate.obj",
        ("conforming-barycentric", "tangential"),
        "20",
        4,
        Size::Small,
    );
}

#[test]
fn the_catalog_listing_names_both_boundary_conditions_and_what_they_fix() {
    let temp = tempfile::tempdir().unwrap();
    let listing = stdout_json(&run_quiet(temp.path(), &["discretizations", "--json"]));
    let entries = listing["discretizations"].as_array().unwrap();
    assert_eq!(entries.len(), tvf_discretizations::builtin_catalog().len());
    for entry in entries {
        assert_eq!(
            entry["boundary_conditions"],
            serde_json::json!(["tangential", "normal"]),
            "{entry}"
        );
        let id = entry["id"].as_str().unwrap();
        let normal = entry["boundary_meanings"]["normal"].as_str().unwrap();
        let expected = if id.starts_with("dec-") || id == "whitney-galerkin" || id == "polygon-dec"
        {
            "relative forms"
        } else if id.starts_with("conforming-") {
            "P1 potentials zero"
        } else {
            "Crouzeix–Raviart potentials zero"
        };
        assert!(normal.contains(expected), "{id}: {normal}");
    }
    let text = String::from_utf8(run_quiet(temp.path(), &["discretizations"]).stdout).unwrap();
    let dec = text
        .lines()
        .find(|l| l.starts_with("dec-circumcentric"))
        .unwrap();
    assert!(dec.contains("normal (relative forms"), "{dec}");
}
