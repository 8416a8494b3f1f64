//! tvf-discretizations' integration tests: the spaces, DEC, Whitney–Galerkin, consistent masses
//! and the eigensolver on their Laplacians.

mod consistent_masses;
mod dec;
mod eigen_regression;
mod spaces;
mod whitney_galerkin;
