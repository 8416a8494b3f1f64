//! Which folder a program keeps its computed bases in ([`BasisCache::choose`]) and whether that
//! folder is safe to use ([`BasisCache::store`]): none when the user turns the cache off, a
//! folder the user chose, else the platform's cache folder ([`user_cache_folder_from`]) — never
//! a folder inside the user's data set.
//!
//! Whoever can write to a cache folder can plant files under the predictable names of the next
//! bases (fingerprint, id, matrix hash, size): a symbolic link that redirects the write, a FIFO
//! that blocks the read, a forged basis that is read as yours. So every cache folder, the
//! default one and one chosen with `--cache-dir` or `$TVF_CACHE_DIR` alike, is created private
//! (`0700` on Unix) when missing and used only if it is a folder that belongs to the user
//! running the program and that not everyone may write to ([`check_cache_folder`]); the
//! default one must moreover not be a symbolic link (its fixed name could have been planted; a
//! chosen one is the user's word and is followed). The files inside get their own checks
//! (`basis_cache_file.rs`). Where owners cannot be checked (not Unix), a chosen folder is used
//! with a warning saying so.

use crate::{BasisMessage, BasisStore};
use std::path::{Path, PathBuf};

/// Where computed bases are kept.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum BasisCache {
    /// Nowhere: compute every time.
    Off,
    /// A folder the user chose (`--cache-dir`, `$TVF_CACHE_DIR`): links followed, then checked
    /// like a default one.
    Chosen(PathBuf),
    /// The folder the program picked (the platform's cache folder): created private and used
    /// only if safe, and never through a link.
    Default(PathBuf),
}

impl BasisCache {
    /// The cache of a program: [`BasisCache::Off`] if `off`; the folder `chosen` by the user (a
    /// flag, an environment variable); else `user_folder()`, the platform's cache folder
    /// ([`user_cache_folder_from`]).
    pub fn choose(
        off: bool,
        chosen: Option<PathBuf>,
        user_folder: impl FnOnce() -> PathBuf,
    ) -> Self {
        match (off, chosen) {
            (true, _) => BasisCache::Off,
            (false, Some(folder)) => BasisCache::Chosen(folder),
            (false, None) => BasisCache::Default(user_folder()),
        }
    }

    /// The store of the cache (`None` for [`BasisCache::Off`], or when the folder is not safe
    /// to use: then the basis is computed without the cache) and what to tell the user: why a
    /// folder is not used, or that a chosen one could not be checked.
    pub fn store(&self) -> (Option<BasisStore>, Vec<BasisMessage>) {
        let (folder, follow_links) = match self {
            BasisCache::Off => return (None, Vec::new()),
            BasisCache::Chosen(folder) => (folder, true),
            BasisCache::Default(folder) => (folder, false),
        };
        match check_cache_folder(folder, follow_links) {
            Ok(FolderCheck::Checked) => (Some(BasisStore::new(folder)), Vec::new()),
            Ok(FolderCheck::OwnerUnknown) => (
                Some(BasisStore::new(folder)),
                vec![BasisMessage::Warning(format!(
                    "the basis cache {}: who may write to it cannot be checked on this system; \
                     anyone who can may plant bases tvf will read as yours",
                    folder.display()
                ))],
            ),
            Err(problem) => (
                None,
                vec![BasisMessage::Warning(format!(
                    "not using the basis cache {}: {problem}; computing without it (a cache \
                     folder must be yours and not writable by everyone)",
                    folder.display()
                ))],
            ),
        }
    }
}

/// What [`check_cache_folder`] could establish.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FolderCheck {
    /// The folder belongs to the user and not everyone may write to it.
    Checked,
    /// The folder exists, but this system has no owners and modes to check.
    OwnerUnknown,
}

