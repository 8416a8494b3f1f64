//! Empty: cargo resolves a package's build-dependencies only when it has a build script, and
//! `Cargo.toml` names the features of host crates (proc macros' `syn`) there.
fn main() {}
