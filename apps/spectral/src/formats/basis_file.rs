//! Basis files (`.tvfb`): a [`SpectralBasis`] saved for reuse, tied to its mesh and
//! discretization.
//!
//! Layout (all integers and floats little-endian):
//!
//! | bytes | content |
//! |---|---|
//! | 8 | magic `TVFBASIS` |
//! | 4 | format version (`u32`, currently 1) |
//! | 4 | header length `H` in bytes, from the magic to the payload (`u32`) |
//! | 8 | mesh fingerprint ([`tvf_core::SurfaceMesh::fingerprint`]) |
//! | 8 × 6 | faces `F`, field dimension `n1` (`2F` for face fields, `E` for DEC 1-forms), fields `d`, harmonic, integrable, co-integrable counts |
//! | 4 + L | discretization id: `u32` length, UTF-8 text: the catalog id (e.g. `conforming-barycentric`) |
//! | 8 | [`Hash64`] of the header bytes before it |
//! | 8·d | eigenvalues (`f64`), ascending |
//! | d, zero-padded to a multiple of 8 | families (`0` harmonic, `1` integrable, `2` co-integrable) |
//! | 8·n1 | diagonal of `M1` |
//! | 8·n1·d | the fields, column by column (`n1` values each) |
//! | 8 | [`Hash64`] of the payload (everything between the header and this checksum) |
//!
//! The round trip is bit-exact. Saving is atomic; loading streams (no second copy in memory).

use crate::eigenfunction_basis::FIELD_CHUNK;
use crate::formats::atomic_write::write_atomically_with;
use crate::{EigenfunctionBasis, FieldFamily, SpectralBasis};
use faer::Mat;
use std::io::{Read, Write};
use std::ops::Range;
use std::path::{Path, PathBuf};
use thiserror::Error;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::Hash64;
use tvf_core::SurfaceMesh;

/// The magic bytes of a basis file.
pub const BASIS_FILE_MAGIC: &[u8; 8] = b"TVFBASIS";
/// The format version this build writes and the newest it reads.
pub const BASIS_FILE_VERSION: u32 = 1;

/// What a basis file must match to be used: the discretization and the mesh.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BasisFileKey {
    /// The catalog id of the discretization, [`HodgeComplex::id`] (names the mass lumping too).
    pub discretization: String,
    /// [`SurfaceMesh::fingerprint`](tvf_core::SurfaceMesh::fingerprint) of the mesh.
    pub mesh_fingerprint: u64,
    /// Faces of the mesh.
    pub face_count: usize,
    /// Field coefficients `n1` of the discretization on the mesh.
    pub field_dimension: usize,
}

impl BasisFileKey {
    /// The key of a basis computed for `complex` on `mesh`.
    pub fn new<H: HodgeComplex + ?Sized>(mesh: &SurfaceMesh, complex: &H) -> Self {
        Self {
            discretization: complex.id().to_string(),
            mesh_fingerprint: mesh.fingerprint(),
            face_count: mesh.face_count(),
            field_dimension: complex.field_dimension(),
        }
    }
}

/// The header of a basis file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BasisFileHeader {
    /// Format version of the file.
    pub version: u32,
    /// Mesh and discretization the basis belongs to.
    pub key: BasisFileKey,
    /// Number of basis fields `d`.
    pub field_count: usize,
    /// Harmonic fields among them.
    pub harmonic_count: usize,
    /// Integrable fields among them.
    pub integrable_count: usize,
    /// Co-integrable fields among them.
    pub cointegrable_count: usize,
}

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

fn family_code(family: FieldFamily) -> u8 {
    match family {
        FieldFamily::Harmonic => 0,
        FieldFamily::Integrable => 1,
        FieldFamily::Cointegrable => 2,
    }
}

