//! [`read_basis_spectrum`]: what a basis file says about its basis without its fields being
//! read — the header (mesh, discretization, counts, layout), the eigenvalues and the family of
//! each field — for a program that shows a basis before choosing a mesh to use it on (Python's
//! `tvf.BasisFile`). The payload's checksum is not read here: using the basis on a mesh
//! ([`crate::BasisFileBlocks::open`], [`crate::load_basis`]) checks it.

use super::basis_file::{check_file_size, family_code};
use super::basis_file_header::read_header;
use crate::basis::check_eigenvalues;
use crate::{BasisFileError, BasisFileHeader, FieldFamily};
use std::fs::File;
use std::os::unix::fs::FileExt;
use std::path::Path;

/// The header, eigenvalues and families of a basis file.
#[derive(Debug, Clone)]
pub struct BasisFileSpectrum {
    /// The header: mesh and discretization key, counts per family, layout.
    pub header: BasisFileHeader,
    /// Eigenvalues of the `d` fields, ascending (units 1/length²).
    pub eigenvalues: Vec<f64>,
    /// Family of each field, `d` entries.
    pub families: Vec<FieldFamily>,
    /// Size of the file in bytes (the size its header promises).
    pub file_bytes: u64,
}

/// Reads the header of the basis file `path`, checks that the file has the size the header
/// promises, and reads its eigenvalues (finite, non-negative, ascending) and family codes
/// (counts as in the header); errors name the file.
pub fn read_basis_spectrum(path: &Path) -> Result<BasisFileSpectrum, BasisFileError> {
    let io = |source| BasisFileError::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = File::open(path).map_err(io)?;
    let file_bytes = file.metadata().map_err(io)?.len();
    let (header, header_length) = read_header(path, &mut std::io::BufReader::new(&file))?;
    check_file_size(path, &header, header_length, file_bytes)?;
    let (eigenvalues, families) = read_front(&file, path, &header, header_length)?;
    Ok(BasisFileSpectrum {
        header,
        eigenvalues,
        families,
        file_bytes,
    })
}

/// Bytes of the front of a basis file's payload for `d` fields: the eigenvalues (`8d`) and the
/// family codes (`d`, padded to whole words).
pub(super) fn front_bytes(d: usize) -> u64 {
    (8 * d + d.div_ceil(8) * 8) as u64
}

/// The eigenvalues (finite, non-negative, ascending) and families (counts as in `header`) at
/// the front of the payload of the basis file `path`, whose header is `header_length` bytes.
pub(super) fn read_front(
    file: &File,
    path: &Path,
    header: &BasisFileHeader,
    header_length: u64,
) -> Result<(Vec<f64>, Vec<FieldFamily>), BasisFileError> {
    let invalid = |reason: String| BasisFileError::Invalid {
        path: path.to_path_buf(),
        reason,
    };
    let d = header.field_count;
    let mut front = vec![0u8; front_bytes(d) as usize];
    file.read_exact_at(&mut front, header_length)
        .map_err(|source| BasisFileError::Io {
            path: path.to_path_buf(),
            source,
        })?;
    let eigenvalues: Vec<f64> = front[..8 * d]
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
        .collect();
    check_eigenvalues(&eigenvalues).map_err(|e| invalid(e.to_string()))?;
    let families = families_of(&front[8 * d..8 * d + d], header).map_err(invalid)?;
    Ok((eigenvalues, families))
}

/// The families of the family `codes` (`d` bytes), their counts the header's.
fn families_of(codes: &[u8], header: &BasisFileHeader) -> Result<Vec<FieldFamily>, String> {
    let families = codes
        .iter()
        .map(|&code| {
            [
                FieldFamily::Harmonic,
                FieldFamily::Integrable,
                FieldFamily::Cointegrable,
            ]
            .into_iter()
            .find(|&f| family_code(f) == code)
            .ok_or_else(|| format!("unknown family code {code}"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let count = |family| families.iter().filter(|&&f| f == family).count();
    if (
        count(FieldFamily::Integrable),
        count(FieldFamily::Cointegrable),
        count(FieldFamily::Harmonic),
    ) != (
        header.integrable_count,
        header.cointegrable_count,
        header.harmonic_count,
    ) {
        return Err("family counts differ from the header".into());
    }
    Ok(families)
}
