//! # tvf-design
//!
//! Tangential vector field splines and soft-constrained design.
#![warn(missing_docs)]
