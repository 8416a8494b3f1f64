//! [`BasisFileBlocks`]: a basis file in the eigenfunctions layout used where it lies, a block of
//! stored columns at a time, so that a basis larger than memory can project and synthesise
//! fields (`tvf filter`, `tvf coefficients`, `tvf compress`), give the rows of `U` a spline's or
//! soft design's constraints touch (`tvf spline`, `tvf design --reduced`) and every field once
//! for the basis id of compressed files (a row through a sparse operator reads only the stored
//! entries it touches, a few reads per column, not a pass over the file): only `n1`-vectors, the
//! `d` eigenvalues, the requested rows and one block of columns (at most [`BLOCK_BYTES`], with its formed fields) are ever in
//! memory, never the `n1 × d` fields [`crate::load_basis`] forms.
//!
//! The projection goes through the stored eigenfunctions and the complex's sparse operators, as
//! [`crate::EigenfunctionBasis`] computes it: with `Φ_i = d0 φ̃_i`, `Ψ_j = −M1⁻¹ d1ᵀ ψ̃_j`,
//!
//! ```text
//! α_i = φ̃_iᵀ (d0ᵀ M1 v),   β_j = ψ̃_jᵀ (−d1 v),   γ_k = Γ_kᵀ M1 v,
//! ```
//!
//! the dense basis's product in another summation order (equal to round-off; the tests bound
//! the difference). The synthesis `U c = Σ_i c_i U_i` forms the fields of a block of basis
//! indices from their stored columns and adds them in basis order, as the loaded basis does:
//! summing the potentials first and taking one gradient (`d0 Σ α_i φ̃_i`) would be cheaper but
//! loses digits to cancellation (on the 1000-field basis of `bunny-closed.obj`, a spline's
//! field differed from the loaded basis's by 3.6·10⁻¹² relative, its constraint residuals grew
//! from 2·10⁻¹⁵ to 2·10⁻¹³). Where the co-gradient is a sparse matrix (a diagonal `M1`), the
//! fields are formed as [`crate::load_basis`] forms them, bit for bit: the synthesis, the
//! fields [`FieldBasis::visit_fields`] hands out (so the basis id is the loaded basis's) and
//! the rows of [`FieldBasis::rows`] are the loaded basis's bit for bit. With a non-diagonal
//! `M1`, the loaded basis forms its co-integrable fields by one mass solve with every
//! co-potential as right-hand side, and a solve of another block of columns differs from it in
//! round-off: the fields are the loaded basis's bit for bit only where the co-potentials fit
//! one block ([`BasisFileBlocks::forms_fields_as_loaded`]), and the co-integrable rows are
//! `ψ̃_jᵀ (−d1 M1⁻¹ e_r)`, one mass solve per row, equal to round-off. Opening checks
//! everything [`crate::load_basis`] checks before
//! anything is computed: the key (mesh, discretization, matrices), the size the header promises,
//! the payload checksum (read through once, in blocks) and that every stored value is finite.
//! Each product then checks that the file's size and modification time are still those it was
//! checked with, and every value it reads for being finite (a file changed in place since is
//! refused, naming it, where that shows).
//!
//! An optional [`BlockObserver`] ([`BasisFileBlocks::with_observer`],
//! [`BasisFileBlocks::open_with_observer`] for the check at opening, or per product through an
//! [`crate::ObservedBasisFile`]) is told, on the calling thread, the start of every pass over
//! the file and each block of it ([`crate::BlockProgress`]); it changes nothing computed.

use super::basis_file::check_file_size;
use super::basis_file_header::read_header;
use super::basis_file_spectrum::{front_bytes, read_front};
use super::block_progress::{BlockObserver, BlockPass, PassProgress};
use crate::basis::check_length;
use crate::eigenfunction_basis::field_of_stored_into;
use crate::field_basis::check_rows;
use crate::{
    BasisFileError, BasisFileHeader, BasisFileKey, BasisFileLayout, FieldBasis, FieldFamily,
    SpectralBasisError,
};
use faer::MatRef;
use rayon::prelude::*;
use sprs::CsMat;
use std::fs::File;
use std::os::unix::fs::FileExt;
use std::path::{Path, PathBuf};
use tvf_core::discretization::sparse::{mul_transpose_vec, mul_vec};
use tvf_core::discretization::{HodgeOperators, Mass};
use tvf_core::Hash64;
use tvf_discretizations::BoxedComplex;

/// Largest block of stored columns read at a time (64 MiB: one potential of a million-face
/// mesh is 4 MiB, so sixteen at a time; the products are bound by reading, not by arithmetic).
pub const BLOCK_BYTES: usize = 64 << 20;

