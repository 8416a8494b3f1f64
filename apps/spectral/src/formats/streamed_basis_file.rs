//! [`save_computed_basis`]: a basis computed straight into its file (`.tvfb`, eigenfunctions
//! layout, see [`crate::formats::basis_file`]), each finished spectrum-slicing interval's
//! eigenfunctions written as the eigensolver hands them on, so that they are never all in
//! memory (on a 1M-face mesh with `-k 1000`, several GiB).
//!
//! The file is the one [`crate::compute_eigenfunction_basis`] and
//! [`crate::save_eigenfunction_basis`] write, byte for byte. Its header needs only the counts
//! of each family, which the inertia counts bound before anything is solved (where they count
//! a few pairs more than the basis keeps, the families' kept columns are moved down to their
//! places at the end, and the file cut: one more pass over it), so it is written first; the columns go to their places as they come (in no particular order); the
//! eigenvalues and families (known at the end) and the harmonic fields fill their places last,
//! and the payload's checksum is then taken by reading the payload back (the hash runs in file
//! order) and written at the end. Everything goes to a staged temporary file
//! ([`tvf_core::io::StagedFile`]) renamed over the target only once complete: an error or an
//! interruption leaves no file.
//!
//! Where the counts are not known up front (a basis cut by an eigenvalue bound), the
//! normalisation of the fields needs more than one column (a co-gradient with mass solves, a
//! non-diagonal `M1`), the eigenfunctions layout is not the smaller, or the target is not a
//! regular file, the basis is computed in memory and saved as before.

use crate::compute_basis::{kept_in_memory, solve_basis, SolvedBasis};
use crate::eigenfunction_sink::EigenfunctionSink;
use crate::formats::basis_file::{family_code, save_eigenfunction_basis, BasisFileError};
use crate::formats::basis_file_header::{
    encode_header, BasisFileHeader, BasisFileKey, BasisFileLayout, BASIS_FILE_VERSION,
};
use crate::formats::basis_file_mass::StoredFieldMass;
use crate::{BasisError, BasisReport, BasisRequest, FieldFamily};
use faer::MatRef;
use std::fs::File;
use std::os::unix::fs::FileExt;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Instant;
use thiserror::Error;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::io::StagedFile;
use tvf_core::Hash64;
use tvf_solvers::{process_cpu_seconds, PhaseStatistics};

/// A basis computed and saved by [`save_computed_basis`]: what is said of it.
#[derive(Debug, Clone)]
pub struct SavedBasis {
    /// Eigenvalues of the basis fields, ascending (`d` entries, units 1/length²).
    pub eigenvalues: Vec<f64>,
    /// Family of each basis field (`d` entries).
    pub families: Vec<FieldFamily>,
    /// How the computation went.
    pub report: BasisReport,
    /// Whether the eigenfunctions went to the file as they were computed (else the basis was
    /// computed in memory and saved, see the module documentation).
    pub streamed: bool,
    /// What finishing the file cost after the eigensolver (its front, the harmonic fields, the
    /// checksum pass; or the whole save where the basis was computed in memory).
    pub writing: PhaseStatistics,
}

