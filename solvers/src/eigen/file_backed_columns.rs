//! [`FileBackedColumns`]: the `n × k` eigenvectors of a streamed call
//! ([`EigenOptions::finished`](super::types::EigenOptions::finished)) in a shared mapping of an
//! unnamed temporary file instead of anonymous memory, so that finished intervals can leave
//! memory until they are handed on ([`super::interval_stream`]): their pages are written to the
//! file and unmapped ([`ParkedColumns::park`], by the job that solved them, as it finishes),
//! and fault back in when it is their turn. Handed-on columns are unmapped and their part of
//! the file punched out ([`drop_columns`]), so neither memory nor disk holds them. Parked pages
//! stay in the page cache while memory is plentiful, where they no longer count as the
//! process's and the kernel can drop them once written. Measured in `docs/performance.md`:
//! without the parking, every interval waited in memory for the lowest one of its family.
//! Linux only; elsewhere, or where no temporary file can be made, the columns are anonymous
//! memory and parking does nothing.

use super::interval_stream::RawColumns;
use crate::huge_pages::{release_pages, reserve_on_huge_pages};
use faer::Mat;

/// Room for `rows × columns` values: a mapped temporary file, or reserved anonymous memory.
pub(crate) enum FileBackedColumns {
    #[cfg(target_os = "linux")]
    Mapped {
        file: std::fs::File,
        ptr: *mut f64,
        bytes: usize,
        rows: usize,
    },
    /// Reserved, untouched anonymous memory (`rows` rows).
    Memory { matrix: Mat<f64>, rows: usize },
}

impl FileBackedColumns {
    /// Room for `rows × columns` values, all zero until written (a sparse file: nothing is on
    /// disk or in memory before it is written).
    pub(crate) fn new(rows: usize, columns: usize) -> Self {
        #[cfg(target_os = "linux")]
        if let Some(mapped) = Self::mapped(rows, columns) {
            return mapped;
        }
        Self::Memory {
            matrix: reserve_on_huge_pages(rows, columns),
            rows,
        }
    }

    #[cfg(target_os = "linux")]
    fn mapped(rows: usize, columns: usize) -> Option<Self> {
        use std::os::unix::fs::OpenOptionsExt;
        use std::os::unix::io::AsRawFd;
        let bytes = rows.checked_mul(columns)?.checked_mul(8)?;
        if bytes == 0 {
            return None;
        }
        let file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .mode(0o600)
            .custom_flags(libc::O_TMPFILE)
            .open(std::env::temp_dir())
            .ok()?;
        file.set_len(bytes as u64).ok()?;
        // SAFETY: a fresh shared mapping of the whole file, owned by the returned value and
        // unmapped when it is dropped.
        let ptr = unsafe {
            libc::mmap(
                std::ptr::null_mut(),
                bytes,
                libc::PROT_READ | libc::PROT_WRITE,
                libc::MAP_SHARED,
                file.as_raw_fd(),
                0,
            )
        };
        (ptr != libc::MAP_FAILED).then_some(Self::Mapped {
            file,
            ptr: ptr as *mut f64,
            bytes,
            rows,
        })
    }

    /// The columns, for [`RawColumns`] views (`k` columns used).
    pub(crate) fn raw(&mut self, k: usize) -> RawColumns {
        match self {
            #[cfg(target_os = "linux")]
            Self::Mapped {
                file, ptr, rows, ..
            } => {
                use std::os::unix::io::AsRawFd;
                RawColumns {
                    ptr: *ptr,
                    rows: *rows,
                    col_stride: *rows,
                    k,
                    file: Some(file.as_raw_fd()),
                }
            }
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

impl Drop for FileBackedColumns {
    fn drop(&mut self) {
        #[cfg(target_os = "linux")]
        if let Self::Mapped { ptr, bytes, .. } = self {
            // SAFETY: the mapping made in `mapped`, no view of it outlives the call that made it.
            unsafe {
                libc::munmap(*ptr as *mut libc::c_void, *bytes);
            }
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
    /// writeback started now) and unmapped.
    ///
    /// # Safety
    /// The columns still lie inside their mapping, and no view of them is alive.
    pub(crate) unsafe fn park(&self) {
        #[cfg(target_os = "linux")]
        {
            // Failures only mean the pages stay in memory.
            libc::sync_file_range(
                self.fd,
                self.offset as i64,
                self.bytes as i64,
                libc::SYNC_FILE_RANGE_WRITE,
            );
            unmap(self.start, self.bytes);
        }
    }
}

/// Gives columns `first..first + width` back for good: unmapped, and for a file their part
/// punched out (no longer on disk nor in the page cache); released pages of anonymous memory.
///
/// # Safety
/// The columns lie inside `columns`, and nothing reads them again.
pub(crate) unsafe fn drop_columns(columns: &RawColumns, first: usize, width: usize) {
    let (offset, bytes) = byte_range(columns, first, width);
    match columns.file {
        #[cfg(target_os = "linux")]
        Some(fd) => {
            unmap(columns.ptr as usize + offset, bytes);
            libc::fallocate(
                fd,
                libc::FALLOC_FL_PUNCH_HOLE | libc::FALLOC_FL_KEEP_SIZE,
                offset as i64,
                bytes as i64,
            );
        }
        _ => release_pages(columns.ptr as usize + offset, bytes),
    }
}

/// Unmaps the whole pages inside `[start, start + bytes)` of a shared file mapping (their
/// contents stay in the file).
#[cfg(target_os = "linux")]
unsafe fn unmap(start: usize, bytes: usize) {
    release_pages(start, bytes);
}
