//! # tvf-spectral
//!
//! Fourier basis of tangent fields, coefficients, filters and compression.
#![warn(missing_docs)]
