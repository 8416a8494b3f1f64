//! [`BasisFileError`]: why a basis file (`.tvfb`, see `basis_file.rs`) could not be written or
//! used; every variant names the file.

use std::path::PathBuf;
use thiserror::Error;

/// Why a basis file could not be written or used (every variant names the file).
#[derive(Debug, Error)]
pub enum BasisFileError {
    /// The operating system refused.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The file does not start with `TVFBASIS`.
    #[error("{}: not a tvf basis file (.tvfb)", path.display())]
    NotABasisFile {
        /// The file.
        path: PathBuf,
    },
    /// Written by a newer tvf.
    #[error("{}: basis file format version {found} is newer than this tvf reads ({supported}); recompute the basis or update tvf", path.display())]
    NewerFormat {
        /// The file.
        path: PathBuf,
        /// Version in the file.
        found: u32,
        /// Newest version this build reads.
        supported: u32,
    },
    /// Computed with another discretization or mass lumping.
    #[error("{}: basis was computed for the {found} discretization, not {expected}", path.display())]
    WrongDiscretization {
        /// The file.
        path: PathBuf,
        /// Discretization in the file.
        found: String,
        /// Discretization asked for.
        expected: String,
    },
    /// Computed for the same discretization id and mesh, but from other matrices (the
    /// assembly changed since): the basis is not theirs.
    #[error("{}: the basis was computed from other matrices of '{discretization}' than this complex has ({} differ{}: matrix hash {found:016x} in the file, {expected:016x} of the complex); recompute the basis", path.display(), differing.join(", "), if differing.len() == 1 { "s" } else { "" })]
    WrongMatrices {
        /// The file.
        path: PathBuf,
        /// The complex id (the same in the file and the complex).
        discretization: String,
        /// Names of the parts whose hashes differ ([`tvf_core::discretization::MatrixHash::PART_NAMES`]).
        differing: Vec<&'static str>,
        /// [`tvf_core::discretization::MatrixHash::value`] in the file.
        found: u64,
        /// [`tvf_core::discretization::MatrixHash::value`] of the complex.
        expected: u64,
    },
    /// Computed for another mesh.
    #[error("{}: basis belongs to another mesh ({found_faces} faces, fingerprint {found:016x}; this mesh: {expected_faces} faces, fingerprint {expected:016x})", path.display())]
    WrongMesh {
        /// The file.
        path: PathBuf,
        /// Fingerprint in the file.
        found: u64,
        /// Fingerprint of the mesh given.
        expected: u64,
        /// Faces in the file.
        found_faces: usize,
        /// Faces of the mesh given.
        expected_faces: usize,
    },
    /// The file is shorter than its header says.
    #[error("{}: truncated basis file ({found} bytes, the header promises {expected})", path.display())]
    Truncated {
        /// The file.
        path: PathBuf,
        /// Bytes the header promises.
        expected: u64,
        /// Bytes present.
        found: u64,
    },
    /// The header or payload checksum does not match: the file is damaged.
    #[error("{}: damaged basis file ({part} checksum mismatch)", path.display())]
    Checksum {
        /// The file.
        path: PathBuf,
        /// "header" or "payload".
        part: &'static str,
    },
    /// Inconsistent content behind valid checksums (or a basis that cannot be saved).
    #[error("{}: invalid basis file: {reason}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is inconsistent.
        reason: String,
    },
}
