//! Generalized symmetric eigensolver for the lowest eigenpairs of `A x = λ M x`.

mod interval_slicing;
mod krylov_slice;
mod lowest;
mod mass_orthogonal;
mod rayleigh_ritz;
mod tall_products;
mod types;

pub use lowest::lowest_eigenpairs;
pub use types::{EigenOptions, EigenProgress, Eigenpairs};
