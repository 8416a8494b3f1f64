//! One module per subcommand.

pub mod info;
pub mod operators;
pub mod analyze;
pub mod compress;
pub mod decompress;
pub mod filter;
pub mod rate_distortion;
mod spectral_inputs;
pub mod spline;
pub mod design;
pub mod basis;
pub mod spectrum;
pub mod decompose;
pub mod coefficients;
pub mod render;
pub mod export;
pub mod demo;
pub mod edit;
