//! tvf-design's integration tests: splines, soft design (full and reduced), constraint files,
//! and the design problems on complexes with non-diagonal masses. `common` holds the shared
//! inputs, `non_diagonal` the complexes with non-diagonal masses and their dense references.

mod common;
mod constraint_file;
mod constraint_fuzz;
mod full_design_accuracy;
mod full_ordering;
mod full_parallelism;
mod non_diagonal;
mod non_diagonal_masses;
mod soft_design;
mod spline;
