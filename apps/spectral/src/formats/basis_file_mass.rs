//! The field mass `M1` in a basis file (`.tvfb`): how the header describes it
//! ([`StoredFieldMass`]), how the fields layout writes it, and how it is read back and checked.
//! The full layout is documented in [`crate::formats::basis_file`].

use std::io::{Read, Write};
use tvf_core::discretization::sparse::as_csr;
use tvf_core::discretization::{Mass, MassForm, MassStorage};

/// Name of a field mass read from a basis file, in errors.
const READ_MASS: &str = "M1 (from the basis file)";

/// Words read or written at a time (64 KiB).
const WORD_CHUNK: usize = 8192;

/// How a basis file holds the field mass `M1`: three header words in format version 3 (storage
/// code, form code, stored entries; see [`StoredFieldMass::words`]). Files of versions 1 and 2
/// hold the diagonal in the fields layout and nothing in the eigenfunctions layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StoredFieldMass {
    /// Not in the file: the eigenfunctions layout takes `M1` from the complex.
    FromComplex,
    /// The diagonal of `M1`: `n1` values.
    Diagonal,
    /// A sparse symmetric `M1` (both triangles) in compressed sparse rows: `n1 + 1` row starts,
    /// `nnz` column indices (ascending in each row) and `nnz` values.
    Sparse {
        /// Stored entries.
        nnz: usize,
    },
}

impl StoredFieldMass {
    /// How the fields layout stores `mass`. Fails for a mass stored as its inverse: the field
    /// mass of a complex is always given directly (`ComplexParts::new`).
    pub(crate) fn of(mass: &Mass) -> Result<Self, String> {
        if mass.form() != MassForm::Direct {
            return Err(format!(
                "{} is stored as its inverse; a basis file holds a field mass given directly",
                mass.what()
            ));
        }
        Ok(match mass.storage() {
            MassStorage::Diagonal(_) => StoredFieldMass::Diagonal,
            MassStorage::Sparse(matrix) => StoredFieldMass::Sparse { nnz: matrix.nnz() },
        })
    }

    /// The three header words: the storage code (`0` from the complex, `1` diagonal, `2`
    /// sparse), the form code (`0`: the stored matrix is `M1` itself; `1`, `M1⁻¹`, is reserved
    /// and refused) and the stored entries `nnz` (`0` unless sparse).
    pub(crate) fn words(self) -> [u64; 3] {
        match self {
            StoredFieldMass::FromComplex => [0, 0, 0],
            StoredFieldMass::Diagonal => [1, 0, 0],
            StoredFieldMass::Sparse { nnz } => [2, 0, nnz as u64],
        }
    }

    /// The description in three header words (see [`StoredFieldMass::words`]).
    pub(crate) fn from_words(words: [u64; 3]) -> Result<Self, String> {
        let [storage, form, nnz] = words;
        if form != 0 {
            return Err(format!(
                "field mass form code {form}: this tvf reads a field mass stored as M1 itself \
                 (code 0)"
            ));
        }
        match (storage, nnz) {
            (0, 0) => Ok(StoredFieldMass::FromComplex),
            (1, 0) => Ok(StoredFieldMass::Diagonal),
            (2, nnz) => usize::try_from(nnz)
                .map(|nnz| StoredFieldMass::Sparse { nnz })
                .map_err(|_| "the field mass's entry count does not fit this machine".into()),
            (0 | 1, nnz) => Err(format!(
                "{nnz} sparse entries given for a field mass that is not sparse"
            )),
            (other, _) => Err(format!("unknown field mass storage code {other}")),
        }
    }

    /// 8-byte words the payload spends on the mass of `n1` field nodes (`None` on overflow).
    pub(crate) fn payload_words(self, n1: usize) -> Option<u64> {
        let n1 = n1 as u64;
        match self {
            StoredFieldMass::FromComplex => Some(0),
            StoredFieldMass::Diagonal => Some(n1),
            StoredFieldMass::Sparse { nnz } => {
                (nnz as u64).checked_mul(2)?.checked_add(n1.checked_add(1)?)
            }
        }
    }
}

/// Writes `mass` as the fields layout stores it ([`StoredFieldMass::of`]): the diagonal's `n1`
/// values, or the row starts and column indices (`u64`) and values (`f64`) of the stored sparse
/// matrix in compressed sparse rows, all little-endian.
pub(crate) fn write_field_mass(out: &mut impl Write, mass: &Mass) -> std::io::Result<()> {
    match mass.storage() {
        MassStorage::Diagonal(values) => write_words(out, values.iter().map(|m| m.to_bits())),
        MassStorage::Sparse(matrix) => {
            let matrix = as_csr(matrix);
            let indptr = matrix.indptr();
            write_words(out, indptr.raw_storage().iter().map(|&i| i as u64))?;
            write_words(out, matrix.indices().iter().map(|&j| j as u64))?;
            write_words(out, matrix.data().iter().map(|m| m.to_bits()))
        }
    }
}

