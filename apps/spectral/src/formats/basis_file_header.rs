//! The header of a basis file (`.tvfb`): what the file belongs to, its counts and its layout,
//! encoded and decoded with its checksum. The full layout is documented in
//! [`crate::formats::basis_file`].

use super::basis_file::{BasisFileError, BASIS_FILE_MAGIC, BASIS_FILE_VERSION};
use super::basis_file_mass::StoredFieldMass;
use std::io::Read;
use std::path::Path;
use tvf_core::discretization::{HodgeComplex, HodgeOperators, MatrixHash};
use tvf_core::mesh::Mesh;
use tvf_core::Hash64;

/// What a basis file must match to be used: the discretization, its matrices and the mesh.
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
    /// [`HodgeComplex::matrix_hash`] of the complex: its five matrices and fixed nodes. `None`
    /// in the header of a file of format version 1 or 2, which predates it.
    pub matrix_hash: Option<MatrixHash>,
}

impl BasisFileKey {
    /// The key of a basis computed for `complex` on `mesh`.
    pub fn new<M: Mesh + ?Sized, H: HodgeComplex + ?Sized>(mesh: &M, complex: &H) -> Self {
        Self {
            discretization: complex.id().to_string(),
            mesh_fingerprint: mesh.fingerprint(),
            face_count: mesh.face_count(),
            field_dimension: complex.field_dimension(),
            matrix_hash: Some(complex.matrix_hash()),
        }
    }

    /// Checks that the basis file `path`, whose header has the key `file`, belongs to this key:
    /// [`BasisFileError::WrongDiscretization`], [`BasisFileError::WrongMesh`] or, when both
    /// keys carry a matrix hash, [`BasisFileError::WrongMatrices`] otherwise.
    pub(crate) fn check_file(
        &self,
        path: &Path,
        file: &BasisFileKey,
    ) -> Result<(), BasisFileError> {
        if self.discretization != file.discretization {
            return Err(BasisFileError::WrongDiscretization {
                path: path.to_path_buf(),
                found: file.discretization.clone(),
                expected: self.discretization.clone(),
            });
        }
        if self.mesh_fingerprint != file.mesh_fingerprint
            || self.face_count != file.face_count
            || self.field_dimension != file.field_dimension
        {
            return Err(BasisFileError::WrongMesh {
                path: path.to_path_buf(),
                found: file.mesh_fingerprint,
                expected: self.mesh_fingerprint,
                found_faces: file.face_count,
                expected_faces: self.face_count,
            });
        }
        match (file.matrix_hash, self.matrix_hash) {
            (Some(found), Some(wanted)) if found != wanted => Err(BasisFileError::WrongMatrices {
                path: path.to_path_buf(),
                discretization: file.discretization.clone(),
                differing: wanted.differing_parts(&found),
                found: found.value(),
                expected: wanted.value(),
            }),
            _ => Ok(()),
        }
    }
}

/// What the payload of a basis file holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BasisFileLayout {
    /// `M1` (see [`StoredFieldMass`]) and the `d` fields densely (`n1` values each).
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
    /// How the payload holds `M1`: [`StoredFieldMass::FromComplex`] exactly in the
    /// eigenfunctions layout (and [`StoredFieldMass::Diagonal`] in the fields layout of
    /// versions 1 and 2).
    pub field_mass: StoredFieldMass,
}

impl BasisFileHeader {
    /// Bytes of the payload and its checksum promised by this header (`None` if they overflow).
    pub(crate) fn payload_bytes(&self) -> Option<u64> {
        let d = self.field_count as u64;
        let n1 = self.key.field_dimension as u64;
        let values = match self.layout {
            BasisFileLayout::Fields => n1
                .checked_mul(d)?
                .checked_add(self.field_mass.payload_words(self.key.field_dimension)?)?,
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
/// Offset of the layout words (layout code, `n0`, `n2`; version 2 on).
const LAYOUT_AT: usize = COUNTS_AT + 6 * 8;
/// Offset of the six matrix hash words (version 3 on).
const MATRIX_HASH_AT: usize = LAYOUT_AT + 3 * 8;
/// Offset of the three field mass words (version 3 on).
const FIELD_MASS_AT: usize = MATRIX_HASH_AT + 6 * 8;
/// Offset of the length of the discretization id, by format version.
fn name_length_at(version: u32) -> usize {
    match version {
        1 => LAYOUT_AT,
        2 => MATRIX_HASH_AT,
        _ => FIELD_MASS_AT + 3 * 8,
    }
}

/// The bytes of `header` with the matrix hash `matrix_hash`, in the current format version,
/// ending with their checksum.
pub(crate) fn encode_header(header: &BasisFileHeader, matrix_hash: &MatrixHash) -> Vec<u8> {
    let name = header.key.discretization.as_bytes();
    let length = name_length_at(BASIS_FILE_VERSION) + 4 + name.len() + 8;
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
    for word in matrix_hash
        .parts()
        .into_iter()
        .chain(header.field_mass.words())
    {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(&(name.len() as u32).to_le_bytes());
    out.extend_from_slice(name);
    let checksum = Hash64::of(&out);
    out.extend_from_slice(&checksum.to_le_bytes());
    out
}

/// Reads and checks the header (format versions 1 to 3); returns it with its length in bytes.
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
    let name_at = name_length_at(version) + 4;
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
    let (matrix_hash, field_mass) = if version < 3 {
        let field_mass = match layout {
            BasisFileLayout::Fields => StoredFieldMass::Diagonal,
            BasisFileLayout::Eigenfunctions { .. } => StoredFieldMass::FromComplex,
        };
        (None, field_mass)
    } else {
        let hash = std::array::from_fn(|i| u64_at(MATRIX_HASH_AT + 8 * i));
        let mass = std::array::from_fn(|i| u64_at(FIELD_MASS_AT + 8 * i));
        let field_mass = StoredFieldMass::from_words(mass).map_err(invalid)?;
        let from_complex = field_mass == StoredFieldMass::FromComplex;
        if from_complex != matches!(layout, BasisFileLayout::Eigenfunctions { .. }) {
            return Err(invalid(format!(
                "the field mass storage {field_mass:?} does not fit the layout {layout:?}"
            )));
        }
        (Some(MatrixHash::from_parts(hash)), field_mass)
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
            matrix_hash,
        },
        field_count: counts[2],
        harmonic_count: counts[3],
        integrable_count: counts[4],
        cointegrable_count: counts[5],
        layout,
        field_mass,
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
