//! Quad and polygon meshes on the command line: `tvf triangulate` and `--triangulate` (polygons
//! split by their own corners, for the triangle entries), the clear error of a triangle entry
//! asked for on polygons, `info`'s face sizes, the complex folder of a polygon mesh read back,
//! and `render` drawing the polygons' edges.

use crate::common::{assert_success, tvf};
use std::path::Path;
use std::process::Output;

fn run(dir: &Path, args: &[&str]) -> Output {
    tvf()
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the tvf binary runs")
}

fn json(output: &Output) -> serde_json::Value {
    assert_success(output);
    serde_json::from_slice(&output.stdout).expect("JSON on stdout")
}

fn eigenvalues(value: &serde_json::Value) -> Vec<f64> {
    value["eigenvalues"]
        .as_array()
        .expect("eigenvalues")
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn triangulate_writes_the_same_vertices_with_two_triangles_per_quad() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let report = json(&run(
        d,
        &[
            "triangulate",
            "--example",
            "quad-torus",
            "-o",
            "t.obj",
            "--json",
        ],
    ));
    let quads = json(&run(d, &["info", "--example", "quad-torus", "--json"]));
    let triangles = json(&run(d, &["info", "t.obj", "--json"]));
    assert_eq!(report["polygons"], quads["faces"], "{report}");
    assert_eq!(
        triangles["faces"].as_u64().unwrap(),
        2 * quads["faces"].as_u64().unwrap()
    );
    assert_eq!(triangles["vertices"], quads["vertices"]);
    assert_eq!(triangles["genus"], quads["genus"]);
    assert_eq!(triangles["mesh_kind"], "triangles");
    assert_eq!(quads["mesh_kind"], "polygons");
    // The same split as --triangulate: the two load the same triangle mesh.
    let via_flag = json(&run(
        d,
        &["info", "--example", "quad-torus", "--triangulate", "--json"],
    ));
    for key in ["vertices", "edges", "faces", "total_area", "signed_volume"] {
        assert_eq!(via_flag[key], triangles[key], "{key}");
    }
    // An output format it cannot write is refused before anything is written.
    let output = run(
        d,
        &["triangulate", "--example", "quad-torus", "-o", "t.off"],
    );
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("t.off") && message.contains(".obj or .ply"),
        "{message}"
    );
    assert!(!d.join("t.off").exists());
}

#[test]
fn a_triangle_entry_on_quads_needs_triangulate_and_then_equals_it_on_the_triangulated_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let entry = ["--discretization", "conforming-barycentric"];
    let spectrum = |args: &[&str]| {
        let mut all = vec!["spectrum", "-k", "8", "--json"];
        all.extend_from_slice(args);
        all.extend_from_slice(&entry);
        run(d, &all)
    };
    let output = spectrum(&["--example", "quad-torus"]);
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("conforming-barycentric")
            && message.contains("--triangulate")
            && message.contains("tvf triangulate"),
        "{message}"
    );
    let flagged = eigenvalues(&json(&spectrum(&[
        "--example",
        "quad-torus",
        "--triangulate",
    ])));
    assert_success(&run(
        d,
        &["triangulate", "--example", "quad-torus", "-o", "t.ply"],
    ));
    let from_file = eigenvalues(&json(&spectrum(&["t.ply"])));
    assert_eq!(flagged.len(), 8);
    // The PLY stores doubles: the same mesh bit for bit, so the same eigenvalues.
    assert_eq!(flagged, from_file);
    // Without a flag a polygon mesh gets polygon-dec: the torus's two harmonic fields.
    let default = json(&run(
        d,
        &["spectrum", "--example", "quad-torus", "-k", "4", "--json"],
    ));
    assert_eq!(default["discretization"], "polygon-dec", "{default}");
    let values = eigenvalues(&default);
    assert!(
        values[0].abs() < 1e-8 && values[1].abs() < 1e-8,
        "{values:?}"
    );
    assert!(values[2] > 1e-3, "{values:?}");
}

#[test]
fn info_counts_faces_by_size() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A square pyramid with a pentagon cap... a house: a quad floor, four walls of which two are
    // pentagons (gable ends) and two quads (roof halves), closed.
    std::fs::write(
        d.join("house.obj"),
        "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nv 0 0 2\nv 2 0 2\nv 2 2 2\nv 0 2 2\nv 1 0 3\nv 1 2 3\n\
         f 1 4 3 2\nf 1 2 6 9 5\nf 3 4 8 10 7\nf 2 3 7 6\nf 4 1 5 8\nf 6 7 10 9\nf 5 9 10 8\n",
    )
    .unwrap();
    let report = json(&run(d, &["info", "house.obj", "--json"]));
    assert_eq!(report["faces"], 7, "{report}");
    assert_eq!(report["face_sizes"], serde_json::json!({"4": 5, "5": 2}));
    assert_eq!(report["genus"], 0);
    assert_eq!(report["closed"], true);
    let output = run(d, &["info", "house.obj"]);
    assert_success(&output);
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.lines()
            .any(|l| l == "faces          7 (quads 5, pentagons 2)"),
        "{text}"
    );
    let output = run(d, &["info", "--example", "cube-sphere"]);
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(text.contains("(quads "), "{text}");
}

