//! Atomic file writes: write into a temporary file in the target's folder, then rename.

use std::path::Path;
use tvf_core::io::AtomicWriter;

use crate::error::RenderError;

/// Writes `path` atomically: `fill` writes into a temporary file in the same folder, which
/// replaces `path` only once everything has been written and flushed. On error the target
/// is untouched and the temporary file is removed. The file gets ordinary permissions (`0o666`
/// minus the umask), see [`tvf_core::io::write_atomically`].
pub fn write_atomically(
    path: &Path,
    fill: impl FnOnce(&mut AtomicWriter<'_>) -> std::io::Result<()>,
) -> Result<(), RenderError> {
    let io = |source| RenderError::Io {
        path: path.to_path_buf(),
        source,
    };
    // One helper for the whole workspace (temporary file with ordinary permissions, rename).
    tvf_core::io::write_atomically(path, fill).map_err(io)
}
