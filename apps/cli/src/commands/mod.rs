//! One module per subcommand.

pub mod info;
pub mod operators;
pub mod analyze;
pub mod compress;
pub mod decompress;
pub mod filter;
pub mod rate_distortion;
mod spectral_inputs;
pub mod edit;