/// The default cache folder from the values of `XDG_CACHE_HOME`, `HOME`, `LOCALAPPDATA` and the
/// user name (relative paths are ignored, as the XDG specification asks):
/// `$XDG_CACHE_HOME/tvf`, else `~/.cache/tvf` on Unix and `%LOCALAPPDATA%\tvf` on Windows, else
/// `tvf-cache-USER` in the temporary folder.
pub fn user_cache_folder_from(
    xdg_cache_home: Option<PathBuf>,
    home: Option<PathBuf>,
    local_app_data: Option<PathBuf>,
    user: Option<PathBuf>,
) -> PathBuf {
    let absolute = |p: Option<PathBuf>| p.filter(|p| p.is_absolute());
    if let Some(folder) = absolute(xdg_cache_home) {
        return folder.join("tvf");
    }
    if cfg!(unix) {
        if let Some(home) = absolute(home) {
            return home.join(".cache").join("tvf");
        }
    } else if let Some(folder) = absolute(local_app_data) {
        return folder.join("tvf");
    }
    let user = user.map_or("user".into(), |u| u.to_string_lossy().into_owned());
    std::env::temp_dir().join(format!("tvf-cache-{user}"))
}

/// Makes `folder` ready as a default cache folder ([`check_cache_folder`] without following a
/// link).
pub fn prepare_private_folder(folder: &Path) -> Result<(), String> {
    check_cache_folder(folder, false).map(drop)
}

/// Makes `folder` ready as a cache folder: creates it private if it is missing (its parents
/// with ordinary permissions), and refuses one that is not a folder, belongs to another user
/// or may be written by everyone; a symbolic link is refused unless `follow_links` (then the
/// folder it leads to is checked). The error says which.
pub fn check_cache_folder(folder: &Path, follow_links: bool) -> Result<FolderCheck, String> {
    if std::fs::symlink_metadata(folder).is_err() {
        create_private(folder)?;
    }
    let metadata = std::fs::symlink_metadata(folder).map_err(|e| e.to_string())?;
    let metadata = match (metadata.file_type().is_symlink(), follow_links) {
        (true, false) => {
            return Err("it is a symbolic link (someone may want tvf's writes elsewhere)".into())
        }
        (true, true) => std::fs::metadata(folder).map_err(|e| format!("its link: {e}"))?,
        (false, _) => metadata,
    };
    if !metadata.is_dir() {
        return Err("it is not a folder".into());
    }
    check_owner(&metadata)
}

/// Creates `folder` with mode `0700` (its missing parents with ordinary permissions); one made
/// at the same time by another process is left to the checks that follow.
fn create_private(folder: &Path) -> Result<(), String> {
    if let Some(parent) = folder.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .map_err(|e| format!("cannot create {}: {e}", parent.display()))?;
    }
    let mut builder = std::fs::DirBuilder::new();
    #[cfg(unix)]
    {
        use std::os::unix::fs::DirBuilderExt;
        builder.mode(0o700);
    }
    match builder.create(folder) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(()),
        Err(e) => Err(format!("cannot create it: {e}")),
    }
}

/// On Unix: the folder belongs to the user running the program and is not writable by
/// everyone.
#[cfg(unix)]
fn check_owner(metadata: &std::fs::Metadata) -> Result<FolderCheck, String> {
    use std::os::unix::fs::MetadataExt;
    // SAFETY: geteuid has no preconditions and cannot fail.
    let me = unsafe { libc::geteuid() };
    owner_problem(metadata.uid(), metadata.mode(), me).map_or(Ok(FolderCheck::Checked), Err)
}

/// Elsewhere a folder carries no Unix owner and mode.
#[cfg(not(unix))]
fn check_owner(_metadata: &std::fs::Metadata) -> Result<FolderCheck, String> {
    Ok(FolderCheck::OwnerUnknown)
}