/// A basis file in the eigenfunctions layout, checked and read in blocks (see the module
/// documentation), with the complex it belongs to.
pub struct BasisFileBlocks {
    file: File,
    path: PathBuf,
    complex: BoxedComplex,
    eigenvalues: Vec<f64>,
    families: Vec<FieldFamily>,
    /// Position of each basis field among the stored columns of its family.
    slots: Vec<usize>,
    /// Per family (integrable, co-integrable, harmonic): offset of its first stored column,
    /// rows of a column, stored columns.
    sections: [Section; 3],
    /// Largest block read at a time ([`BLOCK_BYTES`] unless changed).
    block_bytes: usize,
    /// Size and modification time of the file when it was checked.
    checked: (u64, Option<std::time::SystemTime>),
    /// Told the progress of every pass over the file, if set.
    observer: Option<BlockObserver>,
}

/// The stored columns of one family.
#[derive(Clone, Copy)]
struct Section {
    offset: u64,
    rows: usize,
    count: usize,
}

impl BasisFileBlocks {
    /// Opens the basis file `path` for `complex` (which must be the complex `expected` was made
    /// from): `Ok(None)` for a file in the fields layout (load it whole with
    /// [`crate::load_basis`]); errors name the file.
    pub fn open(
        path: &Path,
        expected: &BasisFileKey,
        complex: BoxedComplex,
    ) -> Result<Option<Self>, BasisFileError> {
        Self::open_with_observer(path, expected, complex, None)
    }

    /// [`Self::open`], telling `observer` the progress of the check (the payload read through
    /// once: [`BlockPass::Checking`]) and then of every pass of the blocks opened
    /// ([`Self::with_observer`]).
    pub fn open_with_observer(
        path: &Path,
        expected: &BasisFileKey,
        complex: BoxedComplex,
        observer: Option<BlockObserver>,
    ) -> Result<Option<Self>, BasisFileError> {
        let io = |source| BasisFileError::Io {
            path: path.to_path_buf(),
            source,
        };
        let file = File::open(path).map_err(io)?;
        let metadata = file.metadata().map_err(io)?;
        let size = metadata.len();
        let (header, header_length) = read_header(path, &mut std::io::BufReader::new(&file))?;
        expected.check_file(path, &header.key)?;
        check_file_size(path, &header, header_length, size)?;
        let BasisFileLayout::Eigenfunctions {
            potential_dimension,
            co_potential_dimension,
        } = header.layout
        else {
            return Ok(None);
        };
        let invalid = |reason: String| BasisFileError::Invalid {
            path: path.to_path_buf(),
            reason,
        };
        if (potential_dimension, co_potential_dimension)
            != (
                complex.potential_dimension(),
                complex.co_potential_dimension(),
            )
        {
            return Err(invalid(format!(
                "the file holds potentials of {potential_dimension} and co-potentials of \
                 {co_potential_dimension} values, the complex's have {} and {}",
                complex.potential_dimension(),
                complex.co_potential_dimension()
            )));
        }
        let d = header.field_count;
        let payload_end = size - 8;
        let mut checking = PassProgress::start(
            observer.as_ref(),
            BlockPass::Checking,
            payload_end.saturating_sub(header_length),
        );
        check_payload(&file, path, header_length, d, payload_end, &mut checking)?;
        let (eigenvalues, families) = read_front(&file, path, &header, header_length)?;
        let body_start = header_length + front_bytes(d);
        let sections = sections_of(
            &header,
            body_start,
            potential_dimension,
            co_potential_dimension,
        );
        let mut seen = [0usize; 3];
        let slots = families
            .iter()
            .map(|&family| {
                let slot = seen[section_index(family)];
                seen[section_index(family)] += 1;
                slot
            })
            .collect();
        Ok(Some(Self {
            file,
            path: path.to_path_buf(),
            complex,
            eigenvalues,
            families,
            slots,
            sections,
            block_bytes: BLOCK_BYTES,
            checked: (size, metadata.modified().ok()),
            observer,
        }))
    }

    /// The same basis read in blocks of at most `bytes` (at least one column at a time). The
    /// results do not depend on it bit for bit where `M1` is diagonal; with a non-diagonal `M1`
    /// the co-integrable fields come from mass solves of other blocks of columns, equal to
    /// round-off (the tests bound the difference by `1e-13` relative).
    pub fn with_block_bytes(mut self, bytes: usize) -> Self {
        self.block_bytes = bytes;
        self
    }

