//! Atomic file writes shared by every tvf crate: the content goes to a temporary file in the
//! target's folder, which is flushed to disk and then renamed over the target, so readers see
//! the old file or the complete new one, never a partial write.
//!
//! The temporary file is created with mode `0o666` minus the process umask (on Unix), like a
//! file made by [`std::fs::File::create`]: outputs are readable by others as usual (e.g.
//! `0o644` under the common umask `022`), not owner-only as temporary files are by default.
//!
//! The target's folder must exist (tvf never creates a missing parent folder; the error says
//! which folder is missing). While it is written, the temporary file is registered with
//! [`super::temporaries`], so an interrupted process removes it; stale temporaries of a killed
//! process are swept from the folder.

use std::io::{BufWriter, Write};
use std::path::Path;

use super::early_writeback::EarlyWriteback;
use super::temporaries::{
    register, sweep_stale_temporaries, TEMPORARY_FILE_PREFIX, TEMPORARY_SUFFIX,
};

/// Environment variable for tests of all-or-nothing outputs and of interruption: `fail:NAME`
/// makes writing a file called `NAME` (the last path component) fail as on a full disk, after
/// its content went to the temporary file; `stall:NAME` makes it wait there for a minute, as
/// on a very slow disk (to interrupt the process then).
pub const WRITE_FAULT_VARIABLE: &str = "TVF_TEST_WRITE_FAULT";

/// The buffered writer [`write_atomically`] hands to its `fill`: the temporary file, whose disk
/// writes start while it is written ([`EarlyWriteback`]).
pub type AtomicWriter<'f> = BufWriter<EarlyWriteback<'f>>;

/// Writes `path` atomically through `fill`, which writes the content into a buffered writer.
/// On error (from `fill` or the file system) the temporary file is removed and `path` is left
/// as it was.
///
/// ```
/// use std::io::Write;
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("hello.txt");
/// tvf_core::io::write_atomically(&path, |w| w.write_all(b"hello")).unwrap();
/// assert_eq!(std::fs::read(&path).unwrap(), b"hello");
/// ```
pub fn write_atomically(
    path: &Path,
    fill: impl FnOnce(&mut AtomicWriter<'_>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let directory = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    if !directory.is_dir() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::NotFound,
            format!("the folder {} does not exist", directory.display()),
        ));
    }
    sweep_stale_temporaries(directory);
    let mut builder = tempfile::Builder::new();
    builder
        .prefix(TEMPORARY_FILE_PREFIX)
        .suffix(TEMPORARY_SUFFIX);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        // open(2) applies the umask to this mode, as it does for File::create.
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut temporary = builder.tempfile_in(directory)?;
    let _registration = register(temporary.path());
    {
        let mut writer = BufWriter::new(EarlyWriteback::new(temporary.as_file_mut()));
        fill(&mut writer)?;
        writer.flush()?;
    }
    match injected_fault(path).as_deref() {
        Some("fail") => {
            return Err(std::io::Error::other(format!(
                "injected write failure ({WRITE_FAULT_VARIABLE})"
            )))
        }
        Some("stall") => std::thread::sleep(std::time::Duration::from_secs(60)),
        _ => {}
    }
    temporary.as_file().sync_all()?;
    temporary.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// The fault [`WRITE_FAULT_VARIABLE`] asks for when writing `path` (`fail` or `stall`), if any.
fn injected_fault(path: &Path) -> Option<String> {
    let value = std::env::var(WRITE_FAULT_VARIABLE).ok()?;
    let (fault, name) = value.split_once(':')?;
    (path.file_name()? == std::ffi::OsStr::new(name)).then(|| fault.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs::File;

    #[test]
    fn replaces_the_file_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.bin");
        write_atomically(&path, |w| w.write_all(b"first")).unwrap();
        write_atomically(&path, |w| w.write_all(b"second")).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_failing_writer_leaves_the_old_file_and_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.bin");
        write_atomically(&path, |w| w.write_all(b"old")).unwrap();
        let result = write_atomically(&path, |w| {
            w.write_all(b"partial")?;
            Err(std::io::Error::other("disk full"))
        });
        assert!(result.is_err());
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    /// The written file has the permissions `File::create` would give (`0o666` minus the
    /// umask), not the owner-only `0o600` of temporary files.
    #[cfg(unix)]
    #[test]
    fn the_file_gets_the_permissions_of_an_ordinary_new_file() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let reference = dir.path().join("reference");
        File::create(&reference).unwrap();
        let expected = std::fs::metadata(&reference).unwrap().permissions().mode() & 0o777;
        let path = dir.path().join("out.bin");
        write_atomically(&path, |w| w.write_all(b"x")).unwrap();
        let mode = std::fs::metadata(&path).unwrap().permissions().mode() & 0o777;
        assert_eq!(
            mode, expected,
            "mode {mode:o}, File::create gives {expected:o}"
        );
    }
}
