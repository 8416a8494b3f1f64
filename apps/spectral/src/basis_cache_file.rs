//! The files of a basis cache folder ([`crate::BasisStore`]), read and written so that whoever
//! else can write to the folder cannot redirect them: the names are predictable (fingerprint,
//! id, matrix hash, size), so another user could plant a symbolic link, a FIFO or a forged file
//! under the name of your next basis.
//!
//! A cache file is opened without following a link and without waiting on a FIFO
//! ([`open_cache_file`]); only a regular file owned by the user running the program is read.
//! A new basis is written into a private temporary folder inside the cache folder and renamed
//! onto its name ([`put_cache_file`]): a rename replaces whatever was there (a link, a FIFO,
//! another user's file) instead of writing through it.

use std::fs::File;
use std::path::{Path, PathBuf};
use tvf_core::io::temporaries::{
    commit_uninterrupted, create_registered, TEMPORARY_FOLDER_PREFIX, TEMPORARY_SUFFIX,
};

/// What is under a cache file's name.
#[derive(Debug)]
pub(crate) enum CacheEntry {
    /// Nothing.
    Missing,
    /// A regular file of the user, opened for reading.
    Usable(File),
    /// Something not to be read, and why (it is replaced when the basis is saved).
    Unusable(String),
}

/// Opens the cache file `path` for reading: without following a symbolic link, without
/// waiting on a FIFO, and only if it is a regular file that belongs to the user running the
/// program.
pub(crate) fn open_cache_file(path: &Path) -> CacheEntry {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK);
    }
    #[cfg(not(unix))]
    if std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink()) {
        return CacheEntry::Unusable(LINK.into());
    }
    let file = match options.open(path) {
        Ok(file) => file,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return CacheEntry::Missing,
        Err(e) if is_link_error(&e) => return CacheEntry::Unusable(LINK.into()),
        Err(e) => return CacheEntry::Unusable(e.to_string()),
    };
    let metadata = match file.metadata() {
        Ok(metadata) => metadata,
        Err(e) => return CacheEntry::Unusable(e.to_string()),
    };
    if !metadata.is_file() {
        return CacheEntry::Unusable(
            "not a regular file (a FIFO, a device or a folder); not read".into(),
        );
    }
    match foreign_owner(&metadata) {
        Some(problem) => CacheEntry::Unusable(problem),
        None => CacheEntry::Usable(file),
    }
}

const LINK: &str =
    "a symbolic link (someone may want tvf to read or write elsewhere); not followed";

/// Whether `error` is the one `open` gives for a link under `O_NOFOLLOW` (`ELOOP`).
fn is_link_error(error: &std::io::Error) -> bool {
    #[cfg(unix)]
    {
        error.raw_os_error() == Some(libc::ELOOP)
    }
    #[cfg(not(unix))]
    {
        let _ = error;
        false
    }
}

/// On Unix: why a file of another user is not read (`None` for the user's own files).
#[cfg(unix)]
fn foreign_owner(metadata: &std::fs::Metadata) -> Option<String> {
    use std::os::unix::fs::MetadataExt;
    // SAFETY: geteuid has no preconditions and cannot fail.
    let me = unsafe { libc::geteuid() };
    (metadata.uid() != me).then(|| {
        format!(
            "it belongs to another user (uid {}, tvf runs as uid {me}); not read",
            metadata.uid()
        )
    })
}

/// Elsewhere files carry no Unix owner: the folder's checks are all there is.
#[cfg(not(unix))]
fn foreign_owner(_metadata: &std::fs::Metadata) -> Option<String> {
    None
}

/// Writes the cache file `path` (in `folder`): `write` fills a file of that name in a private
/// temporary folder inside `folder`, which is then renamed onto `path`, replacing whatever was
/// there. Returns `path`, or why it could not be written (`write`'s error or the file
/// system's).
pub(crate) fn put_cache_file(
    folder: &Path,
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<PathBuf, String> {
    let name = path
        .file_name()
        .ok_or_else(|| format!("{}: not a file name", path.display()))?;
    // Created with mode 0700 by an exclusive mkdir: nobody else can put anything inside.
    let (staging, _registration) = create_registered(
        || {
            tempfile::Builder::new()
                .prefix(TEMPORARY_FOLDER_PREFIX)
                .suffix(TEMPORARY_SUFFIX)
                .tempdir_in(folder)
        },
        |s| s.path().to_path_buf(),
    )
    .map_err(|e| format!("{}: {e}", folder.display()))?;
    let staged = staging.path().join(name);
    write(&staged)?;
    commit_uninterrupted(|| std::fs::rename(&staged, path))
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_and_own_files_are_told_apart() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.tvfb");
        assert!(matches!(open_cache_file(&path), CacheEntry::Missing));
        std::fs::write(&path, b"x").unwrap();
        assert!(matches!(open_cache_file(&path), CacheEntry::Usable(_)));
        let entry = open_cache_file(dir.path());
        assert!(matches!(entry, CacheEntry::Unusable(ref p) if p.contains("not a regular")));
    }

    /// Links, FIFOs and other users' files are refused without being followed, read or waited
    /// on; a new file replaces them by rename, and the files they pointed to stay as they were.
    #[cfg(unix)]
    #[test]
    fn planted_entries_are_refused_and_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let victim = dir.path().join("victim");
        std::fs::write(&victim, b"mine").unwrap();
        let cache = dir.path().join("cache");
        std::fs::create_dir(&cache).unwrap();
        let link = cache.join("link.tvfb");
        std::os::unix::fs::symlink(&victim, &link).unwrap();
        let zero = cache.join("zero.tvfb");
        std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
        let fifo = cache.join("fifo.tvfb");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        assert!(made.unwrap().success());
        for (path, said) in [
            (&link, "symbolic link"),
            (&zero, "symbolic link"),
            (&fifo, "regular"),
        ] {
            match open_cache_file(path) {
                CacheEntry::Unusable(problem) => assert!(problem.contains(said), "{problem}"),
                other => panic!("{}: {other:?}", path.display()),
            }
            let written = put_cache_file(&cache, path, |staged| {
                std::fs::write(staged, b"basis").map_err(|e| e.to_string())
            });
            assert_eq!(written.unwrap(), *path);
            assert_eq!(std::fs::read(path).unwrap(), b"basis");
            assert!(matches!(open_cache_file(path), CacheEntry::Usable(_)));
        }
        assert_eq!(std::fs::read(&victim).unwrap(), b"mine");
        // Nothing is left of the staging folders.
        assert_eq!(std::fs::read_dir(&cache).unwrap().count(), 3);
        // A file of another user (made so by chown, as root) is not read.
        let other = cache.join("other.tvfb");
        std::fs::write(&other, b"forged").unwrap();
        if std::process::Command::new("chown")
            .arg("12345")
            .arg(&other)
            .status()
            .is_ok_and(|s| s.success())
        {
            let entry = open_cache_file(&other);
            assert!(matches!(entry, CacheEntry::Unusable(ref p) if p.contains("another user")));
        }
    }
}
