//! Generalized symmetric eigensolver for the lowest eigenpairs of `A x = λ M x`.

mod interval_slicing;
mod krylov_slice;
mod lowest;
mod mass_orthogonal;
mod pencil;
mod rayleigh_ritz;
mod refinement;
mod statistics;
mod symmetric_products;
mod tall_kernels;
mod tall_products;
mod types;
mod workspace_pool;

pub use interval_slicing::{lowest_eigenpairs_of, EigenRequest, EigenSolution, RequestError};
pub use lowest::lowest_eigenpairs;
pub use pencil::{Pencil, ShiftCount};
pub use statistics::{process_cpu_seconds, Phase, PhaseStatistics, SolverStatistics};
pub use tall_products::keep_columns;
pub use types::{EigenOptions, EigenProgress, Eigenpairs};
