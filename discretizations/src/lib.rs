//! # tvf-discretizations
//!
//! Function spaces, face fields and the conforming and nonconforming Hodge complexes.
#![warn(missing_docs)]
