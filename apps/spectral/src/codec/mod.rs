//! The compression codec (Section 8.6 of the paper and beyond): keeping the lowest coefficient
//! pairs of a field, optionally quantised and range-coded, frames of a sequence, and
//! rate–distortion measurements of real compressed files.

pub(crate) mod compress;
pub(crate) mod compression_error;
pub(crate) mod compression_summary;
pub(crate) mod file_fit;
pub(crate) mod quantization;
pub mod range_coder;
pub(crate) mod rate_distortion;
pub(crate) mod rate_distortion_report;
pub(crate) mod sequence;
pub(crate) mod symbol_coder;
