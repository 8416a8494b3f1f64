//! End-to-end: inputs whose numbers overflow `f64` arithmetic (constraint values near 1e308, a
//! divergence of 1e300, omega = 1e308, fields near 1e300, a mesh scaled by 1e100) are refused
//! with an error naming the file (and the constraint), never answered with a NaN field and
//! exit 0; a cached basis of the wrong size is recomputed.

use crate::common::tvf;
use std::path::Path;
use std::process::Output;

/// Runs `tvf` with `args` and returns (exit code, stderr).
fn run(args: &[&str]) -> (Option<i32>, String, Output) {
    let output = tvf().args(args).output().expect("the tvf binary runs");
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
        output,
    )
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// Every design solver on `constraints`, each expected to fail naming the file and `needle`.
fn assert_every_solver_refuses(dir: &Path, constraints: &str, file: &str, needles: &[&str]) {
    let cache = dir.join("cache").display().to_string();
    let out = dir.join("out.npy");
    let out_text = out.display().to_string();
    let solvers: [&[&str]; 3] = [
        &["spline", "-k", "40"],
        &["design", "--reduced", "-k", "40"],
        &["design", "--full"],
    ];
    for solver in solvers {
        let mut args = vec!["-q"];
        args.extend_from_slice(solver);
        args.extend_from_slice(&[
            "--example",
            "torus",
            "--cache-dir",
            &cache,
            "--constraints",
            constraints,
            "-o",
            &out_text,
        ]);
        let (code, stderr, output) = run(&args);
        assert_eq!(
            code,
            Some(1),
            "{solver:?} on {file}: {stderr}\n{}",
            String::from_utf8_lossy(&output.stdout)
        );
        assert!(stderr.contains(file), "{solver:?}: {stderr}");
        for needle in needles {
            assert!(stderr.contains(needle), "{solver:?}: {needle}: {stderr}");
        }
        assert!(!out.exists(), "{solver:?} wrote a field");
    }
}

#[test]
fn huge_constraint_values_are_errors_naming_file_and_constraint() {
    let dir = tempfile::tempdir().unwrap();
    for (name, value) in [
        ("v308.json", "[1e308, 1e308, -1e308]"),
        ("v200.json", "[1e200, 1e200, -1e200]"),
    ] {
        let file = write(
            dir.path(),
            name,
            &format!(
                r#"{{"omega": 0.1, "constraints": [
                  {{"id": "calm", "kind": "vector", "face": 3, "value": [1, 0, 0]}},
                  {{"id": "wild", "kind": "vector", "face": 12, "value": {value}}}]}}"#
            ),
        );
        assert_every_solver_refuses(dir.path(), &file, name, &["'wild'", "overflow f64"]);
    }
    let file = write(
        dir.path(),
        "div.json",
        r#"{"omega": 0.1, "constraints": [
            {"id": "source", "kind": "divergence", "vertex": 12, "value": 1e300},
            {"id": "calm", "kind": "vector", "face": 3, "value": [1, 0, 0]}]}"#,
    );
    let cache = dir.path().join("cache").display().to_string();
    let out = dir.path().join("div.npy").display().to_string();
    for solver in [&["design", "--reduced"][..], &["design", "--full"][..]] {
        let mut args = vec!["-q"];
        args.extend_from_slice(solver);
        args.extend_from_slice(&[
            "-k",
            "40",
            "--example",
            "torus",
            "--cache-dir",
            &cache,
            "--constraints",
            &file,
            "-o",
            &out,
        ]);
        if solver[1] == "--full" {
            args.retain(|a| *a != "-k" && *a != "40");
        }
        let (code, stderr, _) = run(&args);
        assert_eq!(code, Some(1), "{solver:?}: {stderr}");
        assert!(
            stderr.contains("div.json") && stderr.contains("'source'"),
            "{solver:?}: {stderr}"
        );
    }
}

#[test]
fn an_omega_of_1e308_is_an_error_naming_the_file_and_omega() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(
        dir.path(),
        "omega.json",
        r#"{"omega": 1e308, "constraints": [
            {"id": "a", "kind": "vector", "face": 12, "value": [1, 0, 0]}]}"#,
    );
    assert_every_solver_refuses(dir.path(), &file, "omega.json", &["omega", "1e308"]);
}

