//! End-to-end: an output that is not a regular file — a character device such as `/dev/null`,
//! a FIFO — is written to directly, streaming, and stays what it is: atomic replacement by
//! rename is for regular files (renaming over a device node as root would destroy it, and the
//! temporary file cannot be made in `/dev` as a normal user). The tests make their own device
//! node (`mknod`, as root: CI runs as root) and FIFO (`mkfifo`) in a temporary folder.
#![cfg(unix)]

use crate::common::{assert_success, tvf};
use std::io::Read;
use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

/// A constraint file and a cache folder in `dir`.
fn inputs(dir: &Path) -> (PathBuf, PathBuf) {
    let constraints = dir.join("c.json");
    std::fs::write(
        &constraints,
        r#"{"constraints": [{"id": "a", "kind": "vector", "face": 3, "value": [1, 0, 0]}]}"#,
    )
    .unwrap();
    (constraints, dir.join("cache"))
}

/// `tvf spline` on the icosphere writing its field to `output`.
fn spline_into(output: &Path, constraints: &Path, cache: &Path) -> std::process::Output {
    tvf()
        .args([
            "spline",
            "--example",
            "icosphere",
            "-k",
            "40",
            "--constraints",
        ])
        .arg(constraints)
        .arg("--cache-dir")
        .arg(cache)
        .arg("-o")
        .arg(output)
        .output()
        .expect("the tvf binary runs")
}

/// A null character device (major 1, minor 3) made in a temporary folder; `None` where the
/// system does not let this user make one (not root), which CI (root) never accepts.
fn null_device(dir: &Path) -> Option<PathBuf> {
    let device = dir.join("null");
    let made = Command::new("mknod")
        .arg(&device)
        .args(["c", "1", "3"])
        .status()
        .is_ok_and(|s| s.success());
    if !made && std::env::var("CI").as_deref() == Ok("true") {
        panic!("mknod failed: CI runs as root and must test a device of its own");
    }
    made.then_some(device)
}

#[test]
fn a_device_output_is_written_through_and_stays_a_device() {
    let dir = tempfile::tempdir().unwrap();
    let (constraints, cache) = inputs(dir.path());
    // Without the right to make a device node, the system's own /dev/null: a normal user
    // cannot make a temporary file in /dev, so this too fails if tvf does not stream.
    let device = null_device(dir.path()).unwrap_or_else(|| PathBuf::from("/dev/null"));
    let output = spline_into(&device, &constraints, &cache);
    assert_success(&output);
    let kind = std::fs::symlink_metadata(&device).unwrap().file_type();
    assert!(kind.is_char_device(), "{}: {kind:?}", device.display());
    let folder = device.parent().unwrap();
    let temporaries: Vec<_> = std::fs::read_dir(folder)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with(".tvf-"))
        .collect();
    assert!(temporaries.is_empty(), "{temporaries:?}");
}

#[test]
fn a_fifo_output_streams_to_its_reader_and_stays_a_fifo() {
    let dir = tempfile::tempdir().unwrap();
    let (constraints, cache) = inputs(dir.path());
    let fifo = dir.path().join("field.npy");
    let status = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(status.success());
    let (sender, received) = std::sync::mpsc::channel();
    {
        let fifo = fifo.clone();
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let read = std::fs::File::open(&fifo).and_then(|mut f| f.read_to_end(&mut bytes));
            let _ = sender.send(read.map(|_| bytes));
        });
    }
    let output = spline_into(&fifo, &constraints, &cache);
    // The path must still be the FIFO (a rename over it would leave the reader waiting).
    let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
    if !output.status.success() && kind.is_fifo() {
        // Let the reader see the end, then report.
        let _ = std::fs::OpenOptions::new().write(true).open(&fifo);
    }
    assert_success(&output);
    assert!(kind.is_fifo(), "{kind:?}");
    let bytes = received
        .recv_timeout(Duration::from_secs(60))
        .expect("the reader got the end of the stream")
        .unwrap();
    assert!(
        bytes.starts_with(b"\x93NUMPY"),
        "{:?}",
        &bytes[..bytes.len().min(16)]
    );
    // icosphere(3): 1280 faces of three f64 after the header.
    assert!(bytes.len() > 1280 * 3 * 8, "{} bytes", bytes.len());
}
