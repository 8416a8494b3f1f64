//! [`EarlyWriteback`]: a file writer that starts the disk writes while the file is still being
//! written.
//!
//! Why: an atomic write ends with `fsync` (see [`super::write_atomically`]), which waits until
//! every byte is on the disk. The kernel otherwise holds dirty pages back for seconds, so for a
//! large file all of the disk's work was left to that `fsync` (a noticeable wait for a basis
//! file of hundreds of MB, see `docs/performance.md`). Asking for the writeback of every written stretch of
//! [`WRITEBACK_STRETCH`] bytes right away (`sync_file_range` with `SYNC_FILE_RANGE_WRITE`,
//! which does not wait) lets the disk work while the rest is formed and copied. Elsewhere than
//! Linux it is a plain writer.

use std::fs::File;
use std::io::Write;

/// Bytes written between two writeback requests.
const WRITEBACK_STRETCH: u64 = 32 << 20;

/// Writes through to a file, asking the kernel to start writing each [`WRITEBACK_STRETCH`]
/// bytes to the disk as soon as they are written (see the module documentation).
pub struct EarlyWriteback<'f> {
    file: &'f mut File,
    /// Bytes written so far.
    written: u64,
    /// Start of the stretch whose writeback has not been requested yet.
    requested: u64,
}

impl<'f> EarlyWriteback<'f> {
    /// A writer at the start of `file` (which it writes from its current position, the start
    /// for a fresh file).
    pub fn new(file: &'f mut File) -> Self {
        Self {
            file,
            written: 0,
            requested: 0,
        }
    }

    /// Asks for the writeback of the bytes written since the last request (advice: failures
    /// are ignored, the final `fsync` writes whatever is left).
    fn request_writeback(&mut self) {
        #[cfg(target_os = "linux")]
        {
            use std::os::fd::AsRawFd;
            let (offset, length) = (self.requested, self.written - self.requested);
            if let (Ok(offset), Ok(length)) = (i64::try_from(offset), i64::try_from(length)) {
                // SAFETY: a valid open file descriptor and a byte range; the call only
                // schedules writeback and touches no memory of this process.
                unsafe {
                    libc::sync_file_range(
                        self.file.as_raw_fd(),
                        offset,
                        length,
                        libc::SYNC_FILE_RANGE_WRITE,
                    );
                }
            }
        }
        self.requested = self.written;
    }
}

impl Write for EarlyWriteback<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let written = self.file.write(buf)?;
        self.written += written as u64;
        if self.written - self.requested >= WRITEBACK_STRETCH {
            self.request_writeback();
        }
        Ok(written)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Read;

    /// What goes through the writer is the file's content, across several writeback stretches
    /// and a partial last one.
    #[test]
    fn writes_everything_in_order() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.bin");
        let mut file = File::create(&path).unwrap();
        let bytes: Vec<u8> = (0..(2 * WRITEBACK_STRETCH + 12345))
            .map(|i| (i % 251) as u8)
            .collect();
        {
            let mut writer = EarlyWriteback::new(&mut file);
            for chunk in bytes.chunks(1 << 20) {
                writer.write_all(chunk).unwrap();
            }
            writer.flush().unwrap();
            assert_eq!(writer.requested, 2 * WRITEBACK_STRETCH);
        }
        let mut read = Vec::new();
        File::open(&path).unwrap().read_to_end(&mut read).unwrap();
        assert!(read == bytes);
    }
}