fn write_words(out: &mut impl Write, words: impl Iterator<Item = u64>) -> std::io::Result<()> {
    let mut buffer = Vec::with_capacity(8 * WORD_CHUNK);
    for word in words {
        buffer.extend_from_slice(&word.to_le_bytes());
        if buffer.len() == 8 * WORD_CHUNK {
            out.write_all(&buffer)?;
            buffer.clear();
        }
    }
    out.write_all(&buffer)
}

/// The field mass of a basis read as fields: the arrays stored in the file, checked by
/// [`FieldMassRead::into_mass`] once the payload checksum has been verified, or the complex's
/// `M1` when an eigenfunctions file was turned into fields.
pub(crate) enum FieldMassRead {
    Diagonal(Vec<f64>),
    Sparse {
        indptr: Vec<u64>,
        indices: Vec<u64>,
        data: Vec<f64>,
    },
    Complex(Mass),
}

impl FieldMassRead {
    /// Reads the mass described by `stored` for `n1` field nodes (`None` for
    /// [`StoredFieldMass::FromComplex`]). The caller has checked that the file holds the
    /// [`StoredFieldMass::payload_words`], so nothing larger than the file is allocated.
    pub(crate) fn read(
        input: &mut impl Read,
        stored: StoredFieldMass,
        n1: usize,
    ) -> std::io::Result<Option<Self>> {
        Ok(match stored {
            StoredFieldMass::FromComplex => None,
            StoredFieldMass::Diagonal => {
                Some(FieldMassRead::Diagonal(floats(read_words(input, n1)?)))
            }
            StoredFieldMass::Sparse { nnz } => Some(FieldMassRead::Sparse {
                indptr: read_words(input, n1 + 1)?,
                indices: read_words(input, nnz)?,
                data: floats(read_words(input, nnz)?),
            }),
        })
    }

    /// The mass, checked: every value finite, a diagonal non-negative; a sparse matrix with
    /// row starts from `0` to `nnz`, column indices in range and strictly ascending in each
    /// row, and symmetric. A direct sparse mass is not factored (a basis only applies `M1`).
    /// The error says what is wrong.
    pub(crate) fn into_mass(self) -> Result<Mass, String> {
        let non_finite = |values: &[f64], what: &str| {
            values
                .iter()
                .position(|m| !m.is_finite())
                .map(|k| format!("{what} of M1 is not finite at {k}"))
        };
        match self {
            FieldMassRead::Diagonal(values) => {
                if let Some(problem) = non_finite(&values, "the diagonal") {
                    return Err(problem);
                }
                Mass::diagonal(READ_MASS, values).map_err(|e| e.to_string())
            }
            FieldMassRead::Sparse {
                indptr,
                indices,
                data,
            } => {
                if let Some(problem) = non_finite(&data, "stored entry") {
                    return Err(problem);
                }
                let n1 = indptr.len().saturating_sub(1);
                let ends = (indptr.first().copied(), indptr.last().copied());
                if ends != (Some(0), Some(data.len() as u64)) {
                    return Err(format!(
                        "the row starts of M1 run from {:?} to {:?}, not from 0 to {}",
                        ends.0,
                        ends.1,
                        data.len()
                    ));
                }
                let index = |i: u64| {
                    usize::try_from(i).map_err(|_| format!("index {i} of M1 is out of range"))
                };
                let indptr = indptr.into_iter().map(index).collect::<Result<_, _>>()?;
                let indices = indices.into_iter().map(index).collect::<Result<_, _>>()?;
                let matrix = sprs::CsMat::try_new((n1, n1), indptr, indices, data)
                    .map_err(|(.., e)| format!("the sparse structure of M1 is invalid: {e}"))?;
                Mass::sparse(READ_MASS, matrix).map_err(|e| e.to_string())
            }
            FieldMassRead::Complex(mass) => Ok(mass),
        }
    }
}

/// `count` little-endian `u64`s, read a chunk at a time.
fn read_words(input: &mut impl Read, count: usize) -> std::io::Result<Vec<u64>> {
    let mut words = Vec::with_capacity(count);
    let mut bytes = vec![0u8; 8 * WORD_CHUNK.min(count)];
    let mut left = count;
    while left > 0 {
        let take = WORD_CHUNK.min(left);
        let chunk = &mut bytes[..8 * take];
        input.read_exact(chunk)?;
        words.extend(
            chunk
                .chunks_exact(8)
                .map(|c| u64::from_le_bytes(c.try_into().unwrap_or([0; 8]))),
        );
        left -= take;
    }
    Ok(words)
}

fn floats(words: Vec<u64>) -> Vec<f64> {
    words.into_iter().map(f64::from_bits).collect()
}
