//! The progress of the passes over a basis file read in blocks, on stderr: with stderr
//! redirected, plain `basis file: PASS, KiB DONE/TOTAL` lines for each pass of more than one
//! block (`$TVF_BASIS_BLOCK_BYTES` made small), the last at its total — the projection and the
//! synthesis of `filter`, the rows of `U` and the synthesis of `spline` — and none with
//! `--quiet`; the results the same either way.

use super::common::{assert_success, tvf, write_field_and_constraints};
use std::path::Path;
use tvf_core::generate::torus;
use tvf_core::io::write_obj;

/// `tvf ARGS` with blocks of 4 KiB (a few stored columns of the torus's basis), its stderr.
#[track_caller]
fn stderr_in_small_blocks(dir: &Path, args: &[&str]) -> String {
    let output = tvf()
        .current_dir(dir)
        .args(args)
        .env("TVF_BASIS_BLOCK_BYTES", "4096")
        .output()
        .unwrap();
    assert_success(&output);
    String::from_utf8_lossy(&output.stderr).to_string()
}

/// The `(pass, done, total)` of each progress line of `stderr`.
fn progress_lines(stderr: &str) -> Vec<(String, u64, u64)> {
    stderr
        .lines()
        .filter_map(|line| {
            let rest = line.strip_prefix("basis file: ")?;
            let (pass, counts) = rest.split_once(", KiB ")?;
            let (done, total) = counts.split_once('/')?;
            Some((pass.to_string(), done.parse().ok()?, total.parse().ok()?))
        })
        .collect()
}

/// Checks that every pass of `passes` has progress lines, within its total, the last at it.
#[track_caller]
fn shows_passes(stderr: &str, passes: &[&str]) {
    let lines = progress_lines(stderr);
    for pass in passes {
        let of_pass: Vec<&(String, u64, u64)> = lines.iter().filter(|l| l.0 == *pass).collect();
        assert!(of_pass.len() >= 2, "{pass}: {stderr}");
        assert!(of_pass.iter().all(|l| l.1 <= l.2 && l.2 > 0), "{stderr}");
        let last = of_pass[of_pass.len() - 1];
        assert_eq!(last.1, last.2, "{stderr}");
    }
}

#[test]
fn passes_over_a_basis_file_show_their_progress_unless_quiet() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = torus(1.0, 0.45, 24, 12).unwrap();
    write_obj(dir.path().join("torus.obj"), &mesh).unwrap();
    write_field_and_constraints(&mesh, dir.path());
    let basis = tvf()
        .current_dir(dir.path())
        .args([
            "basis",
            "torus.obj",
            "-k",
            "60",
            "--quiet",
            "-o",
            "basis.tvfb",
        ])
        .output()
        .unwrap();
    assert_success(&basis);

    let filter = [
        "filter",
        "torus.obj",
        "field.txt",
        "--basis",
        "basis.tvfb",
        "--integrable",
        "lowpass:t=0.01",
        "-o",
    ];
    let stderr = stderr_in_small_blocks(dir.path(), &[&filter[..], &["loud.npy"]].concat());
    assert!(stderr.contains("read in blocks"), "{stderr}");
    shows_passes(&stderr, &["projecting", "synthesising"]);
    let quiet = stderr_in_small_blocks(
        dir.path(),
        &[&filter[..], &["quiet.npy", "--quiet"]].concat(),
    );
    assert!(
        progress_lines(&quiet).is_empty() && !quiet.contains("basis file"),
        "{quiet}"
    );
    assert_eq!(
        std::fs::read(dir.path().join("loud.npy")).unwrap(),
        std::fs::read(dir.path().join("quiet.npy")).unwrap()
    );

    let spline = [
        "spline",
        "torus.obj",
        "--constraints",
        "c.json",
        "--basis",
        "basis.tvfb",
        "-o",
        "spline.npy",
    ];
    let stderr = stderr_in_small_blocks(dir.path(), &spline);
    shows_passes(&stderr, &["rows", "synthesising"]);
}
