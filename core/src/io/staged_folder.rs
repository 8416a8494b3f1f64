//! [`StagedFolder`]: a folder output that appears whole or not at all. Its files are written
//! into a temporary sibling folder (`.tvf-folder-*.tmp`, same file system) and moved into place
//! by [`StagedFolder::commit`] once every file is complete; dropping it uncommitted (an error
//! half-way) removes the temporary folder and leaves the target as it was.
//!
//! A target that does not exist (or is an empty folder) is replaced by one rename. Into an
//! existing folder with other files, the new files are renamed one by one (renames need no
//! space, so a full disk fails while staging, before anything moved); other files stay.

use std::path::{Path, PathBuf};

use super::output_path::through_links;

use super::temporaries::{
    commit_uninterrupted, create_registered, sweep_stale_temporaries, Registration,
    TEMPORARY_FOLDER_PREFIX, TEMPORARY_SUFFIX,
};

/// A folder being written; see the [module](self).
#[derive(Debug)]
pub struct StagedFolder {
    target: PathBuf,
    staging: Option<tempfile::TempDir>,
    _registration: Registration,
}

impl StagedFolder {
    /// Starts writing the folder `target`. Its parent folder must exist (tvf never creates a
    /// missing parent); `target` must be a folder if it exists.
    pub fn new(target: &Path) -> std::io::Result<Self> {
        let target = &through_links(target);
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        if !parent.is_dir() {
            return Err(std::io::Error::new(
                std::io::ErrorKind::NotFound,
                format!("the folder {} does not exist", parent.display()),
            ));
        }
        if target.exists() && !target.is_dir() {
            return Err(std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                format!("{} exists and is not a folder", target.display()),
            ));
        }
        sweep_stale_temporaries(parent);
        let mut builder = tempfile::Builder::new();
        builder
            .prefix(TEMPORARY_FOLDER_PREFIX)
            .suffix(TEMPORARY_SUFFIX);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            // mkdir(2) applies the umask, as for create_dir: an ordinary folder once renamed.
            builder.permissions(std::fs::Permissions::from_mode(0o777));
        }
        let (staging, registration) =
            create_registered(|| builder.tempdir_in(parent), |s| s.path().to_path_buf())?;
        Ok(Self {
            target: target.to_path_buf(),
            staging: Some(staging),
            _registration: registration,
        })
    }

    /// Where the files go until [`commit`](Self::commit).
    pub fn path(&self) -> &Path {
        match &self.staging {
            Some(s) => s.path(),
            None => &self.target,
        }
    }

    /// The folder the files end up in.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Moves the complete folder into place (uninterrupted, see
    /// [`super::temporaries::commit_uninterrupted`]: into an existing folder every file moves).
    pub fn commit(mut self) -> std::io::Result<()> {
        let Some(staging) = self.staging.take() else {
            return Ok(());
        };
        commit_uninterrupted(|| self.move_into_place(staging))
    }

    /// The renames of [`commit`](Self::commit).
    fn move_into_place(&self, staging: tempfile::TempDir) -> std::io::Result<()> {
        let empty_target = std::fs::read_dir(&self.target)
            .map(|mut entries| entries.next().is_none())
            .unwrap_or(false);
        if !self.target.exists() || empty_target {
            if empty_target {
                std::fs::remove_dir(&self.target)?;
            }
            let kept = staging.keep();
            return std::fs::rename(&kept, &self.target).inspect_err(|_| {
                let _ = std::fs::remove_dir_all(&kept);
            });
        }
        for entry in std::fs::read_dir(staging.path())? {
            let entry = entry?;
            std::fs::rename(entry.path(), self.target.join(entry.file_name()))?;
        }
        // `staging` (now empty) is removed when dropped here.
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_committed_folder_appears_whole_and_an_abandoned_one_not_at_all() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out");
        let staged = StagedFolder::new(&target).unwrap();
        std::fs::write(staged.path().join("a.npy"), b"a").unwrap();
        assert!(!target.exists(), "nothing appears before the commit");
        drop(staged);
        assert!(!target.exists());
        assert_eq!(names(dir.path()), Vec::<String>::new(), "no temporary left");

        let staged = StagedFolder::new(&target).unwrap();
        std::fs::write(staged.path().join("a.npy"), b"a").unwrap();
        std::fs::write(staged.path().join("b.npy"), b"b").unwrap();
        staged.commit().unwrap();
        assert_eq!(names(&target), ["a.npy", "b.npy"]);
        assert_eq!(names(dir.path()), ["out"]);

        // Into an existing folder: new files replace old ones, other files stay.
        std::fs::write(target.join("notes.txt"), b"mine").unwrap();
        let staged = StagedFolder::new(&target).unwrap();
        std::fs::write(staged.path().join("a.npy"), b"new").unwrap();
        staged.commit().unwrap();
        assert_eq!(names(&target), ["a.npy", "b.npy", "notes.txt"]);
        assert_eq!(std::fs::read(target.join("a.npy")).unwrap(), b"new");
        assert_eq!(names(dir.path()), ["out"]);
    }

    #[test]
    fn a_missing_parent_or_a_file_in_the_way_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let error = StagedFolder::new(&dir.path().join("no/out")).unwrap_err();
        assert!(error.to_string().contains("does not exist"), "{error}");
        let file = dir.path().join("file");
        std::fs::write(&file, b"x").unwrap();
        assert!(StagedFolder::new(&file).is_err());
    }
}
