//! [`TemporaryFileMapping`]: a shared, writable mapping of an unnamed temporary file (Linux's
//! `O_TMPFILE`), and the two things [`super::file_backed_columns`] does to a range of it: write
//! it back and let it leave memory ([`write_back_and_release`]), or give it up for good
//! ([`punch_out`]). Every system call of the streamed eigenvectors is here; the module exists on
//! Linux only, and `file_backed_columns` falls back to anonymous memory elsewhere (and where no
//! temporary file can be made), a fallback its tests run on Linux too.

use crate::huge_pages::release_pages;
use std::fs::File;
use std::os::unix::fs::OpenOptionsExt;
use std::os::unix::io::AsRawFd;

/// `bytes` bytes of an unnamed temporary file in [`std::env::temp_dir`], mapped shared and
/// writable; zero until written (a sparse file: nothing is on disk or in memory before).
/// Unmapped when dropped; the file disappears with its last descriptor.
pub(crate) struct TemporaryFileMapping {
    file: File,
    ptr: *mut f64,
    bytes: usize,
}

impl TemporaryFileMapping {
    /// The mapping, or `None` where the file cannot be made, sized or mapped (no `O_TMPFILE`
    /// support in the temporary folder's file system, `bytes == 0`) or where its file system
    /// has less than `bytes` free: a write into a shared mapping that finds no space is a
    /// `SIGBUS`, which ends the process without a word (a million-face basis did so on a full
    /// disk), so the eigenvectors stay in memory instead. Space taken by others while the
    /// mapping is in use can still do that; the blocks are not reserved up front, because on a
    /// `tmpfs` temporary folder reserving them would take the memory the file is there to save.
    pub(crate) fn new(bytes: usize) -> Option<Self> {
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
        if free_bytes(&file)? < bytes as u128 {
            return None;
        }
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
        (ptr != libc::MAP_FAILED).then_some(Self {
            file,
            ptr: ptr as *mut f64,
            bytes,
        })
    }

    /// The first value of the mapping.
    pub(crate) fn ptr(&self) -> *mut f64 {
        self.ptr
    }

    /// The file's descriptor, for [`write_back_and_release`] and [`punch_out`].
    pub(crate) fn descriptor(&self) -> i32 {
        self.file.as_raw_fd()
    }
}

/// Bytes free for an unprivileged user on the file system of `file`, or `None` if unknown.
fn free_bytes(file: &File) -> Option<u128> {
    // SAFETY: `fstatvfs` fills the zeroed plain-data struct for a valid descriptor.
    let mut stat: libc::statvfs = unsafe { std::mem::zeroed() };
    let status = unsafe { libc::fstatvfs(file.as_raw_fd(), &mut stat) };
    (status == 0).then(|| u128::from(stat.f_bavail) * u128::from(stat.f_frsize))
}

impl Drop for TemporaryFileMapping {
    fn drop(&mut self) {
        // SAFETY: the mapping made in `new`; no view of it outlives the call that made it.
        unsafe {
            libc::munmap(self.ptr as *mut libc::c_void, self.bytes);
        }
    }
}

/// Starts writing `bytes` bytes at `offset` of the file `descriptor` back to disk and releases
/// their pages from the process (mapped at `start`): they leave memory once written and fault
/// back in, from the page cache or the file, when read. Failures only mean the pages stay in
/// memory.
///
/// # Safety
/// `[start, start + bytes)` is the range `offset..offset + bytes` of a live
/// [`TemporaryFileMapping`] of `descriptor`, and no view of it is alive.
pub(crate) unsafe fn write_back_and_release(
    descriptor: i32,
    start: usize,
    offset: usize,
    bytes: usize,
) {
    libc::sync_file_range(
        descriptor,
        offset as i64,
        bytes as i64,
        libc::SYNC_FILE_RANGE_WRITE,
    );
    release_pages(start, bytes);
}

/// Gives the range up for good: its pages released and its part of the file punched out (no
/// longer on disk nor in the page cache; it reads as zeros).
///
/// # Safety
/// As for [`write_back_and_release`], and nothing reads the range again.
pub(crate) unsafe fn punch_out(descriptor: i32, start: usize, offset: usize, bytes: usize) {
    release_pages(start, bytes);
    libc::fallocate(
        descriptor,
        libc::FALLOC_FL_PUNCH_HOLE | libc::FALLOC_FL_KEEP_SIZE,
        offset as i64,
        bytes as i64,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file larger than its file system's free space is not mapped (a sparse file of that
    /// size could be: writing into it would end the process with `SIGBUS`); one that fits is.
    #[test]
    fn a_mapping_is_made_only_where_the_file_fits() {
        let probe = TemporaryFileMapping::new(4096).expect("a small temporary file maps");
        let free = free_bytes(&probe.file).expect("the temporary folder reports its free space");
        let beyond = usize::try_from(free + (1 << 30)).expect("fits in usize");
        assert!(TemporaryFileMapping::new(beyond).is_none());
    }
}
