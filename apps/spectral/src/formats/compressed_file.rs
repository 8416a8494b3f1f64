//! The `.tvfc` file: one or more fields compressed in a spectral basis.
//!
//! Layout (little endian):
//!
//! | offset | size | content |
//! |---|---|---|
//! | 0 | 8 | magic `TVFC\r\n\x1a\n` |
//! | 8 | 2 | format version (1) |
//! | 10 | 1 | coding: 0 = `f64` coefficients, 1 = quantised + range-coded |
//! | 11 | 1 | bits per quantised symbol (0 for `f64`) |
//! | 12 | 8 | mesh fingerprint |
//! | 20 | 8 | basis id ([`basis_id`](crate::formats::basis_id)) |
//! | 28 | 8 | field dimension `n1` (`2F` for face fields, `E` for 1-forms) |
//! | 36 | 4 | pairs `k` (lowest `k` integrable and `k` co-integrable fields) |
//! | 40 | 4 | coefficients per frame `n` (the kept fields, [`pair_selection`](crate::pair_selection)) |
//! | 44 | 4 | frame count `T` |
//! | 48 | 8 | total file length in bytes (tells truncation from other damage) |
//! | 56 | … | `T` frames: `f64` mode `n` doubles; quantised mode the step (`f64`), the coded length (`u32`) and the range-coded symbols |
//! | end − 4 | 4 | CRC-32 of every byte before it |

use crate::codec::compression_error::CompressionError;
use std::io::Write as _;
use std::path::Path;
use tvf_core::io::read_exactly_at_most;

/// Largest `.tvfc` file read (4 GiB: 500 million 64-bit coefficients).
pub const MAX_TVFC_BYTES: u64 = 1 << 32;
/// The magic bytes at the start of every `.tvfc` file.
pub const TVFC_MAGIC: [u8; 8] = *b"TVFC\r\n\x1a\n";
/// The format version this build writes and reads.
pub const TVFC_VERSION: u16 = 1;
/// Bytes before the first frame.
pub const TVFC_HEADER_BYTES: usize = 56;

/// How coefficients are stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoefficientCoding {
    /// 64-bit floats, bit-exact (the paper's rate: 64 bits per coefficient).
    Float64,
    /// Uniform scalar quantisation to `bits`-bit symbols, then adaptive range coding.
    Quantized {
        /// Symbol size, 2 to 32.
        bits: u32,
    },
}

impl CoefficientCoding {
    /// Label for plots and tables: "64-bit coefficients" or "B-bit quantised, range-coded".
    pub fn label(self) -> String {
        match self {
            CoefficientCoding::Float64 => "64-bit coefficients".to_string(),
            CoefficientCoding::Quantized { bits } => format!("{bits}-bit quantised, range-coded"),
        }
    }
}

/// Everything before the frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TvfcHeader {
    /// Fingerprint of the mesh the fields live on.
    pub mesh_fingerprint: u64,
    /// [`basis_id`](crate::formats::basis_id) of the basis the coefficients refer to.
    pub basis_id: u64,
    /// `n1`, the complex's field dimension.
    pub field_dimension: u64,
    /// Number of (integrable, co-integrable) pairs kept.
    pub pairs: u32,
    /// Number of basis fields kept (coefficients per frame).
    pub coefficients: u32,
    /// Coefficient storage.
    pub coding: CoefficientCoding,
}

impl TvfcHeader {
    /// Coefficients per frame.
    pub fn coefficient_count(&self) -> usize {
        self.coefficients as usize
    }
}

/// The stored coefficients of one field, in ascending basis order of the kept fields.
#[derive(Debug, Clone, PartialEq)]
pub enum FramePayload {
    /// Exact coefficients.
    Float64(Vec<f64>),
    /// Quantisation step and range-coded symbols.
    Quantized {
        /// Step of the uniform quantiser.
        step: f64,
        /// The coded symbols.
        bytes: Vec<u8>,
    },
}

/// A whole `.tvfc` file in memory.
#[derive(Debug, Clone, PartialEq)]
pub struct CompressedFields {
    /// The header.
    pub header: TvfcHeader,
    /// One payload per field (frame).
    pub frames: Vec<FramePayload>,
}

