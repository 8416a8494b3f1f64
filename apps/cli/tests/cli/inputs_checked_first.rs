//! End-to-end: a command that takes a basis checks every other input before it computes one:
//! a field of the wrong length, a compressed file of another mesh, a constraint out of range
//! are refused at once, and no basis is left in the cache for a command that failed.

use crate::common::{self, assert_success, tvf};
use std::path::Path;
use tvf_core::generate::{genus_surface, icosphere};
use tvf_core::io::write_obj;

fn run(dir: &Path, args: &[&str]) -> std::process::Output {
    tvf()
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the tvf binary runs")
}

fn cached_bases(folder: &Path) -> usize {
    std::fs::read_dir(folder).map_or(0, |entries| {
        entries
            .filter(|e| {
                e.as_ref()
                    .is_ok_and(|e| e.file_name().to_string_lossy().ends_with(".tvfb"))
            })
            .count()
    })
}

#[test]
fn bad_inputs_are_refused_before_a_basis_is_computed() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_obj(d.join("ico.obj"), &icosphere(3)).unwrap();
    write_obj(d.join("other.obj"), &genus_surface(1, 4)).unwrap();
    // icosphere(3) has 1280 faces: 1000 vectors is the wrong length.
    std::fs::write(d.join("short.txt"), "1 0 0\n".repeat(1000)).unwrap();
    std::fs::write(d.join("f.txt"), "1 0 0\n".repeat(1280)).unwrap();
    std::fs::write(
        d.join("far.json"),
        r#"{"constraints": [{"id": "a", "kind": "vector", "face": 99999, "value": [1, 0, 0]}]}"#,
    )
    .unwrap();
    // A compressed file of the icosphere, decompressed on another mesh.
    let made = d.join("made").display().to_string();
    let compress = [
        "compress",
        "ico.obj",
        "f.txt",
        "--pairs",
        "4",
        "--cache-dir",
        &made,
    ];
    assert_success(&run(d, &[&compress[..], &["-o", "ico.tvfc"]].concat()));

    let cache = d.join("cache");
    let c = cache.display().to_string();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec![
                "decompress",
                "other.obj",
                "ico.tvfc",
                "--cache-dir",
                &c,
                "-o",
                "x.npy",
            ],
            "ico.tvfc",
        ),
        (
            vec![
                "compress",
                "ico.obj",
                "short.txt",
                "--pairs",
                "4",
                "--cache-dir",
                &c,
                "-o",
                "x.tvfc",
            ],
            "short.txt",
        ),
        (
            vec![
                "filter",
                "ico.obj",
                "short.txt",
                "-k",
                "20",
                "--cache-dir",
                &c,
                "-o",
                "x.npy",
            ],
            "short.txt",
        ),
        (
            vec![
                "coefficients",
                "ico.obj",
                "short.txt",
                "-k",
                "20",
                "--cache-dir",
                &c,
            ],
            "short.txt",
        ),
        (
            vec![
                "analyze",
                "ico.obj",
                "short.txt",
                "-k",
                "20",
                "--cache-dir",
                &c,
                "-o",
                "an",
            ],
            "short.txt",
        ),
        (
            vec![
                "rate-distortion",
                "ico.obj",
                "short.txt",
                "--pairs",
                "2",
                "--cache-dir",
                &c,
                "-o",
                "rd",
            ],
            "short.txt",
        ),
        (
            vec![
                "edit",
                "ico.obj",
                "--constraints",
                "far.json",
                "-k",
                "20",
                "--cache-dir",
                &c,
            ],
            "99999",
        ),
    ];
    for (args, needle) in cases {
        let output = run(d, &args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
        assert_eq!(cached_bases(&cache), 0, "{args:?} computed a basis first");
    }
}

/// A file output that names a folder (`-o DIR` for `filter`, `compress`, `spline`, `basis`)
/// and an editor on a complex that cannot draw its fields (a complex folder saying
/// `"sampling": "none"`) are refused before a basis is computed (they once were refused only
/// after it, and the basis was cached).
#[test]
fn outputs_and_capabilities_are_refused_before_a_basis_is_computed() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_obj(d.join("ico.obj"), &icosphere(3)).unwrap();
    std::fs::write(d.join("f.txt"), "1 0 0\n".repeat(1280)).unwrap();
    std::fs::write(
        d.join("c.json"),
        r#"{"constraints": [{"id": "a", "kind": "vector", "face": 1, "value": [1, 0, 0]}]}"#,
    )
    .unwrap();
    std::fs::create_dir(d.join("out")).unwrap();
    assert_success(&run(d, &["operators", "ico.obj", "-o", "ops"]));
    let info = d.join("ops/info.json");
    let text = std::fs::read_to_string(&info).unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    json["sampling"] = "none".into();
    std::fs::write(&info, json.to_string()).unwrap();
    let cache = d.join("cache");
    let c = cache.display().to_string();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["filter", "ico.obj", "f.txt", "-k", "20", "-o", "out"],
            "is a folder",
        ),
        (
            vec!["compress", "ico.obj", "f.txt", "--pairs", "4", "-o", "out"],
            "is a folder",
        ),
        (
            vec![
                "spline",
                "ico.obj",
                "--constraints",
                "c.json",
                "-k",
                "20",
                "-o",
                "out",
            ],
            "is a folder",
        ),
        (
            vec!["basis", "ico.obj", "-k", "20", "-o", "out"],
            "is a folder",
        ),
        (
            vec!["edit", "ico.obj", "--complex", "ops", "-k", "20"],
            "sampling fields",
        ),
    ];
    for (args, needle) in cases {
        let args = [&args[..], &["--cache-dir", &c][..]].concat();
        let args = match args[0] {
            // `tvf basis` keeps no cache.
            "basis" => args[..args.len() - 2].to_vec(),
            _ => args,
        };
        let output = common::output_within(tvf().current_dir(d).args(&args), 60);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
        assert!(
            !stderr.contains("computed in"),
            "{args:?} computed a basis: {stderr}"
        );
        assert_eq!(cached_bases(&cache), 0, "{args:?} computed a basis first");
    }
}