/// Saves `basis` for the mesh and discretization of `key`, atomically.
pub fn save_basis(
    path: &Path,
    basis: &SpectralBasis,
    key: &BasisFileKey,
) -> Result<(), BasisFileError> {
    let fields = basis.fields();
    let contents = BasisContents {
        eigenvalues: basis.eigenvalues(),
        families: basis.families(),
        field_mass: basis.field_mass(),
        field_dimension: basis.field_dimension(),
    };
    write_basis(path, key, &contents, &|range| {
        range
            .map(|j| {
                let column = fields.col(j);
                (0..column.nrows()).map(|i| column[i]).collect()
            })
            .collect()
    })
}

/// Saves a basis in compact form (the eigenfunctions of `complex`) for the mesh and
/// discretization of `key`, atomically: the file holds the dense fields, formed a few at a time
/// in parallel while the file is written, so they are never all in memory. The file is the one
/// [`save_basis`] writes for the dense basis ([`EigenfunctionBasis::dense_fields`]).
pub fn save_eigenfunction_basis<H: HodgeComplex + ?Sized>(
    path: &Path,
    basis: &EigenfunctionBasis,
    complex: &H,
    key: &BasisFileKey,
) -> Result<(), BasisFileError> {
    let contents = BasisContents {
        eigenvalues: basis.eigenvalues(),
        families: basis.families(),
        field_mass: complex.m1().values(),
        field_dimension: complex.field_dimension(),
    };
    write_basis(path, key, &contents, &|range| {
        basis.field_columns(complex, range)
    })
}

/// Everything of a basis file but its fields.
struct BasisContents<'a> {
    eigenvalues: &'a [f64],
    families: &'a [FieldFamily],
    field_mass: &'a [f64],
    field_dimension: usize,
}

