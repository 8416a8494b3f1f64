//! One file of a folder output ([`tvf_core::io::StagedFolder`]: written into a temporary sibling,
//! moved into place whole): [`write_folder_file`], and [`FolderFileError`], which names the file
//! where it will appear, not where it is staged; [`FieldFolderError`] for a folder of field
//! arrays, whose fields are sampled at the faces first.

use std::error::Error as StdError;
use std::path::PathBuf;
use thiserror::Error;
use tvf_core::discretization::DiscretizationError;
use tvf_core::io::{write_atomically, AtomicWriter, StagedFolder};

/// A file of a folder output could not be written; `path` is the file in the output folder.
#[derive(Debug, Error)]
#[error("cannot write {}: {source}", path.display())]
pub struct FolderFileError {
    /// The file, in the folder it was to appear in.
    pub path: PathBuf,
    /// Why (an I/O error, or the error of the writer that made the file).
    #[source]
    pub source: Box<dyn StdError + Send + Sync>,
}

impl FolderFileError {
    /// The error of the file `name` of `folder`, caused by `source`.
    pub fn new(
        folder: &StagedFolder,
        name: &str,
        source: impl Into<Box<dyn StdError + Send + Sync>>,
    ) -> Self {
        Self {
            path: folder.target().join(name),
            source: source.into(),
        }
    }
}

/// Why a folder of field arrays could not be written.
#[derive(Debug, Error)]
pub enum FieldFolderError {
    /// A file could not be written.
    #[error(transparent)]
    Write(#[from] FolderFileError),
    /// A field could not be sampled at the face centroids.
    #[error(transparent)]
    Sampling(#[from] DiscretizationError),
}

/// Writes the file `name` of the staged `folder` atomically ([`write_atomically`]) with `fill`.
pub fn write_folder_file(
    folder: &StagedFolder,
    name: &str,
    fill: impl FnOnce(&mut AtomicWriter<'_>) -> std::io::Result<()>,
) -> Result<(), FolderFileError> {
    write_atomically(&folder.path().join(name), fill)
        .map_err(|e| FolderFileError::new(folder, name, e))
}

/// Writes `bytes` as the file `name` of the staged `folder`.
pub fn write_folder_bytes(
    folder: &StagedFolder,
    name: &str,
    bytes: &[u8],
) -> Result<(), FolderFileError> {
    write_folder_file(folder, name, |w| std::io::Write::write_all(w, bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_appear_at_commit_and_errors_name_the_final_file() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let folder = StagedFolder::new(&out).unwrap();
        write_folder_bytes(&folder, "a.txt", b"hello").unwrap();
        assert!(!out.join("a.txt").exists());
        // A file inside a missing sub-folder cannot be written: the error names the output.
        let error = write_folder_bytes(&folder, "missing/b.txt", b"x").unwrap_err();
        assert_eq!(error.path, out.join("missing/b.txt"));
        assert!(
            error.to_string().starts_with(&format!(
                "cannot write {}",
                out.join("missing/b.txt").display()
            )),
            "{error}"
        );
        folder.commit().unwrap();
        assert_eq!(std::fs::read(out.join("a.txt")).unwrap(), b"hello");
    }
}
