//! [`FileBackedColumns`]: the `n × k` eigenvectors of a streamed call
//! ([`EigenOptions::finished`](super::types::EigenOptions::finished)) in a shared mapping of an
//! unnamed temporary file instead of anonymous memory, so that finished intervals can leave
//! memory until they are handed on ([`super::interval_stream`]): their pages are written to the
//! file and released ([`ParkedColumns::park`], by the job that solved them, as it finishes),
//! and fault back in when it is their turn. Handed-on columns are released and their part of
//! the file punched out ([`drop_columns`]), so neither memory nor disk holds them. Parked pages
//! stay in the page cache while memory is plentiful, where they no longer count as the
//! process's and the kernel can drop them once written. Measured in `docs/performance.md`:
//! without the parking, every interval waited in memory for the lowest one of its family.
//! The file and its system calls are [`super::temporary_file_mapping`]'s, on Linux only;
//! elsewhere, or where no temporary file can be made, the columns are anonymous memory
//! ([`FileBackedColumns::in_memory`]) and parking does nothing. The tests run both on Linux.
//!
//! The file costs time where memory is plentiful: the writeback of a mapped range write-protects
//! each of its 4 KiB pages, one cross-processor TLB flush per page, and the pages fault back in
//! one by one when handed on. So a streamed call whose eigenvectors are small next to the slice
//! budget keeps them in anonymous memory ([`streamed_eigenvectors_in_memory`]); measured in
//! `docs/performance.md`.

use super::interval_stream::RawColumns;
#[cfg(target_os = "linux")]
use super::temporary_file_mapping::{punch_out, write_back_and_release, TemporaryFileMapping};
use crate::huge_pages::{release_pages, reserve_on_huge_pages};
use faer::Mat;

/// The share of the slice budget ([`EigenOptions::slice_memory`](super::EigenOptions)) that the
/// eigenvectors of a streamed call may take in anonymous memory: one part in this many.
const IN_MEMORY_SHARE: usize = 4;

/// Whether the eigenvectors of a streamed call, `bytes` bytes for all its requests together,
/// stay in anonymous memory ([`FileBackedColumns::in_memory`]) rather than in a temporary file:
/// when they take at most a quarter of the slice budget `budget` (bytes). Then they add at most
/// a quarter to the memory the slices may take, and the file's system calls, which cost more
/// than the memory saves at that size, are skipped (`tvf basis hand.obj -k 1000`, 100 MB of
/// eigenvectors: 0.86× the wall time). A million-face basis (8 GB of eigenvectors against the
/// default 4 GiB budget) still goes through the file.
pub fn streamed_eigenvectors_in_memory(bytes: usize, budget: usize) -> bool {
    bytes <= budget / IN_MEMORY_SHARE
}

/// Room for `rows × columns` values: a mapped temporary file, or reserved anonymous memory.
pub(crate) enum FileBackedColumns {
    #[cfg(target_os = "linux")]
    Mapped {
        mapping: TemporaryFileMapping,
        rows: usize,
    },
    /// Reserved, untouched anonymous memory (`rows` rows).
    Memory { matrix: Mat<f64>, rows: usize },
}

impl FileBackedColumns {
    /// Room for `rows × columns` values, all zero until written: a temporary file where one can
    /// be made (Linux), anonymous memory ([`FileBackedColumns::in_memory`]) otherwise.
    pub(crate) fn new(rows: usize, columns: usize) -> Self {
        #[cfg(target_os = "linux")]
        if let Some(mapping) = rows
            .checked_mul(columns)
            .and_then(|values| values.checked_mul(std::mem::size_of::<f64>()))
            .and_then(TemporaryFileMapping::new)
        {
            return Self::Mapped { mapping, rows };
        }
        Self::in_memory(rows, columns)
    }

    /// The fallback: room for `rows × columns` values in reserved anonymous memory, where
    /// parking does nothing.
    pub(crate) fn in_memory(rows: usize, columns: usize) -> Self {
        Self::Memory {
            matrix: reserve_on_huge_pages(rows, columns),
            rows,
        }
    }

    /// The columns, for [`RawColumns`] views (`k` columns used).
    pub(crate) fn raw(&mut self, k: usize) -> RawColumns {
        match self {
            #[cfg(target_os = "linux")]
            Self::Mapped { mapping, rows } => RawColumns {
                ptr: mapping.ptr(),
                rows: *rows,
                col_stride: *rows,
                k,
                file: Some(mapping.descriptor()),
            },
            Self::Memory { matrix, rows } => RawColumns {
                ptr: matrix.as_ptr_mut(),
                rows: *rows,
                col_stride: matrix.col_stride().unsigned_abs(),
                k,
                file: None,
            },
        }
    }
}

/// The byte range of columns `first..first + width` of `columns`, from its start.
fn byte_range(columns: &RawColumns, first: usize, width: usize) -> (usize, usize) {
    let stride = columns.col_stride * std::mem::size_of::<f64>();
    (first * stride, width * stride)
}

/// Columns of a file mapping, as plain numbers (so that the thread that solved them can move
/// them out of memory, [`ParkedColumns::park`]).
#[derive(Clone, Copy)]
pub(crate) struct ParkedColumns {
    /// Address of the first column.
    start: usize,
    /// Its offset in the file, and the bytes of the columns.
    offset: usize,
    bytes: usize,
    fd: i32,
}

