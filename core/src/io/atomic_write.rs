//! Atomic file writes shared by every tvf crate: the content goes to a temporary file in the
//! target's folder, which is flushed to disk and then renamed over the target, so readers see
//! the old file or the complete new one, never a partial write.
//!
//! The temporary file is created with mode `0o666` minus the process umask (on Unix), like a
//! file made by [`std::fs::File::create`]: outputs are readable by others as usual (e.g.
//! `0o644` under the common umask `022`), not owner-only as temporary files are by default.
//!
//! A target that exists and is neither a regular file nor a folder (a character device such as
//! `/dev/null`, a FIFO, a socket) is written to directly, streaming: renaming a file over it
//! would replace the device node or the pipe with a regular file (and needs a temporary file in
//! its folder, e.g. `/dev`). Atomicity is a property of regular files only. A target that is a
//! symbolic link is written through: the file it points to is replaced, the link stays.
//!
//! The target's folder must exist (tvf never creates a missing parent folder; the error says
//! which folder is missing). While it is written, the temporary file is registered with
//! [`super::temporaries`], so an interrupted process removes it; stale temporaries of a killed
//! process are swept from the folder. The rename runs inside
//! [`super::temporaries::commit_uninterrupted`]. Tests inject faults with
//! [`super::inject_write_faults`].

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use super::early_writeback::EarlyWriteback;
use super::output_path::through_links;
use super::temporaries::{
    commit_uninterrupted, create_registered, sweep_stale_temporaries, TEMPORARY_FILE_PREFIX,
    TEMPORARY_SUFFIX,
};
use super::write_faults::apply_injected_fault;

/// The buffered writer [`write_atomically`] hands to its `fill`: the temporary file (or the
/// special file itself), whose disk writes start while it is written ([`EarlyWriteback`]).
pub type AtomicWriter<'f> = BufWriter<EarlyWriteback<'f>>;

/// Writes `path` atomically through `fill`, which writes the content into a buffered writer.
/// On error (from `fill` or the file system) the temporary file is removed and `path` is left
/// as it was. A `path` that is a special file (a device, a FIFO) is written directly.
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
    let path = &through_links(path);
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
    match std::fs::metadata(path) {
        Ok(metadata) if metadata.is_dir() => {
            return Err(std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                format!("{} is a folder, not a file", path.display()),
            ))
        }
        Ok(metadata) if !metadata.is_file() => return write_special_file(path, fill),
        _ => {}
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
    let (mut temporary, _registration) = create_registered(
        || builder.tempfile_in(directory),
        |t| t.path().to_path_buf(),
    )?;
    fill_and_flush(temporary.as_file_mut(), fill)?;
    apply_injected_fault(path)?;
    temporary.as_file().sync_all()?;
    commit_uninterrupted(|| temporary.persist(path).map(drop).map_err(|e| e.error))
}

/// Writes a special file (a device, a FIFO) in place, streaming: nothing to rename, and no
/// `fsync` (pipes and most devices refuse it).
fn write_special_file(
    path: &Path,
    fill: impl FnOnce(&mut AtomicWriter<'_>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut file = std::fs::OpenOptions::new().write(true).open(path)?;
    fill_and_flush(&mut file, fill)?;
    apply_injected_fault(path)
}

/// Runs `fill` on a buffered writer into `file` and flushes it.
fn fill_and_flush(
    file: &mut File,
    fill: impl FnOnce(&mut AtomicWriter<'_>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut writer = BufWriter::new(EarlyWriteback::new(file));
    fill(&mut writer)?;
    writer.flush()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::{inject_write_faults, WriteFault};

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

    /// A FIFO output is written through, streaming, and stays a FIFO (no temporary file, no
    /// rename over it).
    #[cfg(unix)]
    #[test]
    fn a_fifo_output_is_streamed_and_stays_a_fifo() {
        use std::io::Read;
        use std::os::unix::fs::FileTypeExt;
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("pipe");
        let status = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .expect("mkfifo runs");
        assert!(status.success());
        let reader = {
            let fifo = fifo.clone();
            std::thread::spawn(move || {
                let mut text = String::new();
                File::open(&fifo)
                    .unwrap()
                    .read_to_string(&mut text)
                    .unwrap();
                text
            })
        };
        write_atomically(&fifo, |w| w.write_all(b"through the pipe")).unwrap();
        assert_eq!(reader.join().unwrap(), "through the pipe");
        let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
        assert!(kind.is_fifo(), "{kind:?}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    /// A link is written through: its target gets the content and the link stays a link.
    #[cfg(unix)]
    #[test]
    fn a_link_output_is_written_through() {
        let dir = tempfile::tempdir().unwrap();
        let (link, real) = (dir.path().join("link.npy"), dir.path().join("real.npy"));
        std::fs::write(&real, b"old").unwrap();
        std::os::unix::fs::symlink("real.npy", &link).unwrap();
        write_atomically(&link, |w| w.write_all(b"new")).unwrap();
        assert_eq!(std::fs::read(&real).unwrap(), b"new");
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        let dangling = dir.path().join("dangling.npy");
        std::os::unix::fs::symlink("missing/x.npy", &dangling).unwrap();
        let error = write_atomically(&dangling, |w| w.write_all(b"x")).unwrap_err();
        assert!(error.to_string().contains("does not exist"), "{error}");
    }

    #[test]
    fn a_folder_in_the_way_is_an_error_naming_it() {
        let dir = tempfile::tempdir().unwrap();
        let error = write_atomically(dir.path(), |w| w.write_all(b"x")).unwrap_err();
        assert!(error.to_string().contains("is a folder"), "{error}");
    }

    #[test]
    fn an_injected_fault_fails_the_write_and_leaves_nothing() {
        fn fail_one_name(path: &Path) -> Option<WriteFault> {
            (path.file_name()? == "injected-fault.bin").then_some(WriteFault::Fail)
        }
        // Other tests of this process write other names: the hook leaves them alone.
        inject_write_faults(fail_one_name);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("injected-fault.bin");
        let error = write_atomically(&path, |w| w.write_all(b"x")).unwrap_err();
        assert!(error.to_string().contains("injected"), "{error}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        write_atomically(&dir.path().join("other.bin"), |w| w.write_all(b"x")).unwrap();
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
