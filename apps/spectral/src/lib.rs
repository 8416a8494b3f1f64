//! # tvf-spectral
//!
//! The Fourier basis of tangent fields (Section 6 of the paper) and what is built on it:
//! coefficients, reconstruction, analysis and filters (the files at the top level), the
//! compression codec (`codec/`) and the file formats (`formats/`: `.npy`, field files, basis
//! files, compressed files).
//!
//! ```
//! use tvf_core::generate::torus;
//! use tvf_discretizations::{Conforming, MassLumping};
//! use tvf_spectral::{compute_basis, BasisRequest, FieldFamily, FourierAnalysis};
//!
//! let mesh = torus(1.0, 0.4, 16, 8).unwrap(); // genus 1: two harmonic fields
//! let complex = Conforming::new(&mesh, MassLumping::Barycentric)?;
//! // 2g harmonic fields + 10 integrable + 10 co-integrable eigenfields, sorted by eigenvalue
//! let basis = compute_basis(&complex, &BasisRequest::pairs(10))?;
//! assert_eq!(basis.len(), 22);
//! assert_eq!(basis.families()[..2], [FieldFamily::Harmonic; 2]);
//! assert_eq!(basis.fields().nrows(), 2 * mesh.face_count()); // U: 2F × d, Uᵀ M_X U = I
//!
//! // Fourier coefficients of a basis field: 1 at its own index, 0 elsewhere.
//! let u5: Vec<f64> = (0..basis.field_dimension()).map(|i| basis.fields()[(i, 5)]).collect();
//! let analysis = FourierAnalysis::new(&basis, &u5)?;
//! assert!((analysis.coefficients[5] - 1.0).abs() < 1e-9);
//! assert!(analysis.relative_rest_norm < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

mod analysis;
mod analysis_report;
mod basis;
mod basis_cache_file;
mod basis_cache_folder;
mod basis_comparison;
mod basis_error;
mod basis_request;
mod basis_resolution;
mod basis_store;
mod basis_summary;
mod codec;
mod coefficient_report;
mod comparison_report;
mod compute_basis;
mod computed_field;
mod dense_memory;
mod eigenfunction_basis;
mod eigenfunction_sink;
pub mod eigenspace_angles;
mod family_split;
mod field_basis;
mod filter;
mod filter_response;
mod filter_spec;
mod filter_spec_error;
mod formats;
mod fourier;
mod harmonic_fields;
mod laplacian_apply;
mod resident_peak;
mod scalar_spectrum;
#[cfg(test)]
mod test_torus;