impl ParkedColumns {
    /// Columns `first..first + width` of `columns`; `None` for anonymous memory (nothing to
    /// park).
    pub(crate) fn of(columns: &RawColumns, first: usize, width: usize) -> Option<Self> {
        let fd = columns.file?;
        let (offset, bytes) = byte_range(columns, first, width);
        Some(Self {
            start: columns.ptr as usize + offset,
            offset,
            bytes,
            fd,
        })
    }

    /// Moves the columns out of memory until they are read again: written to the file (the
    /// writeback started now) and their pages released.
    ///
    /// # Safety
    /// The columns still lie inside their mapping, and no view of them is alive.
    pub(crate) unsafe fn park(&self) {
        #[cfg(target_os = "linux")]
        write_back_and_release(self.fd, self.start, self.offset, self.bytes);
    }
}

/// Gives columns `first..first + width` back for good: their pages released, and for a file their part
/// punched out (no longer on disk nor in the page cache); released pages of anonymous memory.
///
/// # Safety
/// The columns lie inside `columns`, and nothing reads them again.
pub(crate) unsafe fn drop_columns(columns: &RawColumns, first: usize, width: usize) {
    let (offset, bytes) = byte_range(columns, first, width);
    let start = columns.ptr as usize + offset;
    match columns.file {
        #[cfg(target_os = "linux")]
        Some(fd) => punch_out(fd, start, offset, bytes),
        _ => release_pages(start, bytes),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The value every test writes at row `i` of column `j`.
    fn value(i: usize, j: usize) -> f64 {
        (i * 7 + j) as f64 + 0.5
    }

    /// Entry `(i, j)` of `columns`.
    ///
    /// # Safety
    /// `(i, j)` lies inside `columns`.
    unsafe fn entry(columns: &RawColumns, i: usize, j: usize) -> *mut f64 {
        columns.ptr.add(j * columns.col_stride + i)
    }

    /// Fills four columns of 3,000 rows (24 kB each: whole pages inside every one), parks
    /// columns 1 and 2, checks every value read back, drops column 1 and checks that its whole
    /// pages read as zeros while the other columns keep their values.
    fn parked_columns_read_back_and_dropped_ones_are_zero(mut storage: FileBackedColumns) {
        let (rows, k) = (3000, 4);
        let columns = storage.raw(k);
        // SAFETY: every entry written lies inside the `rows × k` columns; no view is alive.
        unsafe {
            for j in 0..k {
                for i in 0..rows {
                    entry(&columns, i, j).write(value(i, j));
                }
            }
            let parked = ParkedColumns::of(&columns, 1, 2);
            assert_eq!(parked.is_some(), columns.file.is_some());
            if let Some(parked) = parked {
                parked.park();
            }
            for j in 0..k {
                for i in 0..rows {
                    assert_eq!(entry(&columns, i, j).read(), value(i, j), "({i}, {j})");
                }
            }
            drop_columns(&columns, 1, 1);
            let page_values = 4096 / std::mem::size_of::<f64>();
            let column_start = columns.ptr as usize + columns.col_stride * 8;
            let first_whole = (column_start.next_multiple_of(4096) - column_start) / 8;
            let zeros = (first_whole..rows).take(page_values);
            assert!(zeros.len() == page_values, "a whole page inside column 1");
            for i in zeros {
                assert_eq!(
                    entry(&columns, i, 1).read(),
                    0.0,
                    "row {i} of the dropped column"
                );
            }
            for j in [0, 2, 3] {
                for i in 0..rows {
                    assert_eq!(entry(&columns, i, j).read(), value(i, j), "({i}, {j})");
                }
            }
        }
    }

    /// At the default budget of a 24 GiB machine (4 GiB), the eigenvectors of `tvf basis
    /// bunny-closed.obj -k 1000` (about 500 columns of 34,834 and of 104,499 rows) stay in
    /// memory, those of the million-face basis (500 of 510,842 and of 1,532,520 rows) go to
    /// the file; the bound itself is in memory.
    #[test]
    fn only_eigenvectors_small_next_to_the_slice_budget_stay_in_memory() {
        let budget = 4 << 30;
        let bytes = |rows: &[usize]| rows.iter().map(|n| n * 500 * 8).sum::<usize>();
        assert!(streamed_eigenvectors_in_memory(
            bytes(&[34_834, 104_499]),
            budget
        ));
        assert!(!streamed_eigenvectors_in_memory(
            bytes(&[510_842, 1_532_520]),
            budget
        ));
        assert!(streamed_eigenvectors_in_memory(budget / 4, budget));
        assert!(!streamed_eigenvectors_in_memory(budget / 4 + 1, budget));
    }

    #[test]
    fn anonymous_memory_fallback_keeps_values_and_releases_dropped_columns() {
        parked_columns_read_back_and_dropped_ones_are_zero(FileBackedColumns::in_memory(3000, 4));
    }

    #[test]
    #[cfg(target_os = "linux")]
    fn a_temporary_file_parks_columns_and_punches_out_dropped_ones() {
        let storage = FileBackedColumns::new(3000, 4);
        assert!(
            matches!(storage, FileBackedColumns::Mapped { .. }),
            "no temporary file could be mapped in {}",
            std::env::temp_dir().display()
        );
        parked_columns_read_back_and_dropped_ones_are_zero(storage);
    }
}
