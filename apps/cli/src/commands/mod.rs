//! One module per subcommand; a large one has its parts beside it (`compare_*.rs`).

pub mod analyze;
pub mod basis;
pub mod check;
pub mod coefficients;
pub mod compare;
pub mod compare_corpus;
mod compare_entries;
mod compare_pictures;
mod compare_scheduler;
pub mod compress;
pub mod convergence;
pub mod decompose;
pub mod decompress;
pub mod demo;
pub mod design;
pub mod discretizations;
pub mod edit;
pub mod export;
pub mod filter;
pub mod info;
pub mod operators;
pub mod rate_distortion;
pub mod render;
mod spectral_inputs;
pub mod spectrum;
pub mod spline;
pub mod triangulate;
