//! # tvf-spectral
//!
//! The Fourier basis of tangent fields (Section 6 of the paper) and what is built on it:
//! coefficients, reconstruction, filters and compression.
#![warn(missing_docs)]

mod basis;

pub use basis::{FieldFamily, SpectralBasis, SpectralBasisError};
