//! No code: this crate's manifest names the features that `cargo test --workspace` turns on in
//! third-party crates, so that `tvf-cli` and `tvf-python`, which depend on it, resolve the same
//! ones when built alone (the README's first command, maturin's build of the wheel) and reuse
//! the builds in `target/` (see `Cargo.toml` and `scripts/check-features`).
#![forbid(unsafe_code)]
