//! Atomic file writes: write into a temporary file in the target's folder, then rename.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use crate::error::RenderError;

/// Writes `path` atomically: `fill` writes into a temporary file in the same folder, which
/// replaces `path` only once everything has been written and flushed. On error the target
/// is untouched and the temporary file is removed.
pub fn write_atomically(
    path: &Path,
    fill: impl FnOnce(&mut BufWriter<&mut File>) -> std::io::Result<()>,
) -> Result<(), RenderError> {
    let io = |source| RenderError::Io {
        path: path.to_path_buf(),
        source,
    };
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    let mut temp = tempfile::Builder::new()
        .prefix(".tvf-")
        .suffix(".tmp")
        .tempfile_in(&dir)
        .map_err(io)?;
    {
        let mut writer = BufWriter::new(temp.as_file_mut());
        fill(&mut writer).map_err(io)?;
        writer.flush().map_err(io)?;
    }
    temp.as_file().sync_all().map_err(io)?;
    temp.persist(path).map_err(|e| io(e.error))?;
    Ok(())
}
