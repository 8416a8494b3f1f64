//! tvf-discretizations' integration tests: the spaces, DEC, Whitney–Galerkin, consistent masses,
//! the eigensolver on their Laplacians and entries on intrinsic Delaunay triangulations.

mod consistent_masses;
mod dec;
mod eigen_regression;
mod intrinsic;
mod spaces;
mod whitney_galerkin;
