//! End-to-end: inputs that used to give puzzling errors get clear ones: a constraint file with a
//! byte-order mark is read, a negative index is called negative, and inputs that never end (a
//! link to `/dev/zero` as a field, a basis-free compressed file or a constraint file) are
//! refused after at most what their format can justify, naming the file.

use crate::common::{assert_success, tvf};
use std::process::Output;

fn run(dir: &std::path::Path, args: &[&str]) -> Output {
    tvf()
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the tvf binary runs")
}

#[test]
fn a_byte_order_mark_is_skipped_and_a_negative_index_is_named_negative() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let record =
        r#"{"constraints": [{"id": "a", "kind": "vector", "face": 3, "value": [1, 0, 0]}]}"#;
    std::fs::write(d.join("bom.json"), format!("\u{feff}{record}")).unwrap();
    let cache = d.join("cache").display().to_string();
    let spline = |constraints: &str| {
        run(
            d,
            &[
                "-q",
                "spline",
                "--example",
                "torus",
                "-k",
                "10",
                "--cache-dir",
                &cache,
                "--constraints",
                constraints,
                "-o",
                "s.npy",
            ],
        )
    };
    assert_success(&spline("bom.json"));
    for (what, key) in [("face", "face"), ("vertex", "vertex")] {
        let kind = if what == "face" {
            "vector"
        } else {
            "divergence"
        };
        let value = if what == "face" { "[1, 0, 0]" } else { "1" };
        std::fs::write(
            d.join("neg.json"),
            format!(r#"{{"constraints": [{{"id": "n", "kind": "{kind}", "{key}": -1, "value": {value}}}]}}"#),
        )
        .unwrap();
        let output = spline("neg.json");
        let message = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{message}");
        assert!(
            message.contains("neg.json") && message.contains(&format!("{what} -1 is negative")),
            "{message}"
        );
        assert!(!message.contains("has 0 of them"), "{message}");
    }
}

#[cfg(unix)]
#[test]
fn endless_inputs_are_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for name in ["zero.npy", "zero.tvfc", "zero.json"] {
        std::os::unix::fs::symlink("/dev/zero", d.join(name)).unwrap();
    }
    let cache = d.join("cache").display().to_string();
    let cases: [&[&str]; 3] = [
        &["render", "--example", "torus", "zero.npy", "-o", "x.png"],
        &[
            "decompress",
            "--example",
            "torus",
            "zero.tvfc",
            "--cache-dir",
            &cache,
            "-o",
            "x.npy",
        ],
        &[
            "spline",
            "--example",
            "torus",
            "-k",
            "10",
            "--cache-dir",
            &cache,
            "--constraints",
            "zero.json",
            "-o",
            "x.npy",
        ],
    ];
    for args in cases {
        let started = std::time::Instant::now();
        let output = run(d, args);
        let message = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {message}");
        assert!(message.contains("zero."), "{args:?}: {message}");
        assert!(started.elapsed() < std::time::Duration::from_secs(30));
    }
}

#[test]
fn a_concave_polygon_is_kept_reported_by_info_and_rendered() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A square with a notch (reflex corner 4), one polygon; and a square as two convex quads.
    std::fs::write(
        d.join("notch.obj"),
        "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 2 1 0\nv 0 4 0\nf 1 2 3 4 5\n",
    )
    .unwrap();
    std::fs::write(
        d.join("convex.obj"),
        "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 2 0 0\nv 2 4 0\nf 1 5 6 4\nf 5 2 3 6\n",
    )
    .unwrap();
    let output = run(d, &["info", "notch.obj", "--json"]);
    assert_success(&output);
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let warnings = report["warnings"].to_string();
    assert!(
        warnings.contains("non-convex polygons") && warnings.contains("line 6"),
        "{report}"
    );
    // The notch is a valid polygon: polygon-dec (the default on polygons) renders it.
    let output = run(d, &["render", "notch.obj", "-o", "notch.png"]);
    assert_success(&output);
    assert!(d.join("notch.png").is_file());
    let output = run(d, &["info", "convex.obj", "--json"]);
    assert_success(&output);
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert!(
        !report["warnings"].to_string().contains("non-convex"),
        "{report}"
    );
}

#[cfg(unix)]
#[test]
fn an_endless_mesh_stream_is_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink("/dev/zero", dir.path().join("zero.obj")).unwrap();
    let started = std::time::Instant::now();
    let output = run(dir.path(), &["info", "zero.obj"]);
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("zero.obj") && message.contains("larger than"),
        "{message}"
    );
    assert!(started.elapsed() < std::time::Duration::from_secs(60));
}

