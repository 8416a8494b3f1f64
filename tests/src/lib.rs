//! # tvf-tests
//!
//! The conformance suite every discretization gets.
#![warn(missing_docs)]