pub use analysis::{exact_hodge_energies, CoefficientEntry, EnergySplit, SpectralAnalysis};
pub use analysis_report::AnalysisReport;
pub use basis::{FieldFamily, SpectralBasis, SpectralBasisError};
pub use basis_cache_folder::{
    check_cache_folder, prepare_private_folder, user_cache_folder_from, BasisCache, FolderCheck,
};
pub use basis_comparison::{
    area_weights, relative_differences, BasisComparison, BasisComparisonError, ClusterComparison,
    SampledBasis,
};
pub use basis_error::BasisError;
pub use basis_request::{BasisProgress, BasisRequest, BasisSize, BasisStage};
pub use basis_resolution::{
    cache_messages, cached_or_computed_basis, computed_basis_summary, open_checked_basis_file,
    BasisFromFile, BasisMessage, CachedBasis,
};
pub use basis_store::{compute_basis_of_size, BasisStore, StoredBasisOrigin};
pub use basis_summary::{BasisSummary, FamilyCounts};
pub use codec::compress::{pair_selection, FieldCodec};
pub use codec::compression_error::CompressionError;
pub use codec::compression_summary::CompressionSummary;
pub use codec::quantization::UniformQuantizer;
pub use codec::range_coder;
pub use codec::rate_distortion::{
    equal_error_comparison, rate_distortion, rate_distortion_csv, FileStamp, RatePoint,
};
pub use codec::rate_distortion_report::RateDistortionReport;
pub use codec::sequence::{
    compress_with_progress, compress_with_report, decompress_with_progress, relative_l2_error,
    CompressionReport,
};
pub use codec::symbol_coder::{decode_symbols, encode_symbols, max_magnitude, SymbolCodingError};
pub use comparison_report::{ComparedEntry, ComparisonReport, EntryMeasurements};
pub use compute_basis::{compute_basis, compute_eigenfunction_basis, BasisReport};
pub use computed_field::{check_computed_field, NonFiniteField};
pub use eigenfunction_basis::EigenfunctionBasis;
pub use field_basis::FieldBasis;
pub use filter::{FilterError, FilteredField, SpectralFilter};
pub use filter_response::{FrequencyResponse, PiecewiseLinear};
pub use filter_spec::read_curve_file;
pub use filter_spec_error::FilterSpecError;
pub use formats::basis_arrays::write_basis_arrays;
pub use formats::basis_file::{
    load_basis, load_basis_from_file, read_basis_file, read_basis_header, read_basis_header_from,
    save_basis, save_eigenfunction_basis, BasisFileError, BasisFileHeader, BasisFileKey,
    BasisFileLayout, StoredFieldMass, BASIS_FILE_MAGIC, BASIS_FILE_VERSION,
};
pub use formats::basis_file_blocks::{BasisFileBlocks, BLOCK_BYTES};
pub use formats::basis_file_complex::{
    basis_file_complex, basis_file_complex_id, open_basis_file, open_basis_file_with,
    BasisFileUseError,
};
pub use formats::basis_file_spectrum::{read_basis_spectrum, BasisFileSpectrum};
pub use formats::basis_id::{basis_id, field_basis_id};
pub use formats::basis_outputs::{save_basis_outputs, BasisOutputError};
pub use formats::block_progress::{BlockObserver, BlockPass, BlockProgress};
pub use formats::complex_folder::{
    read_complex_folder, ComplexFolderError, COMPLEX_FOLDER_ID, MAX_INFO_BYTES,
};
pub use formats::complex_folder_info::{
    complex_folder_info, mass_file_name, sampling_of, MatrixFileFormat,
};
pub use formats::complex_folder_write::write_complex_folder;
pub use formats::compressed_file::{
    CoefficientCoding, CompressedFields, FramePayload, TvfcHeader, TVFC_HEADER_BYTES, TVFC_MAGIC,
    TVFC_VERSION,
};
pub use formats::field_frames::{
    read_field_file, read_field_frames, write_field_frames, FieldFrames, FieldFromFile,
    FrameSource, MAX_FIELD_COMPONENT, MIN_FIELD_COMPONENT,
};
pub use formats::field_io::{
    read_face_vector_sequence, read_face_vectors, read_npy, read_tangent_field,
    write_face_vector_sequence, write_face_vectors, write_face_vectors_as, write_npy,
    write_tangent_field, FieldFileFormat, FieldIoError,
};
pub use formats::folder_file::{
    write_folder_bytes, write_folder_file, FieldFolderError, FolderFileError,
};
pub use formats::hodge_parts_folder::write_hodge_parts;
pub use formats::npy::{NpyArray, NpyDtype, NpyError};
pub use formats::numpy_export::{npy_bytes, write_sparse_npz, NpyData};
pub use formats::observed_basis_file::ObservedBasisFile;
pub use formats::sparse_file_read::{
    read_matrix_market, read_matrix_market_within, MatrixLimits, MIN_ENTRY_LINE_BYTES,
};
pub use formats::sparse_npz_read::{
    read_index_npy, read_index_npy_within, read_sparse_npz, read_sparse_npz_within,
    InflationBudget, NPZ_INFLATED_LIMIT,
};
pub use formats::stored_basis::StoredBasis;
pub use formats::streamed_basis_file::{save_computed_basis, SavedBasis, SavedBasisError};
pub use fourier::{reconstruct_with_rest, FourierAnalysis};
pub use harmonic_fields::{harmonic_fields, HarmonicFields};
pub use laplacian_apply::{apply_hodge_laplacian, eigen_residual, field_norm};
pub use resident_peak::ResidentPeak;
/// The memory budget of the eigensolver's concurrent slices (the command line's
/// `TVF_SLICE_MEMORY`).
pub use tvf_solvers::{parse_byte_count, set_default_slice_memory};
/// The eigensolver's cost by phase, as [`BasisReport`] gives it.
pub use tvf_solvers::{process_cpu_seconds, PhaseStatistics, SolverStatistics};