impl CompressedFields {
    /// The file's bytes (header, frames, checksum).
    pub fn to_bytes(&self) -> Vec<u8> {
        let h = &self.header;
        let mut out = Vec::with_capacity(TVFC_HEADER_BYTES + 4);
        out.extend_from_slice(&TVFC_MAGIC);
        out.extend_from_slice(&TVFC_VERSION.to_le_bytes());
        let (coding, bits) = match h.coding {
            CoefficientCoding::Float64 => (0u8, 0u8),
            CoefficientCoding::Quantized { bits } => (1u8, bits as u8),
        };
        out.push(coding);
        out.push(bits);
        out.extend_from_slice(&h.mesh_fingerprint.to_le_bytes());
        out.extend_from_slice(&h.basis_id.to_le_bytes());
        out.extend_from_slice(&h.field_dimension.to_le_bytes());
        out.extend_from_slice(&h.pairs.to_le_bytes());
        out.extend_from_slice(&h.coefficients.to_le_bytes());
        out.extend_from_slice(&(self.frames.len() as u32).to_le_bytes());
        let total = TVFC_HEADER_BYTES + self.frames.iter().map(frame_bytes).sum::<usize>() + 4;
        out.extend_from_slice(&(total as u64).to_le_bytes());
        for frame in &self.frames {
            match frame {
                FramePayload::Float64(values) => values
                    .iter()
                    .for_each(|v| out.extend_from_slice(&v.to_le_bytes())),
                FramePayload::Quantized { step, bytes } => {
                    out.extend_from_slice(&step.to_le_bytes());
                    out.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
                    out.extend_from_slice(bytes);
                }
            }
        }
        let checksum = crc32fast::hash(&out);
        out.extend_from_slice(&checksum.to_le_bytes());
        out
    }

