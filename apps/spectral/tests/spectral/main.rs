//! tvf-spectral's integration tests: the Fourier basis, its store, coefficients, filters,
//! analysis, compression and the file formats. `common` holds the shared meshes, complexes and
//! file helpers.

mod analysis;
mod basis_properties;
mod basis_real_meshes;
mod basis_sparse_field_mass;
mod basis_sphere_convergence;
mod basis_split;
mod basis_store;
mod common;
mod compress;
mod compress_entropy;
mod files_basis;
mod files_basis_blocks;
mod files_basis_blocks_decoding;
mod files_basis_blocks_progress;
mod files_basis_matrices;
mod files_basis_sparse_mass;
mod files_basis_streamed;
mod files_fields;
mod filter;
mod parser_fuzz;
mod sequence;
