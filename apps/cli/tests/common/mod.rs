//! Shared helpers of the CLI end-to-end tests: the `tvf` binary and the check that it succeeded.
#![allow(dead_code)]

use std::process::{Command, Output};

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
