//! Generalized symmetric eigensolver for the lowest eigenpairs of `A x = λ M x`, for three
//! kinds of pencils ([`Pencil`]): a diagonal mass, a sparse SPD mass, and the mixed pencils
//! `d1 W⁻¹ d1ᵀ ψ = μ N ψ` solved through a matrix on the edges or a saddle-point matrix.

mod file_backed_columns;
mod interval_slicing;
mod interval_stream;
mod krylov_slice;
mod lowest;
mod mass;
mod mass_orthogonal;
mod mixed_operator;
mod pencil;
mod rayleigh_ritz;
mod refinement;
mod shift_factor;
mod slice_memory;
mod sparse_mass_products;
mod sparse_summaries;
mod spectrum_bound;
mod statistics;
mod stiffness;
mod stored_mass;
mod symmetric_products;
mod tall_kernels;
mod tall_products;
#[cfg(target_os = "linux")]
mod temporary_file_mapping;
mod types;
mod workspace_pool;

pub use file_backed_columns::streamed_eigenvectors_in_memory;
pub use interval_slicing::{lowest_eigenpairs_of, EigenRequest, EigenSolution, RequestError};
pub use lowest::lowest_eigenpairs;
pub use mass::MassMatrix;
pub use pencil::{Pencil, ShiftCount};
pub use slice_memory::{default_slice_memory, parse_byte_count, set_default_slice_memory};
pub use statistics::{process_cpu_seconds, Phase, PhaseStatistics, SolverStatistics};
pub use tall_products::keep_columns;
pub use types::{EigenOptions, EigenProgress, Eigenpairs, EigenvectorSink, FinishedEigenvectors};