    /// The same basis telling `observer` (`None`: nobody) the progress of every pass over the
    /// file, on the calling thread: its start and each block ([`crate::BlockProgress`]). The
    /// results do not depend on it.
    pub fn with_observer(mut self, observer: Option<BlockObserver>) -> Self {
        self.observer = observer;
        self
    }

    /// The complex the basis belongs to.
    pub fn complex(&self) -> &BoxedComplex {
        &self.complex
    }

    /// The complex the basis belongs to, the file closed.
    pub fn into_complex(self) -> BoxedComplex {
        self.complex
    }

    /// Whether [`FieldBasis::visit_fields`] forms every field as [`crate::load_basis`] does, bit
    /// for bit (so that [`crate::field_basis_id`] is the loaded basis's id): always with a
    /// diagonal `M1`; with a non-diagonal one only where the co-potentials fit one block (see
    /// the module documentation).
    pub fn forms_fields_as_loaded(&self) -> bool {
        let co_potentials = self.sections[section_index(FieldFamily::Cointegrable)];
        self.complex.co_gradient().is_sparse()
            || co_potentials.count <= 1
            || 8 * co_potentials.rows * co_potentials.count <= self.block_bytes
    }

    /// `Xᵀ x` for the stored columns `X` of `section` (`rows` each) and `x` (`rows` values),
    /// read a block at a time.
    fn transpose_times(
        &self,
        section: Section,
        x: &[f64],
        pass: &mut PassProgress,
    ) -> Result<Vec<f64>, SpectralBasisError> {
        let mut products = Vec::with_capacity(section.count);
        self.for_each_block(section, pass, |block| {
            products.par_extend(
                block
                    .par_chunks_exact(section.rows)
                    .map(|column| column.iter().zip(x).map(|(a, b)| a * b).sum::<f64>()),
            );
        })?;
        Ok(products)
    }

    /// Calls `visit` with the stored columns of `section` a block at a time, in order (each
    /// block `rows × columns` values, column by column), reporting each block to `pass` once
    /// visited.
    fn for_each_block(
        &self,
        section: Section,
        pass: &mut PassProgress,
        mut visit: impl FnMut(&[f64]),
    ) -> Result<(), SpectralBasisError> {
        if section.rows == 0 || section.count == 0 {
            return Ok(());
        }
        self.check_unchanged()?;
        let per_block = (self.block_bytes / (8 * section.rows)).clamp(1, section.count);
        let mut buffers = ReadBuffers::default();
        for first in (0..section.count).step_by(per_block) {
            let columns = per_block.min(section.count - first);
            visit(self.read_columns(section, first..first + columns, &mut buffers)?);
            pass.advance((8 * section.rows * columns) as u64);
        }
        Ok(())
    }

    /// An error reading the file, for `reason`.
    fn read_error(&self, reason: String) -> SpectralBasisError {
        SpectralBasisError::Read {
            path: self.path.clone(),
            reason,
        }
    }

    /// Checks that the file's size and modification time are those it was checked with.
    fn check_unchanged(&self) -> Result<(), SpectralBasisError> {
        let now = self
            .file
            .metadata()
            .map_err(|e| self.read_error(e.to_string()))?;
        if (now.len(), now.modified().ok()) != self.checked {
            return Err(self.read_error("the file changed since it was checked".into()));
        }
        Ok(())
    }

