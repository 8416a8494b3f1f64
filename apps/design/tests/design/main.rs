//! tvf-design's tests (all of them: the crate has no unit tests): splines, soft design (full and
//! reduced), constraint files, design problems, the reports of solves, the default
//! regularization, and the design problems on complexes with non-diagonal masses. `common` holds
//! the shared inputs, `non_diagonal` the complexes with non-diagonal masses and their dense
//! references.

mod common;
mod constraint_file;
mod constraint_fuzz;
mod design_problem;
mod full_design_accuracy;
mod full_ordering;
mod full_parallelism;
mod non_diagonal;
mod non_diagonal_masses;
mod regularization;
mod reports;
mod soft_design;
mod spline;
