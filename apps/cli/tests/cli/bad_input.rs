//! The bad-input paths named in issues 2–9, end to end: the real binary exits with code 1 and
//! its last stderr line is `error: …` naming the file and the problem. (Missing files, usage
//! errors and the basis cache are in `cli_conventions.rs`; damaged `.tvfc` files in
//! `filter_analyze_compress.rs`.)

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use tvf_core::generate::torus;
use tvf_core::io::write_obj;
use tvf_core::TriangleMesh;
use tvf_spectral::{write_face_vector_sequence, write_npy, NpyArray, NpyDtype};

fn tvf<S: AsRef<OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args(args)
        .output()
        .unwrap()
}

/// Exit code 1, nothing written to `stdout` after the error, and the last stderr line is an
/// error naming every one of `needles` (the file and the problem).
fn assert_refused(output: &Output, needles: &[&str], what: &str) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{what}: {stderr}");
    let last = stderr.lines().last().unwrap_or_default();
    assert!(last.starts_with("error: "), "{what}: {stderr}");
    for needle in needles {
        assert!(last.contains(needle), "{what}: no '{needle}' in: {last}");
    }
}

struct Fixture {
    dir: tempfile::TempDir,
    mesh: TriangleMesh,
    mesh_file: String,
    field: String,
}

impl Fixture {
    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn file(&self, name: &str, content: &str) -> String {
        let path = self.path(name);
        std::fs::write(&path, content).unwrap();
        path.to_str().unwrap().to_string()
    }

    fn out(&self, name: &str) -> String {
        self.path(name).to_str().unwrap().to_string()
    }
}

/// A 256-face torus as OBJ and a constant field file for it.
fn fixture() -> Fixture {
    let dir = tempfile::tempdir().unwrap();
    let mesh = torus(1.0, 0.4, 16, 8).unwrap();
    let mesh_file = dir.path().join("torus.obj");
    write_obj(&mesh_file, &mesh).unwrap();
    let field = dir.path().join("field.txt");
    std::fs::write(&field, "1 0.5 0\n".repeat(mesh.face_count())).unwrap();
    Fixture {
        mesh_file: mesh_file.to_str().unwrap().to_string(),
        field: field.to_str().unwrap().to_string(),
        mesh,
        dir,
    }
}

fn malformed(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../core/tests/data/malformed")
        .join(name)
}

/// Every malformed mesh file of the corpus, with the problem it must report (and the
/// line, where the file has one).
#[test]
fn every_malformed_mesh_file_is_refused_with_its_problem() {
    let cases = [
        (
            "bad_face_token.obj",
            ":4: parse error: malformed face corner",
        ),
        ("bad_number.obj", ":2: parse error: 'abc' is not a number"),
        ("binary_garbage.obj", "not a text file"),
        ("bowtie.obj", "vertex 0 is non-manifold"),
        ("comments_only.obj", "the file is empty"),
        ("empty.obj", "the file is empty"),
        ("face_too_small.obj", ":4: a face has 2 corners"),
        (
            "index_out_of_range.obj",
            ":4: vertex index 9 is out of range",
        ),
        ("mixed_orientation.obj", "inconsistently oriented"),
        ("moebius.obj", "non-orientable"),
        (
            "nan_coordinate.obj",
            ":2: vertex 1 has a non-finite coordinate",
        ),
        (
            "negative_index_out_of_range.obj",
            "vertex index -4 is out of range",
        ),
        ("no_faces.obj", "the mesh has no faces"),
        (
            "non_manifold_edge.obj",
            "shared by 3 faces (non-manifold edge)",
        ),
        ("repeated_index.obj", "uses vertex 1 more than once"),
        ("truncated_vertex.obj", "a vertex needs 3 coordinates"),
        ("zero_area.obj", "face 2 has zero area"),
        ("zero_index.obj", "vertex index 0 is out of range"),
        ("zero_weight.obj", "vertex weight w is zero"),
        ("bad_counts.off", "'one' is not an integer"),
        ("binary_garbage.off", "not a text file"),
        ("coincident_corners.off", "face 1 has zero area"),
        ("double_cone.off", "vertex 0 is non-manifold"),
        ("empty.off", "the file is empty"),
        ("face_too_small.off", "a face has 2 corners"),
        ("huge_counts.off", "the file ends early"),
        ("index_out_of_range.off", "vertex index 3 is out of range"),
        ("inf_coordinate.off", "vertex 2 has a non-finite coordinate"),
        ("negative_index.off", "vertex index -1 is out of range"),
        ("not_off_header.off", "expected an OFF header"),
        ("truncated_faces.off", "declares 4 faces, found 2"),
        ("truncated_vertices.off", "declares 8 vertices, found 5"),
        (
            "wrong_counts_trailing.off",
            "unexpected data after the declared elements",
        ),
        ("bad_header_format.ply", "unknown PLY format"),
        ("bad_header_type.ply", "unknown PLY type"),
        (
            "byte_order_mismatch.ply",
            "vertex index 33554432 is out of range",
        ),
        ("binary_garbage.ply", "must start with 'ply'"),
        ("empty.ply", "the file is empty"),
        ("huge_counts.ply", "the file ends early"),
        ("huge_list.ply", "the file ends early"),
        ("index_out_of_range.ply", "vertex index 5 is out of range"),
        ("missing_vertex_indices.ply", "no vertex_indices list"),
        ("nan_coordinate.ply", "vertex 2 has a non-finite coordinate"),
        ("point_cloud.ply", "the mesh has no faces"),
        (
            "trailing_data.ply",
            "unexpected data after the declared elements",
        ),
        ("truncated_binary.ply", "the file ends early"),
        ("truncated_header.ply", "no 'end_header' line"),
        ("mesh.stl", "unknown mesh format 'stl'"),
    ];
    for (name, problem) in cases {
        let path = malformed(name);
        assert!(path.is_file(), "{} is missing", path.display());
        let output = tvf(&[OsStr::new("info"), path.as_os_str()]);
        assert_refused(&output, &[name, problem], name);
    }
}