#[test]
fn fields_and_meshes_too_large_for_f64_are_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    // An octahedron, and the same scaled by 1e100.
    let corners = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let faces = "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";
    let obj = |scale: f64| {
        let mut text: String = corners
            .iter()
            .map(|c| format!("v {} {} {}\n", c[0] * scale, c[1] * scale, c[2] * scale))
            .collect();
        text.push_str(faces);
        text
    };
    let mesh = write(dir.path(), "oct.obj", &obj(1.0));
    let big = write(dir.path(), "big.obj", &obj(1e100));
    let (code, stderr, output) = run(&["info", &big]);
    assert_eq!(
        code,
        Some(1),
        "{stderr}\n{}",
        String::from_utf8_lossy(&output.stdout)
    );
    assert!(
        stderr.contains("big.obj") && stderr.contains("too large"),
        "{stderr}"
    );
    let (code, stderr, _) = run(&["info", &big, "--json"]);
    assert_eq!(code, Some(1), "{stderr}");

    let huge = write(dir.path(), "huge.txt", &"1e300 1e300 0\n".repeat(8));
    let png = dir.path().join("h.png");
    let (code, stderr, _) = run(&["render", &mesh, &huge, "-o", png.to_str().unwrap()]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("huge.txt") && stderr.contains("too large"),
        "{stderr}"
    );
    assert!(!png.exists());

    let parts = dir.path().join("parts");
    let (code, stderr, output) = run(&["decompose", &mesh, &huge, "-o", parts.to_str().unwrap()]);
    assert_eq!(
        code,
        Some(1),
        "{stderr}\n{}",
        String::from_utf8_lossy(&output.stdout)
    );
    assert!(stderr.contains("huge.txt"), "{stderr}");
    assert!(!parts.join("integrable.npy").exists());

    // Large but representable: squares stay finite, so the decomposition works.
    let large = write(dir.path(), "large.txt", &"1e100 2e100 0\n".repeat(8));
    let (code, stderr, output) = run(&[
        "decompose",
        &mesh,
        &large,
        "--json",
        "-o",
        parts.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0), "{stderr}");
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    for key in [
        "integrable_energy",
        "cointegrable_energy",
        "harmonic_energy",
    ] {
        assert!(report[key].as_f64().is_some_and(f64::is_finite), "{report}");
    }
}

#[test]
fn a_cached_basis_of_the_wrong_size_is_recomputed() {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cache");
    let cache_text = cache.display().to_string();
    let constraints = write(
        dir.path(),
        "c.json",
        r#"{"constraints": [{"id": "a", "kind": "vector", "face": 12, "value": [1, 0, 0]}]}"#,
    );
    let out = dir.path().join("s.npy").display().to_string();
    let spline = |k: &str| {
        let (code, stderr, output) = run(&[
            "spline",
            "--example",
            "torus",
            "-k",
            k,
            "--cache-dir",
            &cache_text,
            "--constraints",
            &constraints,
            "--json",
            "-o",
            &out,
        ]);
        assert_eq!(code, Some(0), "{stderr}");
        let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
        (report["basis_fields"].as_u64(), stderr)
    };
    let (fields, _) = spline("10");
    assert_eq!(fields, Some(10));
    let ten = std::fs::read_dir(&cache)
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    let name = ten.file_name().unwrap().to_string_lossy().into_owned();
    assert!(name.ends_with("-d10.tvfb"), "{name}");
    // The 10-field file under the names of a 20-field and a 6-field basis.
    for k in ["20", "6"] {
        let renamed = cache.join(name.replace("-d10.", &format!("-d{k}.")));
        std::fs::copy(&ten, &renamed).unwrap();
        let (fields, stderr) = spline(k);
        assert_eq!(fields, Some(k.parse().unwrap()), "{stderr}");
        assert!(
            stderr.contains("cached basis is unusable") && stderr.contains("10 fields"),
            "{stderr}"
        );
        // Recomputed and cached again: the next run uses it silently.
        let (fields, stderr) = spline(k);
        assert_eq!(fields, Some(k.parse().unwrap()));
        assert!(stderr.contains("using cached basis"), "{stderr}");
    }
}