/// Writes a basis file whose fields `range` are `columns(range)` (each `field_dimension` values).
fn write_basis(
    path: &Path,
    key: &BasisFileKey,
    contents: &BasisContents<'_>,
    columns: &(dyn Fn(Range<usize>) -> Vec<Vec<f64>> + Sync),
) -> Result<(), BasisFileError> {
    let n = contents.field_dimension;
    let count = contents.eigenvalues.len();
    if n != key.field_dimension {
        return Err(BasisFileError::Invalid {
            path: path.to_path_buf(),
            reason: format!(
                "basis fields have {n} rows, the fields of '{}' on this mesh have {}",
                key.discretization, key.field_dimension
            ),
        });
    }
    let family_count = |family| contents.families.iter().filter(|&&f| f == family).count();
    let header = encode_header(&BasisFileHeader {
        version: BASIS_FILE_VERSION,
        key: key.clone(),
        field_count: count,
        harmonic_count: family_count(FieldFamily::Harmonic),
        integrable_count: family_count(FieldFamily::Integrable),
        cointegrable_count: family_count(FieldFamily::Cointegrable),
    });
    write_atomically_with(path, |w| {
        w.write_all(&header)?;
        let mut out = HashingWriter {
            inner: w,
            hash: Hash64::new(),
        };
        let mut buffer = Vec::with_capacity(8 * n.max(count) + 8);
        buffer.extend(contents.eigenvalues.iter().flat_map(|x| x.to_le_bytes()));
        out.write_all(&buffer)?;
        buffer.clear();
        buffer.extend(contents.families.iter().map(|&f| family_code(f)));
        buffer.resize(count.div_ceil(8) * 8, 0);
        out.write_all(&buffer)?;
        buffer.clear();
        buffer.extend(contents.field_mass.iter().flat_map(|x| x.to_le_bytes()));
        out.write_all(&buffer)?;
        // The next chunk of fields is formed on another thread while this one is written, so
        // forming (parallel) and writing (one thread) overlap; the channel holds no chunk of its
        // own, so at most two chunks exist at a time (2 GB at a million faces).
        std::thread::scope(|scope| {
            let (sender, receiver) = std::sync::mpsc::sync_channel::<Vec<Vec<f64>>>(0);
            scope.spawn(move || {
                for start in (0..count).step_by(FIELD_CHUNK) {
                    let chunk = columns(start..(start + FIELD_CHUNK).min(count));
                    // A closed channel means the writer failed and stopped.
                    if sender.send(chunk).is_err() {
                        break;
                    }
                }
            });
            for chunk in &receiver {
                for column in chunk {
                    if column.len() != n {
                        return Err(std::io::Error::other(format!(
                            "a field has {} values, not {n}",
                            column.len()
                        )));
                    }
                    buffer.clear();
                    buffer.extend(column.iter().flat_map(|x| x.to_le_bytes()));
                    out.write_all(&buffer)?;
                }
            }
            Ok(())
        })?;
        let checksum = out.hash.finish();
        w.write_all(&checksum.to_le_bytes())
    })
    .map_err(|source| BasisFileError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Loads a basis and checks that it belongs to `expected` (mesh and discretization).
pub fn load_basis(path: &Path, expected: &BasisFileKey) -> Result<SpectralBasis, BasisFileError> {
    read_basis(path, Some(expected)).map(|(_, basis)| basis)
}

/// Loads a basis without checking what it belongs to (integrity is still checked); returns its
/// header too.
pub fn read_basis_file(path: &Path) -> Result<(BasisFileHeader, SpectralBasis), BasisFileError> {
    read_basis(path, None)
}

/// Reads only the header of a basis file (checked against its checksum).
pub fn read_basis_header(path: &Path) -> Result<BasisFileHeader, BasisFileError> {
    let file = std::fs::File::open(path).map_err(io(path))?;
    let mut reader = std::io::BufReader::new(file);
    read_header(path, &mut reader).map(|(header, _)| header)
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> BasisFileError + '_ {
    move |source| BasisFileError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// The catalog id a stored discretization name stands for: files written before the catalog
/// store `decomposition (mass)`, e.g. `conforming (barycentric)` for `conforming-barycentric`.
fn catalog_id_of(stored: &str) -> String {
    match stored.strip_suffix(')').and_then(|s| s.split_once(" (")) {
        Some((decomposition, mass)) => format!("{decomposition}-{mass}"),
        None => stored.to_string(),
    }
}

fn encode_header(h: &BasisFileHeader) -> Vec<u8> {
    let name = h.key.discretization.as_bytes();
    let length = 8 + 4 + 4 + 8 + 6 * 8 + 4 + name.len() + 8;
    let mut out = Vec::with_capacity(length);
    out.extend_from_slice(BASIS_FILE_MAGIC);
    out.extend_from_slice(&h.version.to_le_bytes());
    out.extend_from_slice(&(length as u32).to_le_bytes());
    out.extend_from_slice(&h.key.mesh_fingerprint.to_le_bytes());
    for count in [
        h.key.face_count,
        h.key.field_dimension,
        h.field_count,
        h.harmonic_count,
        h.integrable_count,
        h.cointegrable_count,
    ] {
        out.extend_from_slice(&(count as u64).to_le_bytes());
    }
    out.extend_from_slice(&(name.len() as u32).to_le_bytes());
    out.extend_from_slice(name);
    let checksum = Hash64::of(&out);
    out.extend_from_slice(&checksum.to_le_bytes());
    out
}

/// Reads and checks the header; returns it with its length in bytes.
fn read_header(
    path: &Path,
    reader: &mut impl Read,
) -> Result<(BasisFileHeader, u64), BasisFileError> {
    let mut fixed = [0u8; 16];
    match reader.read_exact(&mut fixed) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => {
            return Err(BasisFileError::NotABasisFile {
                path: path.to_path_buf(),
            })
        }
        Err(e) => return Err(io(path)(e)),
    }
    if &fixed[..8] != BASIS_FILE_MAGIC {
        return Err(BasisFileError::NotABasisFile {
            path: path.to_path_buf(),
        });
    }
    let version = u32::from_le_bytes([fixed[8], fixed[9], fixed[10], fixed[11]]);
    if version > BASIS_FILE_VERSION {
        return Err(BasisFileError::NewerFormat {
            path: path.to_path_buf(),
            found: version,
            supported: BASIS_FILE_VERSION,
        });
    }
    let length = u32::from_le_bytes([fixed[12], fixed[13], fixed[14], fixed[15]]) as usize;
    let damaged = || BasisFileError::Checksum {
        path: path.to_path_buf(),
        part: "header",
    };
    if version == 0 || !(16 + 8 + 48 + 4 + 8..=1 << 20).contains(&length) {
        return Err(damaged());
    }
    let mut bytes = fixed.to_vec();
    bytes.resize(length, 0);
    reader.read_exact(&mut bytes[16..]).map_err(|e| {
        if e.kind() == std::io::ErrorKind::UnexpectedEof {
            BasisFileError::Truncated {
                path: path.to_path_buf(),
                expected: length as u64,
                found: 0,
            }
        } else {
            io(path)(e)
        }
    })?;
    let body = length - 8;
    let stored = u64::from_le_bytes(bytes[body..].try_into().map_err(|_| damaged())?);
    if Hash64::of(&bytes[..body]) != stored {
        return Err(damaged());
    }
    let u64_at = |at: usize| {
        let mut w = [0u8; 8];
        w.copy_from_slice(&bytes[at..at + 8]);
        u64::from_le_bytes(w)
    };
    let counts: Vec<usize> = (0..6).map(|i| u64_at(24 + 8 * i) as usize).collect();
    let name_length = u32::from_le_bytes([bytes[72], bytes[73], bytes[74], bytes[75]]) as usize;
    let invalid = |reason: String| BasisFileError::Invalid {
        path: path.to_path_buf(),
        reason,
    };
    if 76 + name_length != body {
        return Err(invalid(
            "header length does not match the discretization id".into(),
        ));
    }
    let discretization = catalog_id_of(
        &String::from_utf8(bytes[76..body].to_vec())
            .map_err(|_| invalid("discretization id is not UTF-8".into()))?,
    );
    let header = BasisFileHeader {
        version,
        key: BasisFileKey {
            discretization,
            mesh_fingerprint: u64_at(16),
            face_count: counts[0],
            field_dimension: counts[1],
        },
        field_count: counts[2],
        harmonic_count: counts[3],
        integrable_count: counts[4],
        cointegrable_count: counts[5],
    };
    if counts[3] + counts[4] + counts[5] != counts[2] {
        return Err(invalid(format!("inconsistent counts {counts:?}")));
    }
    Ok((header, length as u64))
}

fn read_basis(
    path: &Path,
    expected: Option<&BasisFileKey>,
) -> Result<(BasisFileHeader, SpectralBasis), BasisFileError> {
    let file = std::fs::File::open(path).map_err(io(path))?;
    let size = file.metadata().map_err(io(path))?.len();
    let mut reader = std::io::BufReader::with_capacity(1 << 20, file);
    let (header, header_length) = read_header(path, &mut reader)?;
    if let Some(key) = expected {
        if key.discretization != header.key.discretization {
            return Err(BasisFileError::WrongDiscretization {
                path: path.to_path_buf(),
                found: header.key.discretization,
                expected: key.discretization.clone(),
            });
        }
        if key.mesh_fingerprint != header.key.mesh_fingerprint
            || key.face_count != header.key.face_count
            || key.field_dimension != header.key.field_dimension
        {
            return Err(BasisFileError::WrongMesh {
                path: path.to_path_buf(),
                found: header.key.mesh_fingerprint,
                expected: key.mesh_fingerprint,
                found_faces: header.key.face_count,
                expected_faces: key.face_count,
            });
        }
    }
    let (n, d) = (header.key.field_dimension as u64, header.field_count as u64);
    let promised = (|| {
        let fields = n.checked_mul(d)?.checked_mul(8)?;
        header_length
            .checked_add(8 * d)?
            .checked_add(d.div_ceil(8) * 8)?
            .checked_add(8 * n)?
            .checked_add(fields)?
            .checked_add(8)
    })()
    .ok_or_else(|| BasisFileError::Invalid {
        path: path.to_path_buf(),
        reason: "sizes overflow".into(),
    })?;
    if size < promised {
        return Err(BasisFileError::Truncated {
            path: path.to_path_buf(),
            expected: promised,
            found: size,
        });
    }
    if size > promised {
        return Err(BasisFileError::Invalid {
            path: path.to_path_buf(),
            reason: format!("{} bytes of trailing data", size - promised),
        });
    }
    let (n, d) = (n as usize, d as usize);
    let mut input = HashingReader {
        inner: reader,
        hash: Hash64::new(),
    };
    let read_err = io(path);
    let eigenvalues = input.f64s(d).map_err(read_err)?;
    let mut codes = vec![0u8; d.div_ceil(8) * 8];
    input.read_exact(&mut codes).map_err(io(path))?;
    let field_mass = input.f64s(n).map_err(io(path))?;
    let mut fields = Mat::<f64>::zeros(n, d);
    let mut buffer = vec![0u8; 8 * n];
    for j in 0..d {
        input.read_exact(&mut buffer).map_err(io(path))?;
        let mut column = fields.col_mut(j);
        for (i, chunk) in buffer.chunks_exact(8).enumerate() {
            column[i] = f64::from_le_bytes(chunk.try_into().unwrap_or([0; 8]));
        }
    }
    let computed = input.hash.finish();
    let mut stored = [0u8; 8];
    input.inner.read_exact(&mut stored).map_err(io(path))?;
    if u64::from_le_bytes(stored) != computed {
        return Err(BasisFileError::Checksum {
            path: path.to_path_buf(),
            part: "payload",
        });
    }
    let invalid = |reason: String| BasisFileError::Invalid {
        path: path.to_path_buf(),
        reason,
    };
    let families = codes[..d]
        .iter()
        .map(|&c| match c {
            0 => Ok(FieldFamily::Harmonic),
            1 => Ok(FieldFamily::Integrable),
            2 => Ok(FieldFamily::Cointegrable),
            other => Err(invalid(format!("unknown family code {other}"))),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let basis = SpectralBasis::new(eigenvalues, families, fields, field_mass)
        .map_err(|e| invalid(e.to_string()))?;
    if basis.count(FieldFamily::Harmonic) != header.harmonic_count
        || basis.count(FieldFamily::Integrable) != header.integrable_count
    {
        return Err(invalid("family counts differ from the header".into()));
    }
    Ok((header, basis))
}

struct HashingWriter<'a> {
    inner: &'a mut dyn Write,
    hash: Hash64,
}

impl Write for HashingWriter<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let written = self.inner.write(buf)?;
        self.hash.update(&buf[..written]);
        Ok(written)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

struct HashingReader<R> {
    inner: R,
    hash: Hash64,
}

impl<R: Read> Read for HashingReader<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let read = self.inner.read(buf)?;
        self.hash.update(&buf[..read]);
        Ok(read)
    }
}

impl<R: Read> HashingReader<R> {
    fn f64s(&mut self, count: usize) -> std::io::Result<Vec<f64>> {
        let mut bytes = vec![0u8; 8 * count];
        self.read_exact(&mut bytes)?;
        Ok(bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_of_files_written_before_the_catalog_read_as_catalog_ids() {
        assert_eq!(
            catalog_id_of("conforming (barycentric)"),
            "conforming-barycentric"
        );
        assert_eq!(
            catalog_id_of("nonconforming (voronoi)"),
            "nonconforming-voronoi"
        );
        assert_eq!(catalog_id_of("dec-circumcentric"), "dec-circumcentric");
    }
}