    /// The stored columns `columns` of `section` (`rows × columns.len()` values, column by
    /// column), read into `buffers`, each checked for being finite.
    fn read_columns<'b>(
        &self,
        section: Section,
        columns: std::ops::Range<usize>,
        buffers: &'b mut ReadBuffers,
    ) -> Result<&'b [f64], SpectralBasisError> {
        let count = 8 * section.rows * columns.len();
        let offset = section.offset + (8 * section.rows * columns.start) as u64;
        buffers.bytes.resize(count, 0);
        buffers.values.resize(count / 8, 0.0);
        let (bytes, values) = (
            &mut buffers.bytes[..count],
            &mut buffers.values[..count / 8],
        );
        self.file
            .read_exact_at(bytes, offset)
            .map_err(|e| self.read_error(e.to_string()))?;
        values
            .par_iter_mut()
            .zip(bytes.par_chunks_exact(8))
            .for_each(|(value, b)| *value = f64::from_le_bytes(b.try_into().unwrap_or([0; 8])));
        if values.par_iter().any(|v| !v.is_finite()) {
            return Err(self.read_error("a stored value is no longer finite".into()));
        }
        Ok(values)
    }

    /// `U c` (`n1` values) for every `c` of `sets`, each summed field by field in basis order,
    /// as the loaded basis sums it (`Σ_i c_i U[·, i]`, rows in chunks of [`ROW_CHUNK`], fields
    /// with `c_i = 0` skipped): the fields of a chunk of basis indices formed from their stored
    /// columns (at most a block of fields at a time), then added to every sum, so that the file
    /// is read once however many sets there are (and each sum is the one set's alone, bit for
    /// bit).
    fn combine_fields(
        &self,
        sets: &[&[f64]],
        observer: Option<&BlockObserver>,
    ) -> Result<Vec<Vec<f64>>, SpectralBasisError> {
        let n1 = self.field_dimension();
        let mut combined = vec![vec![0.0; n1]; sets.len()];
        if n1 == 0 || sets.is_empty() {
            return Ok(combined);
        }
        self.check_unchanged()?;
        let per_chunk = (self.block_bytes / (8 * n1)).clamp(1, self.len().max(1));
        let mut buffers: [ReadBuffers; 3] = Default::default();
        let mut fields = vec![0.0; n1 * per_chunk.min(self.len())];
        let mut pass = PassProgress::start(observer, BlockPass::Synthesising, self.stored_bytes());
        for first in (0..self.len()).step_by(per_chunk) {
            let chunk = first..(first + per_chunk).min(self.len());
            let chunk_bytes = chunk.clone().map(|i| self.stored_column_bytes(i)).sum();
            if sets
                .iter()
                .all(|c| c[chunk.clone()].iter().all(|&x| x == 0.0))
            {
                pass.advance(chunk_bytes);
                continue;
            }
            let fields = &mut fields[..n1 * chunk.len()];
            self.form_fields(chunk.clone(), &mut buffers, fields)?;
            for (c, combined) in sets.iter().zip(&mut combined) {
                let coefficients = &c[chunk.clone()];
                combined
                    .par_chunks_mut(ROW_CHUNK)
                    .enumerate()
                    .for_each(|(block, out)| {
                        let start = block * ROW_CHUNK;
                        for (field, &c) in fields.chunks_exact(n1).zip(coefficients) {
                            if c != 0.0 {
                                let column = &field[start..start + out.len()];
                                out.iter_mut().zip(column).for_each(|(o, x)| *o += c * x);
                            }
                        }
                    });
            }
            pass.advance(chunk_bytes);
        }
        Ok(combined)
    }

    /// Bytes of all the stored columns.
    fn stored_bytes(&self) -> u64 {
        self.sections
            .iter()
            .map(|s| (8 * s.rows * s.count) as u64)
            .sum()
    }

    /// Bytes of the stored column of basis field `i`.
    fn stored_column_bytes(&self, i: usize) -> u64 {
        (8 * self.sections[section_index(self.families[i])].rows) as u64
    }

    /// The fields of the basis indices `chunk` (`n1` values each, column by column) into
    /// `fields`, formed from their stored columns as [`FieldBasis::visit_fields`] forms them.
    fn form_fields(
        &self,
        chunk: std::ops::Range<usize>,
        buffers: &mut [ReadBuffers; 3],
        fields: &mut [f64],
    ) -> Result<(), SpectralBasisError> {
        let n1 = self.field_dimension();
        let (d0, co_gradient) = (self.complex.d0(), self.complex.co_gradient());
        for (k, family) in FAMILIES.into_iter().enumerate() {
            // The chunk's fields of this family are consecutive stored columns.
            let members: Vec<usize> = chunk
                .clone()
                .filter(|&i| self.families[i] == family)
                .collect();
            let (Some(&low), Some(&high)) = (members.first(), members.last()) else {
                continue;
            };
            let section = self.sections[k];
            let slots = self.slots[low]..self.slots[high] + 1;
            let stored = self.read_columns(section, slots, &mut buffers[k])?;
            let targets: Vec<usize> = members.iter().map(|&i| i - chunk.start).collect();
            if family == FieldFamily::Cointegrable && !co_gradient.is_sparse() {
                let stored = MatRef::from_column_major_slice(stored, section.rows, targets.len());
                let formed = co_gradient.apply_block(stored);
                for (j, &target) in targets.iter().enumerate() {
                    let field = &mut fields[target * n1..(target + 1) * n1];
                    field
                        .iter_mut()
                        .zip(formed.col(j).iter())
                        .for_each(|(f, x)| *f = *x);
                }
                continue;
            }
            let mut outputs: Vec<(usize, &mut [f64])> =
                fields.chunks_exact_mut(n1).enumerate().collect();
            outputs.retain(|(j, _)| targets.binary_search(j).is_ok());
            outputs
                .into_par_iter()
                .zip(stored.par_chunks_exact(section.rows))
                .for_each(|((_, field), stored)| {
                    field_of_stored_into(d0, co_gradient, family, stored, field)
                });
        }
        Ok(())
    }

    /// The values of `functionals` (none of them dense) on every stored column of `section`
    /// (one vector per column, a value per functional), reading only the stored entries they
    /// touch: nearby entries of a column in one read, so that a few rows cost a few reads per
    /// column instead of a pass over the file. The same arithmetic as on a whole column, bit for
    /// bit. The columns are taken a group at a time (a block's worth of columns, at least one
    /// per thread), each group reported to `pass`.
    fn sparse_row_values(
        &self,
        section: Section,
        functionals: &[RowFunctional],
        pass: &mut PassProgress,
    ) -> Result<Vec<Vec<f64>>, SpectralBasisError> {
        if section.rows == 0 || section.count == 0 {
            return Ok(Vec::new());
        }
        self.check_unchanged()?;
        let mut needed: Vec<usize> = functionals
            .iter()
            .flat_map(RowFunctional::entries)
            .collect();
        needed.sort_unstable();
        needed.dedup();
        let spans = entry_spans(&needed);
        let per_group = (self.block_bytes / (8 * section.rows))
            .max(rayon::current_num_threads())
            .clamp(1, section.count);
        let mut out = Vec::with_capacity(section.count);
        for first in (0..section.count).step_by(per_group) {
            let group = first..(first + per_group).min(section.count);
            let columns = group.len();
            let values: Vec<Vec<f64>> =
                self.sparse_group_values(section, functionals, &spans, &needed, group)?;
            out.extend(values);
            pass.advance((8 * section.rows * columns) as u64);
        }
        Ok(out)
    }

    /// [`Self::sparse_row_values`] of the stored columns `group` of `section`, the entries of
    /// each read in `spans` (the `needed` entries grouped).
    fn sparse_group_values(
        &self,
        section: Section,
        functionals: &[RowFunctional],
        spans: &[(usize, usize)],
        needed: &[usize],
        group: std::ops::Range<usize>,
    ) -> Result<Vec<Vec<f64>>, SpectralBasisError> {
        group
            .into_par_iter()
            .map(|column| {
                let start = section.offset + (8 * section.rows * column) as u64;
                let mut values = std::collections::HashMap::with_capacity(needed.len());
                let mut bytes = Vec::new();
                for &(low, high) in spans {
                    bytes.resize(8 * (high - low + 1), 0);
                    self.file
                        .read_exact_at(&mut bytes, start + 8 * low as u64)
                        .map_err(|e| self.read_error(e.to_string()))?;
                    for (j, b) in (low..=high).zip(bytes.chunks_exact(8)) {
                        let value = f64::from_le_bytes(b.try_into().unwrap_or([0; 8]));
                        if !value.is_finite() {
                            return Err(
                                self.read_error("a stored value is no longer finite".into())
                            );
                        }
                        values.insert(j, value);
                    }
                }
                Ok(functionals
                    .iter()
                    .map(|f| f.apply_with(|j| values[&j]))
                    .collect())
            })
            .collect()
    }

    /// Per family (in stored section order), the basis index of each stored column.
    fn basis_indices(&self) -> [Vec<usize>; 3] {
        let mut indices = self.sections.map(|s| vec![0; s.count]);
        for (i, (&family, &slot)) in self.families.iter().zip(&self.slots).enumerate() {
            indices[section_index(family)][slot] = i;
        }
        indices
    }

    /// Field coefficients `rows` of `family`'s fields as functionals of its stored columns.
    fn row_functionals(&self, family: FieldFamily, rows: &[usize]) -> Vec<RowFunctional> {
        let complex = &self.complex;
        match family {
            FieldFamily::Integrable => sparse_rows(complex.d0(), rows),
            FieldFamily::Cointegrable => match complex.co_gradient().as_sparse() {
                Some(matrix) => sparse_rows(matrix, rows),
                None => rows
                    .par_iter()
                    .map(|&r| {
                        let mut unit = vec![0.0; complex.field_dimension()];
                        unit[r] = 1.0;
                        RowFunctional::Dense(complex.co_gradient().apply_transpose(&unit))
                    })
                    .collect(),
            },
            FieldFamily::Harmonic => rows.iter().map(|&r| RowFunctional::Entry(r)).collect(),
        }
    }
}

