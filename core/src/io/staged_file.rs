//! [`StagedFile`]: a file output that is put into place only when the command's other outputs
//! are ready too (`tvf basis -o X --export DIR` writes both or neither). Its content is written,
//! by any writer that takes a path, into a temporary sibling folder (`.tvf-folder-*.tmp`, same
//! file system) and renamed over the target by [`StagedFile::commit`]; dropping it uncommitted
//! removes the temporary folder and leaves the target as it was.
//!
//! A target that is a special file (a device, a FIFO) has nothing to stage: it is written
//! directly ([`super::write_atomically`] streams into it) and the commit does nothing.

use std::path::{Path, PathBuf};

use super::output_path::through_links;
use super::staged_folder::StagedFolder;
use super::temporaries::commit_uninterrupted;
use super::write_faults::apply_injected_fault;

/// A file being written; see the [module](self).
#[derive(Debug)]
pub struct StagedFile {
    target: PathBuf,
    /// The temporary folder holding the content; `None` for a special file.
    staging: Option<StagedFolder>,
}

impl StagedFile {
    /// Starts writing the file `target`. Its folder must exist (tvf never creates a missing
    /// parent); `target` must not be a folder.
    pub fn new(target: &Path) -> std::io::Result<Self> {
        let target = &through_links(target);
        let staging = match std::fs::metadata(target) {
            Ok(metadata) if metadata.is_dir() => {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::AlreadyExists,
                    format!("{} is a folder, not a file", target.display()),
                ))
            }
            Ok(metadata) if !metadata.is_file() => None,
            _ => Some(StagedFolder::new(&staging_target(target))?),
        };
        Ok(Self {
            target: target.to_path_buf(),
            staging,
        })
    }

    /// Where the content goes until [`commit`](Self::commit).
    pub fn path(&self) -> PathBuf {
        match (&self.staging, self.target.file_name()) {
            (Some(staging), Some(name)) => staging.path().join(name),
            _ => self.target.clone(),
        }
    }

    /// Puts the complete file into place (uninterrupted, see
    /// [`super::temporaries::commit_uninterrupted`]). An injected write fault
    /// ([`super::inject_write_faults`]) for the target is applied first, as
    /// [`super::write_atomically`] applies it before its rename (content written in place by
    /// the caller, as a basis computed into its file is, gets it only here).
    pub fn commit(self) -> std::io::Result<()> {
        let content = self.path();
        let Some(staging) = self.staging else {
            return Ok(());
        };
        apply_injected_fault(&self.target)?;
        commit_uninterrupted(|| std::fs::rename(&content, &self.target))?;
        // The now empty staging folder is removed when dropped here.
        drop(staging);
        Ok(())
    }
}

/// A name in the target's folder that is never a real output (the staging folder is created
/// beside it and never renamed to it).
fn staging_target(target: &Path) -> PathBuf {
    let folder = match target.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    folder.join(".tvf-staged-file")
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    #[test]
    fn the_file_appears_at_the_commit_and_not_without_it() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("x.bin");
        std::fs::write(&target, b"old").unwrap();
        let staged = StagedFile::new(&target).unwrap();
        super::super::write_atomically(&staged.path(), |w| w.write_all(b"new")).unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        drop(staged);
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "no temporary"
        );

        let staged = StagedFile::new(&target).unwrap();
        super::super::write_atomically(&staged.path(), |w| w.write_all(b"new")).unwrap();
        staged.commit().unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "no temporary"
        );
    }

    #[test]
    fn a_folder_is_not_a_file_target() {
        let dir = tempfile::tempdir().unwrap();
        let error = StagedFile::new(dir.path()).unwrap_err();
        assert!(error.to_string().contains("is a folder"), "{error}");
    }
}
