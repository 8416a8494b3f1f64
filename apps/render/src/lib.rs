//! # tvf-render
//!
//! Software renderer and plots for meshes, fields and spectra.
#![warn(missing_docs)]
