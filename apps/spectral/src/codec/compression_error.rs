//! [`CompressionError`]: everything that can go wrong compressing fields or reading a `.tvfc`.

use crate::basis::SpectralBasisError;
use crate::codec::symbol_coder::SymbolCodingError;
use thiserror::Error;

/// Why a field could not be compressed or a `.tvfc` file could not be decoded.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CompressionError {
    /// The file does not start with the `.tvfc` magic bytes.
    #[error("not a tvf compressed field file (.tvfc): wrong magic bytes")]
    NotTvfc,
    /// The file was written by a newer (or unknown) format version.
    #[error("unsupported .tvfc format version {found} (this build reads version {supported})")]
    UnsupportedVersion {
        /// Version in the file.
        found: u16,
        /// Version this build reads.
        supported: u16,
    },
    /// The file ends before its header, payload or checksum does.
    #[error("file is truncated: {needed} bytes needed, {actual} present")]
    Truncated {
        /// Bytes the header promises.
        needed: usize,
        /// Bytes present.
        actual: usize,
    },
    /// Bytes after the checksum.
    #[error("file has {extra} unexpected bytes after its checksum")]
    TrailingBytes {
        /// How many.
        extra: usize,
    },
    /// The CRC-32 over header and payload does not match: the file is damaged.
    #[error("file is damaged: checksum {computed:08x} does not match the stored {stored:08x}")]
    ChecksumMismatch {
        /// Stored checksum.
        stored: u32,
        /// Checksum of the bytes read.
        computed: u32,
    },
    /// A header field has an impossible value.
    #[error("invalid header: {0}")]
    InvalidHeader(String),
    /// The file was made for another mesh.
    #[error(
        "file was compressed on another mesh (mesh fingerprint {file:016x}, this mesh {mesh:016x})"
    )]
    MeshMismatch {
        /// Fingerprint in the file.
        file: u64,
        /// Fingerprint of the mesh given.
        mesh: u64,
    },
    /// The file holds fields of another size than the complex's (made with another
    /// discretization).
    #[error("the file holds fields of {file} coefficients, but the fields of {complex} on this mesh have {dimension} (compressed with another discretization?)")]
    FieldDimensionMismatch {
        /// Field dimension `n1` in the file.
        file: u64,
        /// Id of the complex given.
        complex: String,
        /// Its field dimension `n1`.
        dimension: usize,
    },
    /// The file was made with another basis.
    #[error("file was compressed with another basis (basis id {file:016x}, this basis {basis:016x}); decode with the basis it was made with")]
    BasisMismatch {
        /// Basis id in the file.
        file: u64,
        /// Id of the basis given.
        basis: u64,
    },
    /// Neither family of the basis has as many fields as pairs were requested.
    #[error("the basis has at most {available} {family} fields, {requested} pairs requested (compute a larger basis with a larger -k, or lower --pairs)")]
    NotEnoughFields {
        /// The larger family, `integrable` or `cointegrable`.
        family: &'static str,
        /// Fields of that family in the basis.
        available: usize,
        /// Fields requested.
        requested: usize,
    },
    /// A field or coefficient is NaN or infinite.
    #[error("{what} entry {index} is not finite")]
    NonFinite {
        /// What was checked.
        what: &'static str,
        /// Position.
        index: usize,
    },
    /// No frame to compress.
    #[error("no field to compress")]
    NoFrames,
    /// The quantised stream could not be coded or decoded.
    #[error(transparent)]
    Symbols(#[from] SymbolCodingError),
    /// A field does not fit the basis.
    #[error(transparent)]
    Basis(#[from] SpectralBasisError),
    /// Reading or writing a file failed.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The I/O error.
        message: String,
    },
    /// A problem with the named file.
    #[error("{path}: {source}")]
    InFile {
        /// The file.
        path: String,
        /// The problem.
        source: Box<CompressionError>,
    },
}