/// The products of [`FieldBasis`], each telling `observer` the progress of its passes (the
/// trait's methods pass the blocks' own observer; [`crate::ObservedBasisFile`] another).
impl BasisFileBlocks {
    /// [`FieldBasis::coefficients`]: one [`BlockPass::Projecting`] pass over the stored columns.
    pub(crate) fn observed_coefficients(
        &self,
        field: &[f64],
        observer: Option<&BlockObserver>,
    ) -> Result<Vec<f64>, SpectralBasisError> {
        check_length("field", self.field_dimension(), field.len())?;
        let complex = &self.complex;
        let weighted = complex.m1().apply(field);
        let divergence = mul_transpose_vec(complex.d0(), &weighted);
        let curl: Vec<f64> = mul_vec(complex.d1(), field).iter().map(|x| -x).collect();
        let [integrable, cointegrable, harmonic] = self.sections;
        let mut pass = PassProgress::start(observer, BlockPass::Projecting, self.stored_bytes());
        let products = [
            self.transpose_times(integrable, &divergence, &mut pass)?,
            self.transpose_times(cointegrable, &curl, &mut pass)?,
            self.transpose_times(harmonic, &weighted, &mut pass)?,
        ];
        Ok((0..self.len())
            .map(|i| products[section_index(self.families[i])][self.slots[i]])
            .collect())
    }

