//! Helpers that tests of several tvf crates share: where the real meshes are
//! ([`shared_meshes`], [`shared_mesh`]: a missing folder skips a test with a note, and fails it
//! under `CI=true`), and the editor run as a process and spoken to over HTTP
//! ([`EditorProcess`], [`request`], [`status`]).
//!
//! A dev-dependency of the crates whose tests use it, and a dependency of `tvf-conformance`,
//! whose suite (test code shipped as a library) adds the real meshes to its corpus.
#![forbid(unsafe_code)]

mod editor_process;
mod shared_meshes;

pub use editor_process::{request, status, EditorProcess};
pub use shared_meshes::{shared_mesh, shared_meshes};
