//! # tvf-convergence
//!
//! How a discretization converges: catalog entries (or any builders of complexes) on refinement
//! sequences of surfaces whose spectrum is known in closed form — the unit sphere and the unit
//! hemisphere under both boundary conditions — with the relative error of the lowest
//! eigenvalues of each family per level, the observed orders and the time of each basis
//! ([`study`]), and the study as a Markdown table and a summary of orders ([`table`]).
//! `tvf convergence`, the Python package's `tvf.convergence` and papers/'s discretization
//! comparison run it; `tvf-figures` plots it.
#![forbid(unsafe_code)]

pub mod study;
pub mod table;