/// Report details: 7 trailing bytes of an `.npy` are called 7 (not 1), an empty, blank or
/// multi-line constraint id is refused (its residual line would have no label, or break).
#[test]
fn trailing_npy_bytes_are_counted_and_an_empty_id_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cache = d.join("cache").display().to_string();
    let npy = d.join("f.npy");
    tvf_spectral::write_face_vectors(&npy, &vec![[1.0, 0.0, 0.0]; 1280]).unwrap();
    let mut bytes = std::fs::read(&npy).unwrap();
    bytes.extend_from_slice(b"1234567");
    std::fs::write(&npy, bytes).unwrap();
    let args = [
        "coefficients",
        "--example",
        "icosphere",
        "f.npy",
        "-k",
        "10",
    ];
    let output = run(d, &[&args[..], &["--cache-dir", &cache]].concat());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("f.npy") && stderr.contains("7 bytes of trailing data"),
        "{stderr}"
    );

    for id in ["", "  ", "a\\nb"] {
        let constraints = format!(
            r#"{{"constraints": [{{"id": "a", "kind": "vector", "face": 3, "value": [1, 0, 0]}},
                {{"id": "{id}", "kind": "vector", "face": 9, "value": [0, 1, 0]}}]}}"#
        );
        std::fs::write(d.join("c.json"), constraints).unwrap();
        let args = [
            "spline",
            "--example",
            "icosphere",
            "--constraints",
            "c.json",
        ];
        let output = run(
            d,
            &[
                &args[..],
                &["-k", "10", "--cache-dir", &cache, "-o", "s.npy"],
            ]
            .concat(),
        );
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{id:?}: {stderr}");
        assert!(
            stderr.contains("c.json")
                && stderr.contains("constraint 1")
                && stderr.contains("has the id"),
            "{id:?}: {stderr}"
        );
        assert!(!d.join("s.npy").exists());
    }
}

/// `tvf info` on an OBJ that starts with a byte-order mark reports what it reports without
/// one (the mark used to hide the first vertex and shift every index), and on two closed
/// components, one reversed, names the reversed one although the total volume is positive.
#[test]
fn info_reads_a_marked_obj_and_names_a_reversed_component() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mesh = tvf_core::generate::genus_surface(1, 4);
    let mut text = String::from("v 9 9 9\n");
    for p in mesh.positions() {
        text += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for f in mesh.faces() {
        text += &format!("f {} {} {}\n", f[0] + 2, f[1] + 2, f[2] + 2);
    }
    std::fs::write(d.join("plain.obj"), &text).unwrap();
    std::fs::write(d.join("marked.obj"), format!("\u{feff}{text}")).unwrap();
    let info = |name: &str| -> serde_json::Value {
        let output = run(d, &["info", name, "--json"]);
        assert_success(&output);
        serde_json::from_slice(&output.stdout).unwrap()
    };
    let (plain, marked) = (info("plain.obj"), info("marked.obj"));
    for key in ["vertices", "faces", "total_area", "genus", "warnings"] {
        assert_eq!(plain[key], marked[key], "{key}: {plain} vs {marked}");
    }

    // Two octahedra, the second reversed and half the size.
    let mut two = String::new();
    let corners = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let faces = [
        [1, 3, 5],
        [3, 2, 5],
        [2, 4, 5],
        [4, 1, 5],
        [3, 1, 6],
        [2, 3, 6],
        [4, 2, 6],
        [1, 4, 6],
    ];
    for (k, scale) in [(0usize, 2.0), (1, 1.0)] {
        for c in corners {
            two += &format!(
                "v {} {} {}\n",
                5.0 * k as f64 + scale * c[0],
                scale * c[1],
                scale * c[2]
            );
        }
        for [a, b, c] in faces {
            let [b, c] = if k == 1 { [c, b] } else { [b, c] };
            two += &format!("f {} {} {}\n", 6 * k + a, 6 * k + b, 6 * k + c);
        }
    }
    std::fs::write(d.join("two.obj"), two).unwrap();
    let output = run(d, &["info", "two.obj"]);
    assert_success(&output);
    let report = String::from_utf8_lossy(&output.stdout);
    assert!(
        report.contains("normals point inward") && report.contains("component 1"),
        "{report}"
    );
}