#[test]
fn the_complex_folder_of_a_polygon_mesh_says_so_and_reads_back_with_the_same_spectrum() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A quad torus: V = F and E = 2F, so only info.json's node kinds tell the spaces apart.
    assert_success(&run(
        d,
        &["operators", "--example", "quad-torus", "-o", "ops"],
    ));
    let info_path = d.join("ops/info.json");
    let mut info: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&info_path).unwrap()).unwrap();
    assert_eq!(info["mesh_kind"], "polygons", "{info}");
    assert_eq!(info["face_sizes"], serde_json::json!({"4": 1536}));
    assert_eq!(info["vertices"], info["faces"]);
    assert_eq!(info["sampling"], "polygon-sharp");
    assert_eq!(info["discretization"], "polygon-dec");
    let spectrum = |extra: &[&str]| {
        let mut args = vec!["spectrum", "--example", "quad-torus", "-k", "8", "--json"];
        args.extend_from_slice(extra);
        run(d, &args)
    };
    let built = eigenvalues(&json(&spectrum(&[])));
    let read = eigenvalues(&json(&spectrum(&["--complex", "ops"])));
    for (a, b) in built.iter().zip(&read) {
        assert!(
            (a - b).abs() <= 1e-9 * (1.0 + a.abs()),
            "{built:?} vs {read:?}"
        );
    }
    let refusal = |info: &serde_json::Value| {
        std::fs::write(&info_path, serde_json::to_string_pretty(info).unwrap()).unwrap();
        let output = spectrum(&["--complex", "ops"]);
        assert!(!output.status.success());
        String::from_utf8_lossy(&output.stderr).into_owned()
    };
    // Without the node kinds, the sizes are ambiguous: refused naming info.json.
    let kinds = info["nodes"].take();
    let message = refusal(&info);
    assert!(
        message.contains(
            "info.json: inconsistent complex: the potential space (columns of d0) \
             has 1536 nodes, which is ambiguous: the mesh has 1536 vertices and 1536 faces"
        ),
        "{message}"
    );
    // A stated kind that does not fit the size is refused too.
    info["nodes"] = kinds;
    info["nodes"]["co_potentials"] = "edges".into();
    let message = refusal(&info);
    assert!(
        message.contains(
            "info.json: inconsistent complex: the co-potential space (rows of d1) \
             has 1536 nodes, but its nodes are stated to be edges: the mesh has 3072"
        ),
        "{message}"
    );
    info["nodes"]["co_potentials"] = "corners".into();
    let message = refusal(&info);
    assert!(
        message.contains("info.json: nodes/co_potentials is 'corners'"),
        "{message}"
    );
}

#[test]
fn render_draws_the_polygon_edges_unless_told_not_to_and_none_on_triangles() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let render = |out: &str, extra: &[&str]| {
        let mut args = vec![
            "render",
            "--example",
            "quad-torus",
            "-o",
            out,
            "--size",
            "320x240",
        ];
        args.extend_from_slice(extra);
        assert_success(&run(d, &args));
        image::open(d.join(out)).unwrap().to_rgba8()
    };
    let edged = render("edged.png", &[]);
    let plain = render("plain.png", &["--no-polygon-edges"]);
    // The edges darken a share of the surface's pixels, and only darken.
    let (mut darker, mut lighter) = (0usize, 0usize);
    for (a, b) in edged.pixels().zip(plain.pixels()) {
        let (sa, sb) = (
            a.0[..3].iter().map(|&x| x as u32).sum::<u32>(),
            b.0[..3].iter().map(|&x| x as u32).sum::<u32>(),
        );
        darker += usize::from(sa + 30 < sb);
        lighter += usize::from(sa > sb + 30);
    }
    let total = (edged.width() * edged.height()) as usize;
    assert!(darker > total / 50, "{darker} of {total} pixels darker");
    assert_eq!(lighter, 0);
    // A triangulated mesh has no polygon edges: the flag changes nothing.
    let a = render("t1.png", &["--triangulate"]);
    let b = render("t2.png", &["--triangulate", "--no-polygon-edges"]);
    assert!(a == b);
}