    /// Parses a file's bytes: magic, version, length, checksum, then the header's consistency.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, CompressionError> {
        if bytes.len() < TVFC_MAGIC.len() || bytes[..8] != TVFC_MAGIC {
            return Err(CompressionError::NotTvfc);
        }
        let mut reader = Reader { bytes, position: 8 };
        let version = u16::from_le_bytes(reader.take()?);
        if version != TVFC_VERSION {
            return Err(CompressionError::UnsupportedVersion {
                found: version,
                supported: TVFC_VERSION,
            });
        }
        if bytes.len() < TVFC_HEADER_BYTES + 4 {
            return Err(CompressionError::Truncated {
                needed: TVFC_HEADER_BYTES + 4,
                actual: bytes.len(),
            });
        }
        let total = u64::from_le_bytes(bytes[48..56].try_into().unwrap_or([0; 8]));
        if (bytes.len() as u64) < total {
            return Err(CompressionError::Truncated {
                needed: usize::try_from(total).unwrap_or(usize::MAX),
                actual: bytes.len(),
            });
        }
        if bytes.len() as u64 > total {
            return Err(CompressionError::TrailingBytes {
                extra: (bytes.len() as u64 - total) as usize,
            });
        }
        // The checksum covers everything; check it before trusting any count in the header.
        let body = &bytes[..bytes.len() - 4];
        let stored = u32::from_le_bytes(bytes[bytes.len() - 4..].try_into().unwrap_or([0; 4]));
        let computed = crc32fast::hash(body);
        if stored != computed {
            return Err(CompressionError::ChecksumMismatch { stored, computed });
        }
        let mut reader = Reader {
            bytes: body,
            position: 10,
        };
        let [coding, bits] = reader.take::<2>()?;
        let coding = match coding {
            0 if bits == 0 => CoefficientCoding::Float64,
            1 if (2..=32).contains(&bits) => CoefficientCoding::Quantized { bits: bits.into() },
            _ => {
                return Err(CompressionError::InvalidHeader(format!(
                    "unknown coefficient coding {coding} with {bits} bits"
                )))
            }
        };
        let header = TvfcHeader {
            mesh_fingerprint: u64::from_le_bytes(reader.take()?),
            basis_id: u64::from_le_bytes(reader.take()?),
            field_dimension: u64::from_le_bytes(reader.take()?),
            pairs: u32::from_le_bytes(reader.take()?),
            coefficients: u32::from_le_bytes(reader.take()?),
            coding,
        };
        let frame_count = u32::from_le_bytes(reader.take()?) as usize;
        reader.position = TVFC_HEADER_BYTES;
        let n = header.coefficient_count();
        let mut frames = Vec::new();
        for _ in 0..frame_count {
            let frame = match coding {
                CoefficientCoding::Float64 => {
                    let raw = reader.slice(8 * n)?;
                    FramePayload::Float64(
                        raw.chunks_exact(8)
                            .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
                            .collect(),
                    )
                }
                CoefficientCoding::Quantized { .. } => {
                    let step = f64::from_le_bytes(reader.take()?);
                    if !step.is_finite() || step <= 0.0 {
                        return Err(CompressionError::InvalidHeader(format!(
                            "quantisation step {step} is not a positive number"
                        )));
                    }
                    let length = u32::from_le_bytes(reader.take()?) as usize;
                    FramePayload::Quantized {
                        step,
                        bytes: reader.slice(length)?.to_vec(),
                    }
                }
            };
            frames.push(frame);
        }
        if reader.position != body.len() {
            return Err(CompressionError::InvalidHeader(format!(
                "{frame_count} frames end at byte {} of a {}-byte payload",
                reader.position,
                body.len()
            )));
        }
        Ok(Self { header, frames })
    }

    /// Reads and parses a `.tvfc` file; errors name the file.
    pub fn read(path: &Path) -> Result<Self, CompressionError> {
        let in_file = |source: CompressionError| CompressionError::InFile {
            path: path.display().to_string(),
            source: Box::new(source),
        };
        let io = |e: std::io::Error| CompressionError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        };
        // The magic first: anything else (a stream of zeros) is refused before it is read.
        let mut file = std::fs::File::open(path).map_err(io)?;
        let mut bytes = Vec::new();
        read_exactly_at_most(&mut file, TVFC_MAGIC.len() as u64, &mut bytes).map_err(io)?;
        if bytes[..] == TVFC_MAGIC {
            read_exactly_at_most(&mut file, MAX_TVFC_BYTES, &mut bytes).map_err(io)?;
            if bytes.len() as u64 > MAX_TVFC_BYTES {
                return Err(io(std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    format!("larger than {MAX_TVFC_BYTES} bytes, more than a .tvfc file can need"),
                )));
            }
        }
        Self::from_bytes(&bytes).map_err(in_file)
    }

    /// Writes the file atomically (a temporary file beside `path`, then a rename).
    /// Returns the number of bytes written.
    pub fn write_atomic(&self, path: &Path) -> Result<usize, CompressionError> {
        let bytes = self.to_bytes();
        tvf_core::io::write_atomically(path, |w| w.write_all(&bytes)).map_err(|e| {
            CompressionError::Io {
                path: path.display().to_string(),
                message: e.to_string(),
            }
        })?;
        Ok(bytes.len())
    }
}

/// Bytes one frame takes in the file.
fn frame_bytes(frame: &FramePayload) -> usize {
    match frame {
        FramePayload::Float64(values) => 8 * values.len(),
        FramePayload::Quantized { bytes, .. } => 8 + 4 + bytes.len(),
    }
}

/// Sequential reads with truncation errors.
struct Reader<'a> {
    bytes: &'a [u8],
    position: usize,
}

impl<'a> Reader<'a> {
    fn slice(&mut self, length: usize) -> Result<&'a [u8], CompressionError> {
        let end = self
            .position
            .checked_add(length)
            .filter(|&e| e <= self.bytes.len());
        let end = end.ok_or(CompressionError::Truncated {
            needed: self.position.saturating_add(length).saturating_add(4),
            actual: self.bytes.len() + 4,
        })?;
        let out = &self.bytes[self.position..end];
        self.position = end;
        Ok(out)
    }

    fn take<const N: usize>(&mut self) -> Result<[u8; N], CompressionError> {
        let slice = self.slice(N)?;
        let mut out = [0u8; N];
        out.copy_from_slice(slice);
        Ok(out)
    }
}
