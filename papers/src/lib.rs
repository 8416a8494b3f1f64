//! # tvf-papers
//!
//! Reproductions of papers' tables and figures, one folder per paper (see `papers/README.md`).
#![warn(missing_docs)]
