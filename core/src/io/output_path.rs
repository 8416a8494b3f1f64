//! [`check_output`]: the rules every output path of tvf follows, checked before anything is
//! computed: its folder must exist (tvf never creates a missing parent folder), and it must not
//! be one of the command's inputs (writing it would destroy the input).

use std::path::{Path, PathBuf};
use thiserror::Error;

/// An output path that breaks a rule of [`check_output`].
#[derive(Debug, Error, PartialEq, Eq)]
pub enum OutputPathError {
    /// The folder the output would go into does not exist.
    #[error("cannot write {output}: the folder {folder} does not exist (create it first)")]
    MissingFolder {
        /// The output.
        output: PathBuf,
        /// Its missing parent folder.
        folder: PathBuf,
    },
    /// The output is one of the inputs.
    #[error("cannot write {output}: it is also an input of this command (choose another output)")]
    IsAnInput {
        /// The output.
        output: PathBuf,
    },
    /// A file output names an existing folder.
    #[error("cannot write {output}: it is a folder; give the name of a file to write")]
    IsAFolder {
        /// The output.
        output: PathBuf,
    },
}

/// Checks that `output` (a file or a folder to write) can be written without surprises: its
/// parent folder exists (for a symbolic link: its target's), and it is not the same file or
/// folder as any of `inputs` (compared after resolving links and relative paths).
pub fn check_output(output: &Path, inputs: &[&Path]) -> Result<(), OutputPathError> {
    // A link is written through: the folder of its target must exist.
    let written = through_links(output);
    let folder = match written.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !folder.is_dir() {
        return Err(OutputPathError::MissingFolder {
            output: output.to_path_buf(),
            folder: folder.to_path_buf(),
        });
    }
    if let Ok(resolved) = output.canonicalize() {
        if inputs
            .iter()
            .any(|input| input.canonicalize().is_ok_and(|i| i == resolved))
        {
            return Err(OutputPathError::IsAnInput {
                output: output.to_path_buf(),
            });
        }
    }
    Ok(())
}

/// [`check_output`] for an output that is one file: moreover it must not be an existing folder
/// (after following links), which the write would only find out at the end.
pub fn check_file_output(output: &Path, inputs: &[&Path]) -> Result<(), OutputPathError> {
    check_output(output, inputs)?;
    if std::fs::metadata(output).is_ok_and(|m| m.is_dir()) {
        return Err(OutputPathError::IsAFolder {
            output: output.to_path_buf(),
        });
    }
    Ok(())
}

/// The path an output at `path` is written to: `path` itself, or for a symbolic link the path
/// it points to (following a chain of links), so the link stays a link and its target gets the
/// content. A link that points nowhere yet gives the path where its target would be.
pub(crate) fn through_links(path: &Path) -> PathBuf {
    /// Links followed at most (a loop of links stops here).
    const MAX_LINKS: usize = 40;
    let mut path = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        let is_link = std::fs::symlink_metadata(&path).is_ok_and(|m| m.file_type().is_symlink());
        let Some(target) = is_link.then(|| std::fs::read_link(&path).ok()).flatten() else {
            break;
        };
        path = match path.parent() {
            Some(parent) => parent.join(target),
            None => target,
        };
    }
    path
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_folders_and_inputs_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let mesh = dir.path().join("m.obj");
        std::fs::write(&mesh, b"v 0 0 0").unwrap();
        assert_eq!(check_output(&dir.path().join("out.png"), &[&mesh]), Ok(()));
        let missing = dir.path().join("no/out.png");
        let error = check_output(&missing, &[]).unwrap_err();
        assert!(error.to_string().contains("out.png"), "{error}");
        assert!(matches!(error, OutputPathError::MissingFolder { .. }));
        let same = dir.path().join("sub/../m.obj");
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        assert_eq!(
            check_output(&same, &[&mesh]),
            Err(OutputPathError::IsAnInput {
                output: same.clone()
            })
        );
        // A bare file name goes into the current folder, which exists.
        assert_eq!(check_output(Path::new("plain.png"), &[]), Ok(()));
        // A folder is a folder output's target, but never a file output's.
        assert_eq!(check_output(dir.path(), &[]), Ok(()));
        assert_eq!(
            check_file_output(dir.path(), &[]),
            Err(OutputPathError::IsAFolder {
                output: dir.path().to_path_buf()
            })
        );
        assert!(check_file_output(&missing, &[]).is_err());
    }

    #[cfg(unix)]
    #[test]
    fn links_are_followed_to_their_targets() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::create_dir(d.join("data")).unwrap();
        std::os::unix::fs::symlink("data/real.npy", d.join("link.npy")).unwrap();
        std::os::unix::fs::symlink("link.npy", d.join("chain.npy")).unwrap();
        assert_eq!(through_links(&d.join("chain.npy")), d.join("data/real.npy"));
        assert_eq!(through_links(&d.join("plain.npy")), d.join("plain.npy"));
        std::os::unix::fs::symlink("loop", d.join("loop")).unwrap();
        assert_eq!(through_links(&d.join("loop")), d.join("loop"));
    }
}
