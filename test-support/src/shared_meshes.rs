//! The real meshes of `../shared/meshes` (beside the repository): found, or a skip with a note
//! outside CI and a failure under `CI=true`.

use std::path::{Path, PathBuf};

/// The folder of the real meshes: `shared/meshes` in the folder that holds the repository
/// (`../shared/meshes` from the repository's root).
fn folder() -> PathBuf {
    let repository = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("test-support/ lies in the repository");
    repository
        .parent()
        .unwrap_or(repository)
        .join("shared/meshes")
}

/// Whether this run is CI's (`CI=true`), where the real meshes are always present.
fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true")
}

/// `Some(path)` if `path` exists; else a note on stderr (the caller skips what needs it), or,
/// under `CI=true`, a panic at the caller's line: CI has the meshes, and a test there must not
/// pass by skipping.
#[track_caller]
fn present(path: PathBuf) -> Option<PathBuf> {
    if path.exists() {
        return Some(path);
    }
    assert!(
        !in_ci(),
        "{} is missing, and CI=true: the tests that use the real meshes must run in CI",
        path.display()
    );
    eprintln!("skipping: {} not found", path.display());
    None
}

/// The folder of the real meshes (`../shared/meshes` from the repository's root), or `None`
/// with a note on stderr where it does not exist. Panics under `CI=true` if it is missing.
#[track_caller]
pub fn shared_meshes() -> Option<PathBuf> {
    present(folder())
}

/// The file `name` (e.g. `"bunny.obj"`) in [`shared_meshes`], or `None` with a note on stderr
/// where the folder or the file does not exist. Panics under `CI=true` if either is missing.
#[track_caller]
pub fn shared_mesh(name: &str) -> Option<PathBuf> {
    present(folder().join(name))
}