    /// [`FieldBasis::reconstruct_many`]: one [`BlockPass::Synthesising`] pass.
    pub(crate) fn observed_reconstruct_many(
        &self,
        sets: &[&[f64]],
        observer: Option<&BlockObserver>,
    ) -> Result<Vec<Vec<f64>>, SpectralBasisError> {
        for coefficients in sets {
            check_length("coefficients", self.len(), coefficients.len())?;
        }
        self.combine_fields(sets, observer)
    }

    /// [`FieldBasis::rows`]: one [`BlockPass::Rows`] pass.
    pub(crate) fn observed_rows(
        &self,
        rows: &[usize],
        observer: Option<&BlockObserver>,
    ) -> Result<Vec<Vec<f64>>, SpectralBasisError> {
        check_rows(rows, self.field_dimension())?;
        let mut out = vec![vec![0.0; self.len()]; rows.len()];
        let indices = self.basis_indices();
        let mut pass = PassProgress::start(observer, BlockPass::Rows, self.stored_bytes());
        for (k, family) in FAMILIES.into_iter().enumerate() {
            let functionals = self.row_functionals(family, rows);
            let section = self.sections[k];
            let mut first = 0;
            let mut store = |values: Vec<Vec<f64>>| {
                for (j, column) in values.iter().enumerate() {
                    let i = indices[k][first + j];
                    for (row, &value) in out.iter_mut().zip(column) {
                        row[i] = value;
                    }
                }
                first += values.len();
            };
            if functionals
                .iter()
                .any(|f| matches!(f, RowFunctional::Dense(_)))
            {
                self.for_each_block(section, &mut pass, |block| {
                    store(
                        block
                            .par_chunks_exact(section.rows)
                            .map(|stored| functionals.iter().map(|f| f.apply(stored)).collect())
                            .collect(),
                    )
                })?;
            } else {
                store(self.sparse_row_values(section, &functionals, &mut pass)?);
            }
        }
        Ok(out)
    }

    /// [`FieldBasis::visit_fields`]: one [`BlockPass::Fields`] pass.
    pub(crate) fn observed_visit_fields(
        &self,
        visit: &(dyn Fn(usize, &[f64]) + Sync),
        observer: Option<&BlockObserver>,
    ) -> Result<(), SpectralBasisError> {
        let indices = self.basis_indices();
        let (d0, co_gradient) = (self.complex.d0(), self.complex.co_gradient());
        let n1 = self.field_dimension();
        let mut pass = PassProgress::start(observer, BlockPass::Fields, self.stored_bytes());
        for (k, family) in FAMILIES.into_iter().enumerate() {
            let section = self.sections[k];
            let mut first = 0;
            self.for_each_block(section, &mut pass, |block| {
                let columns = block.len() / section.rows;
                let targets = &indices[k][first..first + columns];
                if family == FieldFamily::Cointegrable && !co_gradient.is_sparse() {
                    // One block solve, as the loaded basis forms its co-exact fields.
                    let stored = MatRef::from_column_major_slice(block, section.rows, columns);
                    let fields = co_gradient.apply_block(stored);
                    targets.par_iter().enumerate().for_each(|(j, &i)| {
                        visit(i, &fields.col(j).iter().copied().collect::<Vec<f64>>())
                    });
                } else {
                    block
                        .par_chunks_exact(section.rows)
                        .zip(targets)
                        .for_each_init(
                            || vec![0.0; n1],
                            |field, (stored, &i)| {
                                field_of_stored_into(d0, co_gradient, family, stored, field);
                                visit(i, field);
                            },
                        );
                }
                first += columns;
            })?;
        }
        Ok(())
    }
}

