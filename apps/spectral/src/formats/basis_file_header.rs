//! The header of a basis file (`.tvfb`): what the file belongs to, its counts and its layout,
//! encoded and decoded with its checksum. The full layout is documented in
//! [`crate::formats::basis_file`].

use super::basis_file::{BasisFileError, BASIS_FILE_MAGIC, BASIS_FILE_VERSION};
use std::io::Read;
use std::path::Path;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::{Hash64, SurfaceMesh};

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

/// What the payload of a basis file holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BasisFileLayout {
    /// The diagonal of `M1` and the `d` fields densely (`n1` values each).
    Fields,
    /// The eigenfunctions ([`crate::EigenfunctionBasis`]): the integrable fields' potentials
    /// (`n0` values each), the co-integrable fields' co-potentials (`n2` values each) and the
    /// harmonic fields (`n1` values each); the fields are formed through the complex's sparse
    /// gradients when the file is loaded.
    Eigenfunctions {
        /// Rows `n0` of a potential.
        potential_dimension: usize,
        /// Rows `n2` of a co-potential.
        co_potential_dimension: usize,
    },
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
    /// What the payload holds (always [`BasisFileLayout::Fields`] in version 1 files).
    pub layout: BasisFileLayout,
}

impl BasisFileHeader {
    /// Bytes of the payload and its checksum promised by this header (`None` if they overflow).
    pub(crate) fn payload_bytes(&self) -> Option<u64> {
        let d = self.field_count as u64;
        let n1 = self.key.field_dimension as u64;
        let values = match self.layout {
            BasisFileLayout::Fields => n1.checked_mul(d)?.checked_add(n1)?,
            BasisFileLayout::Eigenfunctions {
                potential_dimension,
                co_potential_dimension,
            } => (potential_dimension as u64)
                .checked_mul(self.integrable_count as u64)?
                .checked_add(
                    (co_potential_dimension as u64).checked_mul(self.cointegrable_count as u64)?,
                )?
                .checked_add(n1.checked_mul(self.harmonic_count as u64)?)?,
        };
        values
            .checked_add(d)?
            .checked_mul(8)?
            .checked_add(d.div_ceil(8) * 8)?
            .checked_add(8)
    }
}

/// Offset of the six counts (faces, `n1`, `d`, harmonic, integrable, co-integrable).
const COUNTS_AT: usize = 24;
/// Offset of the version-2 layout words (layout code, `n0`, `n2`).
const LAYOUT_AT: usize = COUNTS_AT + 6 * 8;

/// The bytes of `header`, in the current format version, ending with their checksum.
pub(crate) fn encode_header(header: &BasisFileHeader) -> Vec<u8> {
    let name = header.key.discretization.as_bytes();
    let length = LAYOUT_AT + 3 * 8 + 4 + name.len() + 8;
    let mut out = Vec::with_capacity(length);
    out.extend_from_slice(BASIS_FILE_MAGIC);
    out.extend_from_slice(&BASIS_FILE_VERSION.to_le_bytes());
    out.extend_from_slice(&(length as u32).to_le_bytes());
    out.extend_from_slice(&header.key.mesh_fingerprint.to_le_bytes());
    let (layout_code, n0, n2) = match header.layout {
        BasisFileLayout::Fields => (0, 0, 0),
        BasisFileLayout::Eigenfunctions {
            potential_dimension,
            co_potential_dimension,
        } => (1, potential_dimension, co_potential_dimension),
    };
    for word in [
        header.key.face_count,
        header.key.field_dimension,
        header.field_count,
        header.harmonic_count,
        header.integrable_count,
        header.cointegrable_count,
        layout_code,
        n0,
        n2,
    ] {
        out.extend_from_slice(&(word as u64).to_le_bytes());
    }
    out.extend_from_slice(&(name.len() as u32).to_le_bytes());
    out.extend_from_slice(name);
    let checksum = Hash64::of(&out);
    out.extend_from_slice(&checksum.to_le_bytes());
    out
}

/// Reads and checks the header (format versions 1 and 2); returns it with its length in bytes.
pub(crate) fn read_header(
    path: &Path,
    reader: &mut impl Read,
) -> Result<(BasisFileHeader, u64), BasisFileError> {
    let io = |source| BasisFileError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut fixed = [0u8; 16];
    match reader.read_exact(&mut fixed) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => {
            return Err(BasisFileError::NotABasisFile {
                path: path.to_path_buf(),
            })
        }
        Err(e) => return Err(io(e)),
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
    // Version 1 has no layout words: its name length follows the counts.
    let name_at = if version == 1 {
        LAYOUT_AT + 4
    } else {
        LAYOUT_AT + 3 * 8 + 4
    };
    let length = u32::from_le_bytes([fixed[12], fixed[13], fixed[14], fixed[15]]) as usize;
    let damaged = || BasisFileError::Checksum {
        path: path.to_path_buf(),
        part: "header",
    };
    if version == 0 || !(name_at + 8..=1 << 20).contains(&length) {
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
            io(e)
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
    let invalid = |reason: String| BasisFileError::Invalid {
        path: path.to_path_buf(),
        reason,
    };
    let word = |i: usize| {
        usize::try_from(u64_at(COUNTS_AT + 8 * i))
            .map_err(|_| invalid("a count does not fit this machine".into()))
    };
    let counts = (0..6).map(word).collect::<Result<Vec<_>, _>>()?;
    let layout = if version == 1 {
        BasisFileLayout::Fields
    } else {
        match u64_at(LAYOUT_AT) {
            0 => BasisFileLayout::Fields,
            1 => BasisFileLayout::Eigenfunctions {
                potential_dimension: word(7)?,
                co_potential_dimension: word(8)?,
            },
            other => return Err(invalid(format!("unknown layout code {other}"))),
        }
    };
    let name_length = u32::from_le_bytes(
        bytes[name_at - 4..name_at]
            .try_into()
            .map_err(|_| damaged())?,
    ) as usize;
    if name_at + name_length != body {
        return Err(invalid(
            "header length does not match the discretization id".into(),
        ));
    }
    let discretization = catalog_id_of(
        &String::from_utf8(bytes[name_at..body].to_vec())
            .map_err(|_| invalid("discretization id is not UTF-8".into()))?,
    );
    let consistent = counts[3]
        .checked_add(counts[4])
        .and_then(|sum| sum.checked_add(counts[5]))
        == Some(counts[2]);
    if !consistent {
        return Err(invalid(format!("inconsistent counts {counts:?}")));
    }
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
        layout,
    };
    Ok((header, length as u64))
}

/// The catalog id a stored discretization name stands for: files written before the catalog
/// store `decomposition (mass)`, e.g. `conforming (barycentric)` for `conforming-barycentric`.
fn catalog_id_of(stored: &str) -> String {
    match stored.strip_suffix(')').and_then(|s| s.split_once(" (")) {
        Some((decomposition, mass)) => format!("{decomposition}-{mass}"),
        None => stored.to_string(),
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
