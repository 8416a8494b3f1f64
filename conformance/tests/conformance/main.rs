//! tvf-conformance's integration tests: the suite on every catalog entry (`catalog_suites`),
//! cross-discretization facts, the convergence study, the corpora, mesh strategies, the property
//! runner, meshes with boundary, and mutations the suite must catch.

mod catalog_suites;
mod conformance_reference;
mod corpus;
mod mutations;
mod open_meshes;
mod properties;