/// `tvf filter` with gains whose products overflow `f64` (`--rest 1e308`, a field ×1e149 with
/// `--rest 1e300`, a curve of gain 1e308) is an error naming the cause, and writes nothing: never
/// a field of NaN entries with exit 0 (which the text reader would then refuse).
#[test]
fn a_filter_whose_result_overflows_is_an_error_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cache = d.join("cache").display().to_string();
    // icosphere(3) has 1280 faces; a field not in the span of 40 eigenfields (a rest part).
    let field: String = (0..1280)
        .map(|t| format!("{} {} 0\n", 1.0 + (t % 7) as f64, (t % 3) as f64))
        .collect();
    let plain = write(d, "f.txt", &field);
    let scaled: String = (0..1280)
        .map(|t| format!("{}e149 {} 0\n", 1.0 + (t % 7) as f64, (t % 3) as f64))
        .collect();
    let big = write(d, "big.txt", &scaled);
    let cases: [(&str, &[&str]); 4] = [
        (&plain, &["--rest", "1e308"]),
        (&big, &["--rest", "1e300"]),
        (&plain, &["--integrable", "curve:0,1e308"]),
        (&plain, &["--cointegrable", "curve:0,1e308;100,1e308"]),
    ];
    for (field, gains) in cases {
        for out in ["out.npy", "out.txt"] {
            let output = d.join(out).display().to_string();
            let mut args = vec!["filter", "--example", "icosphere", field, "-k", "40"];
            args.extend_from_slice(&["--cache-dir", &cache, "--json", "-o", &output]);
            args.extend_from_slice(gains);
            let (code, stderr, result) = run(&args);
            let stdout = String::from_utf8_lossy(&result.stdout);
            assert_eq!(code, Some(1), "{gains:?} {out}: {stderr}\n{stdout}");
            assert!(
                stderr.contains("not finite")
                    || stderr.contains("overflows")
                    || stderr.contains("cannot write the field"),
                "{gains:?}: {stderr}"
            );
            assert!(!stdout.contains("null"), "{gains:?}: {stdout}");
            assert!(!d.join(out).exists(), "{gains:?}: {out} was written");
        }
    }
    // The same command with ordinary gains writes a field the readers accept.
    let output = d.join("ok.txt").display().to_string();
    let args = [
        "filter",
        "--example",
        "icosphere",
        &plain,
        "-k",
        "40",
        "--cache-dir",
        &cache,
        "--rest",
        "2",
        "-o",
        &output,
    ];
    let (code, stderr, _) = run(&args);
    assert_eq!(code, Some(0), "{stderr}");
    let again = d.join("again.txt").display().to_string();
    let args = [
        "filter",
        "--example",
        "icosphere",
        &output,
        "-k",
        "40",
        "--cache-dir",
        &cache,
        "-o",
        &again,
    ];
    let (code, stderr, _) = run(&args);
    assert_eq!(
        code,
        Some(0),
        "the filter's own output is readable: {stderr}"
    );
}

/// A field whose largest component is about 1e-300 has squared norms that underflow: it is
/// refused naming the file (its energies and shares would all be reported as 0).
#[test]
fn a_field_too_small_for_f64_energies_is_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cache = d.join("cache").display().to_string();
    let tiny: String = (0..1280)
        .map(|t| format!("{}e-300 {}e-300 0\n", 1.0 + (t % 7) as f64, (t % 3) as f64))
        .collect();
    let tiny = write(d, "tiny.txt", &tiny);
    let analysis = d.join("an").display().to_string();
    for command in ["coefficients", "analyze"] {
        let mut args = vec![command, "--example", "icosphere", &tiny, "-k", "40"];
        args.extend_from_slice(&["--cache-dir", &cache]);
        if command == "analyze" {
            args.extend_from_slice(&["-o", &analysis]);
        }
        let (code, stderr, output) = run(&args);
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert_eq!(code, Some(1), "{command}: {stderr}\n{stdout}");
        assert!(
            stderr.contains("tiny.txt") && stderr.contains("too small"),
            "{command}: {stderr}"
        );
        assert!(!stdout.contains("0.00 %"), "{command}: {stdout}");
    }
}
