//! The file formats of tvf-spectral: `.npy` arrays, field files and frame sequences, basis
//! files (`.tvfb`) with the complex they belong to, compressed fields (`.tvfc`), and the
//! content id of a basis; complex folders (the five matrices of a complex as files, with
//! `info.json`); the sparse matrices and integer arrays other tools write. Every write is atomic; every error names the file.

pub(crate) mod basis_arrays;
pub(crate) mod basis_file;
pub(crate) mod basis_file_blocks;
pub(crate) mod basis_file_complex;
pub(crate) mod basis_file_error;
pub(crate) mod basis_file_header;
pub(crate) mod basis_file_mass;
pub(crate) mod basis_file_spectrum;
pub(crate) mod basis_id;
pub(crate) mod basis_outputs;
pub(crate) mod block_progress;
pub(crate) mod complex_folder;
pub(crate) mod complex_folder_info;
pub(crate) mod complex_folder_write;
pub(crate) mod compressed_file;
pub(crate) mod field_frames;
pub(crate) mod field_io;
pub(crate) mod folder_file;
pub(crate) mod folder_input;
pub(crate) mod hodge_parts_folder;
pub(crate) mod npy;
pub(crate) mod numpy_export;
pub(crate) mod observed_basis_file;
pub(crate) mod sparse_file_read;
pub(crate) mod sparse_npz_read;
pub(crate) mod stored_basis;
pub(crate) mod streamed_basis_file;
