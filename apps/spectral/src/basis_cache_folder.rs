//! Which folder a program keeps its computed bases in ([`BasisCache::choose`]): none when the
//! user turns the cache off, a folder the user chose, else a default one next to the mesh file
//! (or, for a mesh without a file, the user's cache folder, [`crate::user_cache_folder_from`]).

use crate::BasisCache;
use std::path::{Path, PathBuf};

/// The name of the default cache folder next to a mesh file.
pub const MESH_CACHE_FOLDER: &str = ".tvf-cache";

impl BasisCache {
    /// The cache of a program: [`BasisCache::Off`] if `off`; the folder `chosen` by the user (a
    /// flag, an environment variable) as given; else a default folder, checked before use
    /// ([`BasisCache::Default`]): [`MESH_CACHE_FOLDER`] next to `mesh_file` (in the current
    /// folder for a bare file name) or, without a mesh file, `user_folder()`.
    pub fn choose(
        off: bool,
        chosen: Option<PathBuf>,
        mesh_file: Option<&Path>,
        user_folder: impl FnOnce() -> PathBuf,
    ) -> Self {
        if off {
            return BasisCache::Off;
        }
        if let Some(folder) = chosen {
            return BasisCache::Chosen(folder);
        }
        BasisCache::Default(match mesh_file {
            Some(path) => path
                .parent()
                .filter(|p| !p.as_os_str().is_empty())
                .unwrap_or(Path::new("."))
                .join(MESH_CACHE_FOLDER),
            None => user_folder(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cache_is_off_chosen_or_next_to_the_mesh() {
        let user = || PathBuf::from("/home/a/.cache/tvf");
        let mesh = Some(Path::new("meshes/bunny.obj"));
        let chosen = Some(PathBuf::from("mine"));
        assert_eq!(
            BasisCache::choose(true, chosen.clone(), mesh, user),
            BasisCache::Off
        );
        assert_eq!(
            BasisCache::choose(false, chosen, mesh, user),
            BasisCache::Chosen("mine".into())
        );
        assert_eq!(
            BasisCache::choose(false, None, mesh, user),
            BasisCache::Default("meshes/.tvf-cache".into())
        );
        assert_eq!(
            BasisCache::choose(false, None, Some(Path::new("bunny.obj")), user),
            BasisCache::Default("./.tvf-cache".into())
        );
        assert_eq!(
            BasisCache::choose(false, None, None, user),
            BasisCache::Default(user())
        );
    }
}
