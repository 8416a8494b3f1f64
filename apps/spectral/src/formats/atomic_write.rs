//! Atomic file writes: a temporary file in the destination's directory, renamed over the target.

use std::io::Write;
use std::path::Path;

/// Writes `bytes` to `path` atomically: readers see the old file or the complete new one, never a
/// partial write. The data go to a temporary file in the same directory (same file system), are
/// flushed to disk, and the temporary file is renamed to `path`. On error the temporary file is
/// removed and `path` is untouched. The file gets ordinary permissions (`0o666` minus the
/// umask), see [`tvf_core::io::write_atomically`].
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomically_with(path, |w| w.write_all(bytes))
}

/// Like [`write_atomically`], with the content produced by `fill` into a buffered writer (for
/// large outputs that should not be assembled in memory first).
pub fn write_atomically_with(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    // One helper for the whole workspace (temporary file with ordinary permissions, rename).
    tvf_core::io::write_atomically(path, |writer| fill(writer))
}