/// Through every kind of subcommand, a malformed mesh stops each with the same
/// message, before any work.
#[test]
fn a_malformed_mesh_is_refused_by_every_subcommand() {
    let fx = fixture();
    let path = malformed("nan_coordinate.obj");
    let m = path.to_str().unwrap();
    let c = fx.file("c.json", r#"{"constraints": []}"#);
    let o = fx.out("out");
    let f = fx.field.as_str();
    for args in [
        vec!["operators", m, "-o", &o],
        vec!["basis", m, "-k", "4", "-o", &o],
        vec!["spectrum", m, "-k", "4"],
        vec!["decompose", m, f, "-o", &o],
        vec!["filter", m, f, "-k", "4", "-o", &o],
        vec!["compress", m, f, "--pairs", "2", "-o", &o],
        vec!["spline", m, "--constraints", &c, "-o", &o],
        vec!["design", m, "--constraints", &c, "--full", "-o", &o],
        vec!["render", m, "-o", &o],
        vec!["export", m, f, "-o", &o],
        vec!["edit", m],
        vec!["demo", "--mesh", m, "-o", &o],
    ] {
        let output = tvf(&args);
        assert_refused(
            &output,
            &["nan_coordinate.obj", "vertex 1 has a non-finite coordinate"],
            args[0],
        );
    }
}

/// Meshes with boundary: the commands accept them (the boundary condition is part of the
/// complex).
#[test]
fn a_mesh_with_boundary_is_accepted() {
    let fx = fixture();
    let open = fx.file(
        "open.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n",
    );
    let field = fx.file("open-field.txt", "1 0 0\n1 0 0\n");
    let o = fx.out("out");
    // Meshes with boundary decompose (the boundary condition is part of the complex).
    let output = tvf(&["decompose", &open, &field, "-o", &o, "--quiet"]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Field files of the wrong shape, size or content, in every format.
#[test]
fn bad_field_files_name_the_file_and_the_problem() {
    let fx = fixture();
    let faces = fx.mesh.face_count();
    let o = fx.out("out");
    // An .npy of shape F×2.
    let flat = fx.path("flat.npy");
    write_npy(
        &flat,
        &NpyArray {
            shape: vec![faces, 2],
            data: vec![1.0; 2 * faces],
            dtype: NpyDtype::F64,
        },
    )
    .unwrap();
    let flat = flat.to_str().unwrap();
    // An .npy with one vector too few.
    let short = fx.path("short.npy");
    write_npy(
        &short,
        &NpyArray {
            shape: vec![faces - 1, 3],
            data: vec![1.0; 3 * (faces - 1)],
            dtype: NpyDtype::F64,
        },
    )
    .unwrap();
    let short = short.to_str().unwrap();
    let not_npy = fx.file("text.npy", "1 0 0\n");
    let nan = fx.file(
        "nan.txt",
        &format!("nan 0 0\n{}", "1 0 0\n".repeat(faces - 1)),
    );
    let words = fx.file("words.txt", "one two three\n");
    let m = fx.mesh_file.as_str();
    let cases: [(Vec<&str>, &[&str]); 6] = [
        (
            vec!["decompose", m, flat, "-o", &o],
            &["flat.npy", "shape", "2]"],
        ),
        (
            vec!["render", m, short, "-o", &o],
            &["short.npy", &format!("{faces} faces")],
        ),
        (
            vec!["export", m, &not_npy, "-o", "x.vtk"],
            &["text.npy", "not an .npy file"],
        ),
        (
            vec!["decompose", m, &nan, "-o", &o],
            &["nan.txt", "vector 0 has a non-finite component"],
        ),
        (
            vec!["decompose", m, &words, "-o", &o],
            &["words.txt", "line 1"],
        ),
        (
            vec!["filter", m, flat, "-k", "4", "-o", &o],
            &["flat.npy", "shape"],
        ),
    ];
    for (args, needles) in cases {
        let output = tvf(&args);
        assert_refused(&output, needles, &format!("{args:?}"));
    }
}

/// Sequences whose frames do not fit the mesh, and an empty frame folder.
#[test]
fn bad_sequences_name_the_file_and_the_problem() {
    let fx = fixture();
    let o = fx.out("x.tvfc");
    let m = fx.mesh_file.as_str();
    let array = fx.path("frames.npy");
    write_face_vector_sequence(&array, &vec![vec![[1.0, 0.0, 0.0]; 10]; 3], NpyDtype::F32).unwrap();
    let output = tvf(&[
        "compress",
        m,
        array.to_str().unwrap(),
        "--pairs",
        "2",
        "-k",
        "8",
        "--no-cache",
        "-o",
        &o,
    ]);
    assert_refused(&output, &["frames.npy", "10 vectors", "256 faces"], "array");
    let empty = fx.path("empty-folder");
    std::fs::create_dir(&empty).unwrap();
    let output = tvf(&[
        "compress",
        m,
        empty.to_str().unwrap(),
        "--pairs",
        "2",
        "-k",
        "8",
        "--no-cache",
        "-o",
        &o,
    ]);
    assert_refused(
        &output,
        &["empty-folder", "no .npy or .txt frame"],
        "folder",
    );
    let output = tvf(&["decompress", m, "no-such-file.tvfc", "-o", &o]);
    assert_refused(&output, &["no-such-file.tvfc"], "missing .tvfc");
    let garbage = fx.file("garbage.tvfc", "this is not a compressed field");
    let output = tvf(&["decompress", m, &garbage, "-o", &o]);
    assert_refused(&output, &["garbage.tvfc", "wrong magic"], "garbage .tvfc");
}

/// A filter curve file that is missing or malformed is bad input (exit 1, file named);
/// a malformed SPEC on the command line is a usage error (exit 2).
#[test]
fn bad_filter_specs_name_the_file_or_the_spec() {
    let fx = fixture();
    let m = fx.mesh_file.as_str();
    let f = fx.field.as_str();
    let o = fx.out("x.npy");
    let output = tvf(&[
        "filter",
        m,
        f,
        "-k",
        "4",
        "--integrable",
        "@missing-curve.json",
        "-o",
        &o,
    ]);
    assert_refused(
        &output,
        &["missing-curve.json", "--integrable"],
        "missing curve",
    );
    let bad = fx.file("curve.json", r#"{"points": [[0, 1], [1]]}"#);
    let output = tvf(&[
        "filter",
        m,
        f,
        "-k",
        "4",
        "--cointegrable",
        &format!("@{bad}"),
        "-o",
        &o,
    ]);
    assert_refused(&output, &["curve.json", "--cointegrable"], "bad curve");
    let output = tvf(&[
        "filter",
        m,
        f,
        "-k",
        "4",
        "--integrable",
        "lowpass:s=1",
        "-o",
        &o,
    ]);
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("lowpass:t="));
}

/// Basis files that are damaged, truncated, of a newer format, not basis files, or
/// made for another mesh.
#[test]
fn bad_basis_files_name_the_file_and_the_problem() {
    let fx = fixture();
    let m = fx.mesh_file.as_str();
    let good = fx.out("good.tvfb");
    let output = tvf(&["basis", m, "-k", "6", "--quiet", "-o", &good]);
    assert!(output.status.success());
    let bytes = std::fs::read(&good).unwrap();
    let write = |name: &str, bytes: &[u8]| {
        let path = fx.path(name);
        std::fs::write(&path, bytes).unwrap();
        path.to_str().unwrap().to_string()
    };
    let mut flipped = bytes.clone();
    let last = flipped.len() - 100;
    flipped[last] ^= 0x01;
    let damaged = write("damaged.tvfb", &flipped);
    let truncated = write("truncated.tvfb", &bytes[..bytes.len() / 2]);
    let mut newer = bytes.clone();
    newer[8..12].copy_from_slice(&99u32.to_le_bytes());
    let newer = write("newer.tvfb", &newer);
    let garbage = write("garbage.tvfb", b"not a basis file at all, just some text");
    let other_mesh = fx.path("other.obj");
    write_obj(&other_mesh, &torus(1.0, 0.3, 16, 8).unwrap()).unwrap();
    let other_mesh = other_mesh.to_str().unwrap();
    let f = fx.field.as_str();
    let c = fx.file("c.json", r#"{"constraints": []}"#);
    let cases: [(Vec<&str>, &[&str]); 5] = [
        (
            vec!["coefficients", m, f, "--basis", &damaged],
            &["damaged.tvfb", "damaged"],
        ),
        (
            vec!["filter", m, f, "--basis", &truncated, "-o", "x.npy"],
            &["truncated.tvfb", "truncated"],
        ),
        (
            vec!["analyze", m, f, "--basis", &newer, "-o", "x"],
            &["newer.tvfb", "version 99"],
        ),
        (
            vec![
                "spline",
                m,
                "--constraints",
                &c,
                "--basis",
                &garbage,
                "-o",
                "x.npy",
            ],
            &["garbage.tvfb", "not a"],
        ),
        (
            vec!["coefficients", other_mesh, f, "--basis", &good],
            &["good.tvfb", "another mesh"],
        ),
    ];
    for (args, needles) in cases {
        let output = tvf(&args);
        assert_refused(&output, needles, &format!("{args:?}"));
    }
}

/// Constraint files: malformed JSON, unknown kinds, indices out of range (face,
/// vertex, edge), bad barycentric coordinates, duplicate ids, negative ω, a fingerprint of
/// another mesh, redundant and conflicting constraints (reported by id), a missing file.
#[test]
fn bad_constraint_files_name_the_file_the_constraint_and_the_problem() {
    let fx = fixture();
    let m = fx.mesh_file.as_str();
    let o = fx.out("x.npy");
    let v = fx.mesh.vertex_count();
    let e = fx.mesh.edge_count();
    let cases: Vec<(&str, String, Vec<String>)> = vec![
        ("syntax.json", r#"{"constraints": [}"#.to_string(), vec!["syntax.json".into()]),
        (
            "kind.json",
            r#"{"constraints": [{"id": "k", "kind": "swirl", "face": 1, "value": 1}]}"#.into(),
            vec!["kind.json".into(), "'k'".into(), "unknown kind 'swirl'".into()],
        ),
        (
            "vertex.json",
            format!(r#"{{"constraints": [{{"id": "src", "kind": "divergence", "vertex": {v}, "value": 1}}]}}"#),
            vec!["vertex.json".into(), "'src'".into(), format!("vertex {v} is out of range")],
        ),
        (
            "edge.json",
            format!(r#"{{"constraints": [{{"id": "vx", "kind": "curl", "edge": {e}, "value": 1}}]}}"#),
            vec!["edge.json".into(), "'vx'".into(), format!("edge {e} is out of range")],
        ),
        (
            "bary.json",
            r#"{"constraints": [{"id": "p", "kind": "vector", "face": 2, "barycentric": [0.5, 0.6, 0.1], "value": [1, 0, 0]}]}"#.into(),
            vec!["bary.json".into(), "'p'".into(), "barycentric".into()],
        ),
        (
            "key.json",
            r#"{"constraints": [{"id": "w", "kind": "curl", "vertex": 3, "value": 1}]}"#.into(),
            vec!["key.json".into(), "'w'".into(), "use \"edge\"".into()],
        ),
        (
            "weight.json",
            r#"{"constraints": [{"id": "z", "kind": "vector", "face": 3, "value": [1, 0, 0], "weight": 0}]}"#.into(),
            vec!["weight.json".into(), "'z'".into(), "weight must be finite and positive".into()],
        ),
        (
            "twice.json",
            r#"{"constraints": [{"id": "a", "kind": "vector", "face": 1, "value": [1, 0, 0]},
                                {"id": "a", "kind": "vector", "face": 2, "value": [1, 0, 0]}]}"#.into(),
            vec!["twice.json".into(), "'a' is used twice".into()],
        ),
        (
            "omega.json",
            r#"{"omega": -1, "constraints": []}"#.into(),
            vec!["omega.json".into(), "omega must be finite and non-negative".into()],
        ),
        (
            "fingerprint.json",
            r#"{"mesh_fingerprint": "0123456789abcdef", "constraints": []}"#.into(),
            vec![
                "fingerprint.json".into(),
                "0123456789abcdef".into(),
                format!("{:016x}", fx.mesh.fingerprint()),
            ],
        ),
        (
            "redundant.json",
            r#"{"constraints": [{"id": "a", "kind": "vector", "face": 3, "value": [1, 0, 0]},
                                {"id": "b", "kind": "vector", "face": 3, "value": [1, 0, 0]}]}"#.into(),
            vec!["redundant.json".into(), "'b' is redundant".into(), "\"a\"".into()],
        ),
        (
            "conflict.json",
            r#"{"constraints": [{"id": "a", "kind": "vector", "face": 3, "value": [1, 0, 0]},
                                {"id": "b", "kind": "vector", "face": 3, "value": [0, 1, 0]}]}"#.into(),
            vec!["conflict.json".into(), "'b' is conflicting".into(), "\"a\"".into()],
        ),
    ];
    for (name, content, needles) in &cases {
        let path = fx.file(name, content);
        let output = tvf(&["spline", m, "--constraints", &path, "-k", "20", "-o", &o]);
        let needles: Vec<&str> = needles.iter().map(String::as_str).collect();
        assert_refused(&output, &needles, name);
        assert!(!Path::new(&o).exists(), "{name}: an output was written");
    }
    // The same checks guard design and render's overlay.
    let vertex = fx.path("vertex.json");
    let output = tvf(&[
        OsStr::new("design"),
        OsStr::new(m),
        OsStr::new("--constraints"),
        vertex.as_os_str(),
        OsStr::new("--full"),
        OsStr::new("-o"),
        OsStr::new(&o),
    ]);
    assert_refused(&output, &["vertex.json", "'src'", "out of range"], "design");
    let edge = fx.path("edge.json");
    let output = tvf(&[
        OsStr::new("render"),
        OsStr::new(m),
        OsStr::new("--constraints"),
        edge.as_os_str(),
        OsStr::new("-o"),
        OsStr::new(&fx.out("x.png")),
    ]);
    assert_refused(&output, &["edge.json", "'vx'", "out of range"], "render");
    let output = tvf(&["spline", m, "--constraints", "no-such.json", "-o", &o]);
    assert_refused(
        &output,
        &["no-such.json", "cannot read"],
        "missing constraints",
    );
}

/// the editor refuses what it cannot serve before it starts the server.
#[test]
fn the_editor_refuses_bad_input_before_serving() {
    let fx = fixture();
    let m = fx.mesh_file.as_str();
    // DEC on the quad-grid torus, which is not Delaunay: refused before serving.
    let output = tvf(&["edit", m, "--discretization", "dec-barycentric", "-k", "10"]);
    assert_refused(
        &output,
        &["torus.obj", "not Delaunay"],
        "DEC on a non-Delaunay mesh",
    );
    let conflict = fx.file(
        "conflict.json",
        r#"{"constraints": [{"id": "a", "kind": "vector", "face": 3, "value": [1, 0, 0]},
                            {"id": "b", "kind": "vector", "face": 3, "value": [0, 1, 0]}]}"#,
    );
    let output = tvf(&[
        "edit",
        m,
        "-k",
        "20",
        "--no-cache",
        "--constraints",
        &conflict,
    ]);
    assert_refused(
        &output,
        &["conflict.json", "'b'", "conflicting"],
        "conflict",
    );
}

/// an output that cannot be written names the file.
#[test]
fn an_unwritable_output_names_the_file() {
    let fx = fixture();
    let m = fx.mesh_file.as_str();
    let f = fx.field.as_str();
    let blocker = fx.file("blocker", "a file where a folder is expected");
    let inside = format!("{blocker}/x");
    for args in [
        vec!["render", m, "-o", &format!("{inside}.png")],
        vec!["export", m, f, "-o", &format!("{inside}.vtk")],
        vec!["basis", m, "-k", "4", "-o", &format!("{inside}.tvfb")],
        vec!["decompose", m, f, "-o", &inside],
    ] {
        let output = tvf(&args);
        assert_refused(&output, &["blocker/x"], args[0]);
    }
}
