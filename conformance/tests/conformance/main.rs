//! tvf-conformance's integration tests: the suite on every catalog entry (`catalog_suites`),
//! every triangle entry on the intrinsic Delaunay triangulation (`intrinsic_entries`),
//! cross-discretization facts, the convergence study, the corpora, mesh strategies, the property
//! runner, meshes with boundary, polygon meshes, and mutations the suite must catch.

mod catalog_suites;
mod conformance_reference;
mod corpus;
mod intrinsic_entries;
mod mutations;
mod open_meshes;
mod polygon_meshes;
mod properties;
