//! Where computed bases are cached by default, and why tvf can trust such a folder.
//!
//! A cache folder tvf picks itself could be prepared by someone else: a fixed name in a shared
//! folder (`/tmp/…`, a mesh in `/tmp`) can be a symbolic link planted by another user, which
//! would redirect tvf's writes, or a folder of theirs holding a forged basis that tvf would
//! use. So a default folder is created private (`0700` on Unix) and used only if it is a real
//! folder (not a link), owned by the user running tvf, and not writable by everyone; otherwise
//! tvf warns and computes without the cache. A folder chosen with `--cache-dir` or
//! `$TVF_CACHE_DIR` is used as given.
//!
//! Built-in `--example` meshes (no file to sit next to) are cached in the user's cache folder:
//! `$XDG_CACHE_HOME/tvf`, else `~/.cache/tvf` on Unix and `%LOCALAPPDATA%\tvf` on Windows, else
//! `tvf-cache-USER` in the temporary folder.

use std::path::{Path, PathBuf};

/// The default cache folder for built-in example meshes (see the [module](self)).
pub fn user_cache_folder() -> PathBuf {
    let variable = |name| std::env::var_os(name).map(PathBuf::from);
    user_cache_folder_from(
        variable("XDG_CACHE_HOME"),
        variable("HOME"),
        variable("LOCALAPPDATA"),
        variable("USER").or_else(|| variable("USERNAME")),
    )
}

/// [`user_cache_folder`] from the values of `XDG_CACHE_HOME`, `HOME`, `LOCALAPPDATA` and the
/// user name (relative paths are ignored, as the XDG specification asks).
fn user_cache_folder_from(
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

/// Makes `folder` ready as a default cache folder: creates it private if it is missing (its
/// parents with ordinary permissions), and refuses one that is a symbolic link, not a folder,
/// owned by another user or writable by everyone. The error says which.
pub fn prepare_private_folder(folder: &Path) -> Result<(), String> {
    if std::fs::symlink_metadata(folder).is_err() {
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
            Ok(()) => {}
            // Made by a process running at the same time: checked below like any other.
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
            Err(e) => return Err(format!("cannot create it: {e}")),
        }
    }
    let metadata = std::fs::symlink_metadata(folder).map_err(|e| e.to_string())?;
    if metadata.file_type().is_symlink() {
        return Err("it is a symbolic link (someone may want tvf's writes elsewhere)".into());
    }
    if !metadata.is_dir() {
        return Err("it is not a folder".into());
    }
    check_owner(&metadata)
}

/// On Unix: the folder belongs to the user running tvf and is not writable by everyone.
#[cfg(unix)]
fn check_owner(metadata: &std::fs::Metadata) -> Result<(), String> {
    use std::os::unix::fs::MetadataExt;
    // SAFETY: geteuid has no preconditions and cannot fail.
    let me = unsafe { libc::geteuid() };
    owner_problem(metadata.uid(), metadata.mode(), me).map_or(Ok(()), Err)
}

/// Elsewhere the folder's permissions are the user profile's: nothing more to check.
#[cfg(not(unix))]
fn check_owner(_metadata: &std::fs::Metadata) -> Result<(), String> {
    Ok(())
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
    fn a_missing_folder_is_created_private_and_a_link_refused() {
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
        }
        let file = dir.path().join("file");
        std::fs::write(&file, b"x").unwrap();
        assert!(prepare_private_folder(&file)
            .unwrap_err()
            .contains("not a folder"));
    }
}