/// Why [`save_computed_basis`] failed.
#[derive(Debug, Error)]
pub enum SavedBasisError {
    /// The basis could not be computed.
    #[error(transparent)]
    Compute(#[from] BasisError),
    /// The file could not be written.
    #[error(transparent)]
    File(#[from] BasisFileError),
}

/// Computes the basis of `request` for `complex` and writes it to `path` as its eigenfunctions
/// are found (see the module documentation); the file is the one
/// [`save_eigenfunction_basis`] writes of [`crate::compute_eigenfunction_basis`]'s basis, bit
/// for bit, and exists only once complete.
pub fn save_computed_basis<H: HodgeComplex + ?Sized>(
    path: &Path,
    complex: &H,
    request: &BasisRequest<'_>,
    key: &BasisFileKey,
) -> Result<SavedBasis, SavedBasisError> {
    let invalid = |reason: &str| BasisFileError::Invalid {
        path: path.to_path_buf(),
        reason: reason.to_string(),
    };
    if key.matrix_hash != Some(complex.matrix_hash()) {
        return Err(invalid("the key's matrix hash is not the complex's").into());
    }
    if key.field_dimension != complex.field_dimension() {
        return Err(invalid("the key's field dimension is not the complex's").into());
    }
    let start = Instant::now();
    // A device or a FIFO is written in place, streaming, by the usual save.
    if std::fs::metadata(path).is_ok_and(|m| !m.is_file()) {
        let solved = solve_basis(complex, request, None)?;
        return saved_in_memory(path, complex, key, solved, start);
    }
    let io = |source| BasisFileError::Io {
        path: path.to_path_buf(),
        source,
    };
    let staged = StagedFile::new(path).map_err(io)?;
    let file = File::options()
        .read(true)
        .write(true)
        .create_new(true)
        .open(staged.path())
        .map_err(io)?;
    let writer = StreamedBasisFile {
        file,
        path: path.to_path_buf(),
        key: key.clone(),
        dimensions: (
            complex.potential_dimension(),
            complex.co_potential_dimension(),
            complex.field_dimension(),
        ),
        layout: OnceLock::new(),
    };
    let solved = solve_basis(complex, request, Some(&writer))?;
    if !solved.streamed {
        drop(writer);
        drop(staged);
        return saved_in_memory(path, complex, key, solved, start);
    }
    let mut report = solved.report;
    report.seconds = start.elapsed().as_secs_f64();
    let (writing_start, writing_cpu) = (Instant::now(), process_cpu_seconds());
    let eigenvalues: Vec<f64> = solved.entries.iter().map(|e| e.0).collect();
    let families: Vec<FieldFamily> = solved.entries.iter().map(|e| e.1).collect();
    writer.finish(&eigenvalues, &families, solved.harmonic.as_ref())?;
    drop(writer);
    staged.commit().map_err(io)?;
    Ok(SavedBasis {
        eigenvalues,
        families,
        report,
        streamed: true,
        writing: PhaseStatistics {
            wall_seconds: writing_start.elapsed().as_secs_f64(),
            cpu_seconds: process_cpu_seconds() - writing_cpu,
            ..PhaseStatistics::default()
        },
    })
}

/// [`save_computed_basis`] of a basis whose eigenfunctions were kept in memory (computed from
/// `start`): normalised and saved as before streaming.
fn saved_in_memory<H: HodgeComplex + ?Sized>(
    path: &Path,
    complex: &H,
    key: &BasisFileKey,
    solved: SolvedBasis,
    start: Instant,
) -> Result<SavedBasis, SavedBasisError> {
    let (basis, mut report) = kept_in_memory(complex, solved);
    report.seconds = start.elapsed().as_secs_f64();
    let (writing_start, cpu) = (Instant::now(), process_cpu_seconds());
    save_eigenfunction_basis(path, &basis, complex, key)?;
    Ok(SavedBasis {
        eigenvalues: basis.eigenvalues().to_vec(),
        families: basis.families().to_vec(),
        report,
        streamed: false,
        writing: PhaseStatistics {
            wall_seconds: writing_start.elapsed().as_secs_f64(),
            cpu_seconds: process_cpu_seconds() - cpu,
            ..PhaseStatistics::default()
        },
    })
}

/// Where each part of the file goes, fixed by the family counts.
struct FileLayout {
    /// Bytes of the header (the payload starts here, with the eigenvalues).
    header_length: u64,
    /// Integrable, co-integrable and harmonic fields.
    counts: (usize, usize, usize),
    /// Offset of the first potential.
    body_start: u64,
}

/// A basis file being written column by column ([`EigenfunctionSink`]).
struct StreamedBasisFile {
    file: File,
    /// The target (for errors).
    path: PathBuf,
    key: BasisFileKey,
    /// `n0`, `n2`, `n1`.
    dimensions: (usize, usize, usize),
    layout: OnceLock<FileLayout>,
}

impl StreamedBasisFile {
    fn error(&self, source: std::io::Error) -> BasisFileError {
        BasisFileError::Io {
            path: self.path.clone(),
            source,
        }
    }

    /// The header and layout of a file with `counts` (integrable, co-integrable, harmonic)
    /// fields; `None` for a key without a matrix hash.
    fn layout_of(&self, counts: (usize, usize, usize)) -> Option<(Vec<u8>, FileLayout)> {
        let (n0, n2, _) = self.dimensions;
        let (na, nb, nh) = counts;
        let d = na + nb + nh;
        let header = encode_header(
            &BasisFileHeader {
                version: BASIS_FILE_VERSION,
                key: self.key.clone(),
                field_count: d,
                harmonic_count: nh,
                integrable_count: na,
                cointegrable_count: nb,
                layout: BasisFileLayout::Eigenfunctions {
                    potential_dimension: n0,
                    co_potential_dimension: n2,
                },
                field_mass: StoredFieldMass::FromComplex,
            },
            &self.key.matrix_hash?,
        );
        let header_length = header.len() as u64;
        let layout = FileLayout {
            header_length,
            counts,
            body_start: header_length + 8 * d as u64 + d.div_ceil(8) as u64 * 8,
        };
        Some((header, layout))
    }

    /// Moves the kept columns of a file written for `written` counts to their places in a file
    /// of `kept` counts (each family's first columns kept; everything moves towards the start,
    /// so copying forward in blocks never overwrites what is still to be read) and writes its
    /// header; returns its layout.
    fn relayout(
        &self,
        written: &FileLayout,
        kept: (usize, usize, usize),
    ) -> Result<FileLayout, BasisFileError> {
        let (na, nb, nh) = kept;
        let (wa, wb, wh) = written.counts;
        if na > wa || nb > wb || nh != wh {
            return Err(BasisFileError::Invalid {
                path: self.path.clone(),
                reason: format!(
                    "the basis kept {na} + {nb} + {nh} fields, more than the {wa} + {wb} + {wh} \
                     written"
                ),
            });
        }
        let (header, layout) = self
            .layout_of(kept)
            .ok_or_else(|| BasisFileError::Invalid {
                path: self.path.clone(),
                reason: "the key carries no matrix hash".into(),
            })?;
        let error = |e| self.error(e);
        let (n0, n2, _) = self.dimensions;
        let mut block = vec![0u8; CHECKSUM_BLOCK];
        for (family, count, rows) in [
            (FieldFamily::Integrable, na, n0),
            (FieldFamily::Cointegrable, nb, n2),
        ] {
            let (from, to) = (
                self.offset(written, family, 0),
                self.offset(&layout, family, 0),
            );
            let bytes = 8 * (count * rows) as u64;
            let mut done = 0;
            while done < bytes {
                let length = (bytes - done).min(CHECKSUM_BLOCK as u64) as usize;
                self.file
                    .read_exact_at(&mut block[..length], from + done)
                    .map_err(error)?;
                self.file
                    .write_all_at(&block[..length], to + done)
                    .map_err(error)?;
                done += length as u64;
            }
        }
        self.file.write_all_at(&header, 0).map_err(error)?;
        let end = self.offset(&layout, FieldFamily::Harmonic, nh);
        self.file.set_len(end + 8).map_err(error)?;
        Ok(layout)
    }

    /// Offset of column `index` of `family`.
    fn offset(&self, layout: &FileLayout, family: FieldFamily, index: usize) -> u64 {
        let (n0, n2, n1) = self.dimensions;
        let (na, nb, _) = layout.counts;
        let words = match family {
            FieldFamily::Integrable => index * n0,
            FieldFamily::Cointegrable => na * n0 + index * n2,
            FieldFamily::Harmonic => na * n0 + nb * n2 + index * n1,
        };
        layout.body_start + 8 * words as u64
    }

    /// Writes `values` as little-endian `f64`s at `offset`.
    fn write_values(&self, offset: u64, values: &[f64]) -> std::io::Result<()> {
        let bytes: Vec<u8> = values.iter().flat_map(|x| x.to_le_bytes()).collect();
        self.file.write_all_at(&bytes, offset)
    }

    /// Writes the eigenvalues, families and harmonic fields (`n1 × h`), then the checksum of
    /// the payload, read back in file order, and flushes the file to disk.
    fn finish(
        &self,
        eigenvalues: &[f64],
        families: &[FieldFamily],
        harmonic: MatRef<'_, f64>,
    ) -> Result<(), BasisFileError> {
        let Some(written) = self.layout.get() else {
            return Err(BasisFileError::Invalid {
                path: self.path.clone(),
                reason: "no column was written".into(),
            });
        };
        let count = |family| families.iter().filter(|&&f| f == family).count();
        let kept = (
            count(FieldFamily::Integrable),
            count(FieldFamily::Cointegrable),
            count(FieldFamily::Harmonic),
        );
        let moved;
        let layout = if kept == written.counts {
            written
        } else {
            moved = self.relayout(written, kept)?;
            &moved
        };
        let mut front: Vec<u8> = eigenvalues.iter().flat_map(|x| x.to_le_bytes()).collect();
        front.extend(families.iter().map(|&f| family_code(f)));
        front.resize(8 * eigenvalues.len() + families.len().div_ceil(8) * 8, 0);
        let error = |e| self.error(e);
        self.file
            .write_all_at(&front, layout.header_length)
            .map_err(error)?;
        for i in 0..harmonic.ncols() {
            let column: Vec<f64> = harmonic.col(i).iter().copied().collect();
            let offset = self.offset(layout, FieldFamily::Harmonic, i);
            self.write_values(offset, &column).map_err(error)?;
        }
        let end = self.offset(layout, FieldFamily::Harmonic, layout.counts.2);
        let mut hash = Hash64::new();
        hash.update(&front);
        let mut block = vec![0u8; CHECKSUM_BLOCK];
        let mut at = layout.body_start;
        while at < end {
            let length = (end - at).min(CHECKSUM_BLOCK as u64) as usize;
            self.file
                .read_exact_at(&mut block[..length], at)
                .map_err(error)?;
            hash.update(&block[..length]);
            at += length as u64;
        }
        self.file
            .write_all_at(&hash.finish().to_le_bytes(), end)
            .map_err(error)?;
        self.file.sync_all().map_err(error)
    }
}

/// Bytes read at a time for the checksum.
const CHECKSUM_BLOCK: usize = 8 << 20;

impl EigenfunctionSink for StreamedBasisFile {
    fn begin(&self, counts: (usize, usize, usize)) -> Result<bool, String> {
        let (n0, n2, n1) = self.dimensions;
        let (na, nb, nh) = counts;
        let d = na + nb + nh;
        // The layout `save_eigenfunction_basis` chooses for this basis (a sparse co-gradient).
        if n0 * na + n2 * nb + n1 * nh >= n1 * d {
            return Ok(false);
        }
        let Some((header, layout)) = self.layout_of(counts) else {
            return Ok(false);
        };
        self.file
            .write_all_at(&header, 0)
            .map_err(|e| self.error(e).to_string())?;
        self.layout
            .set(layout)
            .map_err(|_| "the file's layout was set twice".to_string())?;
        Ok(true)
    }

    fn column(&self, family: FieldFamily, index: usize, values: &[f64]) -> Result<(), String> {
        let layout = self
            .layout
            .get()
            .ok_or_else(|| "a column came before the file's layout".to_string())?;
        self.write_values(self.offset(layout, family, index), values)
            .map_err(|e| self.error(e).to_string())
    }
}
