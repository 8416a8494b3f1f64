//! Shared helpers of the CLI end-to-end tests: the `tvf` binary, the check that it succeeded,
//! and a test field file.

use std::path::Path;
use std::process::{Command, Output};
use tvf_core::TriangleMesh;

/// A command running the `tvf` binary built for these tests.
pub fn tvf() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tvf"))
}

/// Fails the test (at the caller's line) with the command's stderr unless it exited with 0.
#[track_caller]
pub fn assert_success(output: &Output) {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Writes a field with both families (a rotation about z plus a gradient-like part, one vector
/// per face, as text) to `path`.
pub fn write_field(mesh: &TriangleMesh, path: &Path) {
    let field: String = mesh
        .faces()
        .iter()
        .map(|f| {
            let c: [f64; 3] = std::array::from_fn(|k| {
                f.iter().map(|&v| mesh.positions()[v][k]).sum::<f64>() / 3.0
            });
            format!("{} {} {}\n", -c[1] + 0.3 * c[0], c[0] + 0.2, 0.1 * c[2])
        })
        .collect();
    std::fs::write(path, field).unwrap();
}
