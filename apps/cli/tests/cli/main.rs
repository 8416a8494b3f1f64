//! The command line end to end: one test binary running the `tvf` binary, one module per
//! subject (a subcommand, a convention shared by subcommands, a kind of input or output).
//! `common` holds the helpers every module uses.

mod bad_input;
mod basis;
mod basis_blocks_decoding;
mod basis_blocks_progress;
mod cache_safety;
mod check;
mod clear_errors;
mod cli_conventions;
mod coefficients;
mod common;
mod compare;
mod complex_folder;
mod convergence;
mod dec_every_command;
mod decompose;
mod demo;
mod edit_server;
mod example_positionals;
mod filter_analyze_compress;
mod flags_and_outputs;
mod info;
mod info_shared_meshes;
mod inputs_checked_first;
mod intrinsic_delaunay;
mod intrinsic_shared_meshes;
mod non_finite;
mod numpy_outputs;
mod open_meshes;
mod operators;
mod outputs;
mod polygon_meshes;
mod recorded_spectra;
mod recorded_spectra_shared_meshes;
mod render_export;
mod special_outputs;
mod spectrum;
mod spline_design;