impl FieldBasis for BasisFileBlocks {
    fn len(&self) -> usize {
        self.eigenvalues.len()
    }

    fn field_dimension(&self) -> usize {
        self.complex.field_dimension()
    }

    fn eigenvalues(&self) -> &[f64] {
        &self.eigenvalues
    }

    fn families(&self) -> &[FieldFamily] {
        &self.families
    }

    fn coefficients(&self, field: &[f64]) -> Result<Vec<f64>, SpectralBasisError> {
        self.observed_coefficients(field, self.observer.as_ref())
    }

    fn reconstruct(&self, coefficients: &[f64]) -> Result<Vec<f64>, SpectralBasisError> {
        Ok(self.reconstruct_many(&[coefficients])?.remove(0))
    }

    fn reconstruct_many(&self, sets: &[&[f64]]) -> Result<Vec<Vec<f64>>, SpectralBasisError> {
        self.observed_reconstruct_many(sets, self.observer.as_ref())
    }

    fn inner_product(&self, a: &[f64], b: &[f64]) -> f64 {
        let mass = self.complex.m1();
        match mass.diagonal_values() {
            Some(mass) => a.iter().zip(b).zip(mass).map(|((x, y), m)| x * m * y).sum(),
            None => mass.inner(a, b),
        }
    }

    fn field_mass(&self) -> &Mass {
        self.complex.m1()
    }

    fn rows(&self, rows: &[usize]) -> Result<Vec<Vec<f64>>, SpectralBasisError> {
        self.observed_rows(rows, self.observer.as_ref())
    }

    fn visit_fields(
        &self,
        visit: &(dyn Fn(usize, &[f64]) + Sync),
    ) -> Result<(), SpectralBasisError> {
        self.observed_visit_fields(visit, self.observer.as_ref())
    }
}

/// Reusable buffers of [`BasisFileBlocks::read_columns`]: the bytes read and their values.
#[derive(Default)]
struct ReadBuffers {
    bytes: Vec<u8>,
    values: Vec<f64>,
}

/// Rows of the field summed together by one thread in [`BasisFileBlocks::combine_fields`], as
/// the loaded basis's synthesis takes them (4096 rows of `f64`, 32 KiB, stay in cache while
/// every field adds its slice).
const ROW_CHUNK: usize = 4096;

/// The families in the order of the stored sections.
const FAMILIES: [FieldFamily; 3] = [
    FieldFamily::Integrable,
    FieldFamily::Cointegrable,
    FieldFamily::Harmonic,
];

/// Field coefficient `r` of the field of a stored column `s`, as a functional of `s`: a row of a
/// sparse operator (`d0`, or the co-gradient of a diagonal `M1`) summed in the order the field
/// is formed in, a dense vector `w` (the co-gradient's transpose applied to `e_r`), or the stored
/// value itself (harmonic fields).
enum RowFunctional {
    /// The stored entries of the row, by ascending column, and whether the operator is stored
    /// by rows (summed as `mul_vec` sums it: by rows from `Sum`, by columns from `0.0`).
    Sparse(Vec<(usize, f64)>, bool),
    /// `wᵀ s`.
    Dense(Vec<f64>),
    /// `s[r]`.
    Entry(usize),
}

impl RowFunctional {
    fn apply(&self, stored: &[f64]) -> f64 {
        match self {
            Self::Dense(w) => w.iter().zip(stored).map(|(a, b)| a * b).sum(),
            _ => self.apply_with(|j| stored[j]),
        }
    }

    /// The functional of the stored column whose entry `j` is `stored(j)`, summed in the same
    /// order whatever gives the entries.
    fn apply_with(&self, stored: impl Fn(usize) -> f64) -> f64 {
        match self {
            Self::Sparse(entries, true) => entries.iter().map(|&(j, a)| a * stored(j)).sum(),
            Self::Sparse(entries, false) => {
                entries.iter().fold(0.0, |sum, &(j, a)| sum + a * stored(j))
            }
            Self::Dense(w) => w.iter().enumerate().map(|(j, a)| a * stored(j)).sum(),
            Self::Entry(r) => stored(*r),
        }
    }