/// What is wrong with a folder of owner `owner` and mode `mode` for the user `me`, if anything
/// (a plain function, so that its rules are tested on every platform).
#[cfg_attr(not(unix), allow(dead_code))]
fn owner_problem(owner: u32, mode: u32, me: u32) -> Option<String> {
    if owner != me {
        return Some(format!(
            "it belongs to another user (uid {owner}, tvf runs as uid {me})"
        ));
    }
    if mode & 0o002 != 0 {
        return Some(format!(
            "everyone may write to it (mode {:o})",
            mode & 0o7777
        ));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cache_is_off_chosen_or_the_users() {
        let user = || PathBuf::from("/home/a/.cache/tvf");
        let chosen = Some(PathBuf::from("mine"));
        assert_eq!(
            BasisCache::choose(true, chosen.clone(), user),
            BasisCache::Off
        );
        assert_eq!(
            BasisCache::choose(false, chosen, user),
            BasisCache::Chosen("mine".into())
        );
        assert_eq!(
            BasisCache::choose(false, None, user),
            BasisCache::Default(user())
        );
    }

    #[test]
    fn the_user_cache_folder_follows_xdg_then_home() {
        let p = |s: &str| Some(PathBuf::from(s));
        assert_eq!(
            user_cache_folder_from(p("/x/cache"), p("/home/a"), None, None),
            PathBuf::from("/x/cache/tvf")
        );
        // A relative XDG_CACHE_HOME is ignored.
        let fallback = user_cache_folder_from(p("rel"), p("/home/a"), p("/appdata"), p("a"));
        if cfg!(unix) {
            assert_eq!(fallback, PathBuf::from("/home/a/.cache/tvf"));
        } else {
            assert_eq!(fallback, PathBuf::from("/appdata/tvf"));
        }
        assert_eq!(
            user_cache_folder_from(None, None, None, p("a")),
            std::env::temp_dir().join("tvf-cache-a")
        );
    }

    #[test]
    fn owners_and_modes_are_judged() {
        assert_eq!(owner_problem(1000, 0o40700, 1000), None);
        assert_eq!(owner_problem(1000, 0o40775, 1000), None);
        assert!(owner_problem(1001, 0o40700, 1000)
            .unwrap()
            .contains("another user"));
        assert!(owner_problem(1000, 0o41777, 1000)
            .unwrap()
            .contains("everyone"));
    }

    #[test]
    fn a_missing_folder_is_created_private_and_a_default_link_refused() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join("deep/cache/tvf");
        prepare_private_folder(&folder).unwrap();
        assert!(folder.is_dir());
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&folder).unwrap().permissions().mode();
            assert_eq!(mode & 0o777, 0o700, "{mode:o}");
            let link = dir.path().join("link");
            std::os::unix::fs::symlink(&folder, &link).unwrap();
            let problem = prepare_private_folder(&link).unwrap_err();
            assert!(problem.contains("symbolic link"), "{problem}");
            // A chosen folder is the user's word: its link is followed, the folder checked.
            assert_eq!(check_cache_folder(&link, true), Ok(FolderCheck::Checked));
        }
        let file = dir.path().join("file");
        std::fs::write(&file, b"x").unwrap();
        assert!(prepare_private_folder(&file)
            .unwrap_err()
            .contains("not a folder"));
    }

    /// A chosen folder gets the checks of the default one: one everyone may write to (a team
    /// folder of mode 0777 or 1777) is not used, with a warning that says why.
    #[cfg(unix)]
    #[test]
    fn a_chosen_folder_everyone_may_write_to_is_not_used() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        for mode in [0o777, 0o1777] {
            let shared = dir.path().join(format!("shared-{mode:o}"));
            std::fs::create_dir(&shared).unwrap();
            std::fs::set_permissions(&shared, std::fs::Permissions::from_mode(mode)).unwrap();
            let (store, messages) = BasisCache::Chosen(shared).store();
            assert!(store.is_none());
            let [BasisMessage::Warning(warning)] = &messages[..] else {
                panic!("{messages:?}");
            };
            assert!(warning.contains("everyone may write to it"), "{warning}");
        }
        let mine = dir.path().join("mine");
        let (store, messages) = BasisCache::Chosen(mine.clone()).store();
        assert_eq!(
            (store, messages),
            (Some(BasisStore::new(&mine)), Vec::new())
        );
        let mode = std::fs::metadata(&mine).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o700, "{mode:o}");
    }
}