    /// The stored entries a sparse functional reads (none for a dense one).
    fn entries(&self) -> Vec<usize> {
        match self {
            Self::Sparse(entries, _) => entries.iter().map(|&(j, _)| j).collect(),
            Self::Dense(_) => Vec::new(),
            Self::Entry(r) => vec![*r],
        }
    }
}

/// Entries of a column closer than this many values are read together (512 bytes).
const SPAN_GAP: usize = 64;

/// The sorted entries `needed` grouped into inclusive spans `(low, high)` of nearby entries.
fn entry_spans(needed: &[usize]) -> Vec<(usize, usize)> {
    let mut spans: Vec<(usize, usize)> = Vec::new();
    for &j in needed {
        match spans.last_mut() {
            Some((_, high)) if j <= *high + SPAN_GAP => *high = j,
            _ => spans.push((j, j)),
        }
    }
    spans
}

/// The entries of rows `rows` of `matrix`, by ascending column.
fn sparse_rows(matrix: &CsMat<f64>, rows: &[usize]) -> Vec<RowFunctional> {
    let by_rows;
    let csr = if matrix.is_csr() {
        matrix
    } else {
        by_rows = matrix.to_csr();
        &by_rows
    };
    rows.iter()
        .map(|&r| {
            let entries = csr
                .outer_view(r)
                .map(|row| row.iter().map(|(j, &a)| (j, a)).collect())
                .unwrap_or_default();
            RowFunctional::Sparse(entries, matrix.is_csr())
        })
        .collect()
}

/// Position of `family` in per-family arrays: integrable, co-integrable, harmonic.
fn section_index(family: FieldFamily) -> usize {
    match family {
        FieldFamily::Integrable => 0,
        FieldFamily::Cointegrable => 1,
        FieldFamily::Harmonic => 2,
    }
}

/// Where each family's stored columns are in a file with `header` whose body starts at
/// `body_start`.
fn sections_of(header: &BasisFileHeader, body_start: u64, n0: usize, n2: usize) -> [Section; 3] {
    let integrable = Section {
        offset: body_start,
        rows: n0,
        count: header.integrable_count,
    };
    let cointegrable = Section {
        offset: integrable.offset + (8 * n0 * integrable.count) as u64,
        rows: n2,
        count: header.cointegrable_count,
    };
    let harmonic = Section {
        offset: cointegrable.offset + (8 * n2 * cointegrable.count) as u64,
        rows: header.key.field_dimension,
        count: header.harmonic_count,
    };
    [integrable, cointegrable, harmonic]
}

/// Checks the payload `[start, end)` of `file` (`d` eigenvalues and family codes, then stored
/// columns) against the checksum stored at `end`, reading it once in blocks (each reported to
/// `pass`), and that every stored column value is finite.
fn check_payload(
    file: &File,
    path: &Path,
    start: u64,
    d: usize,
    end: u64,
    pass: &mut PassProgress,
) -> Result<(), BasisFileError> {
    let io = |source| BasisFileError::Io {
        path: path.to_path_buf(),
        source,
    };
    let body_start = start + front_bytes(d);
    let mut hash = Hash64::new();
    let mut block = vec![0u8; BLOCK_BYTES];
    let mut non_finite = None;
    let mut at = start;
    while at < end {
        let length = (end - at).min(BLOCK_BYTES as u64) as usize;
        file.read_exact_at(&mut block[..length], at).map_err(io)?;
        hash.update(&block[..length]);
        // The front is whole words, so the body's values start at a multiple of 8 bytes.
        let skip = body_start.saturating_sub(at).min(length as u64);
        if non_finite.is_none() {
            non_finite = block[skip as usize..length]
                .chunks_exact(8)
                .position(|c| !f64::from_le_bytes(c.try_into().unwrap_or([0; 8])).is_finite())
                .map(|word| (at + skip - body_start) / 8 + word as u64);
        }
        at += length as u64;
        pass.advance(length as u64);
    }
    let mut stored = [0u8; 8];
    file.read_exact_at(&mut stored, end).map_err(io)?;
    if u64::from_le_bytes(stored) != hash.finish() {
        return Err(BasisFileError::Checksum {
            path: path.to_path_buf(),
            part: "payload",
        });
    }
    match non_finite {
        Some(word) => Err(BasisFileError::Invalid {
            path: path.to_path_buf(),
            reason: format!("stored value {word} of the eigenfunctions is not finite"),
        }),
        None => Ok(()),
    }
}
