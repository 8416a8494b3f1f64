//! Resolving the spectral basis a program works with: a given basis file, checked against the
//! mesh and its discretization ([`open_checked_basis_file`]), or a basis of a requested size
//! read from or computed into a cache folder ([`BasisCache`], [`cached_or_computed_basis`]).
//! What happened is said by [`BasisMessage`]s the caller prints.
//!
//! A cache folder the program picks itself could be prepared by someone else: a fixed name in
//! a shared folder (`/tmp/…`) can be a symbolic link planted by another user, which would
//! redirect the writes, or a folder of theirs holding a forged basis. So a default folder
//! ([`BasisCache::Default`]) is created private (`0700` on Unix) and used only if it is a real
//! folder (not a link), owned by the user running the program, and not writable by everyone
//! ([`prepare_private_folder`]); a folder the user chose ([`BasisCache::Chosen`]) is used as
//! given.

use crate::{
    compute_basis_of_size, open_basis_file, open_basis_file_with, read_basis_header, BasisError,
    BasisFileUseError, BasisProgress, BasisSize, BasisStore, FieldFamily, SpectralBasis,
    StoredBasisOrigin,
};
use std::path::{Path, PathBuf};
use std::time::Instant;
use tvf_core::discretization::{BoundaryCondition, HodgeOperators};
use tvf_core::SurfaceMesh;
use tvf_discretizations::{BoxedComplex, Catalog};

/// Something to tell the user about a resolved basis (on stderr).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum BasisMessage {
    /// Information.
    Note(String),
    /// Something did not go as asked, and the basis was obtained another way.
    Warning(String),
}

/// A basis read from a file given by the user, with the discretization it belongs to.
pub struct BasisFromFile {
    /// The discretization (the file's, rebuilt through the catalog, or the one given).
    pub discretization: BoxedComplex,
    /// The basis.
    pub basis: SpectralBasis,
    /// Wall-clock seconds of the read.
    pub seconds: f64,
    /// The file's format version if it predates matrix hashes (1 or 2): then the basis was
    /// checked against its discretization's id and the mesh only.
    pub unchecked_version: Option<u32>,
}

/// Reads the basis file `path` for `mesh`: with `complex` given, checked against it (see
/// [`open_basis_file_with`]); else its discretization is rebuilt through `catalog` (`entry` and
/// `boundary` must match the file's, see [`open_basis_file`]).
pub fn open_checked_basis_file(
    catalog: &Catalog,
    path: &Path,
    mesh: &SurfaceMesh,
    entry: Option<&str>,
    boundary: Option<BoundaryCondition>,
    complex: Option<BoxedComplex>,
) -> Result<BasisFromFile, BasisFileUseError> {
    let start = Instant::now();
    let (discretization, basis) = match complex {
        Some(complex) => open_basis_file_with(path, mesh, complex)?,
        None => open_basis_file(catalog, path, mesh, entry, boundary)?,
    };
    let seconds = start.elapsed().as_secs_f64();
    let header = read_basis_header(path)?;
    Ok(BasisFromFile {
        discretization,
        basis,
        seconds,
        unchecked_version: header.key.matrix_hash.is_none().then_some(header.version),
    })
}

impl BasisFromFile {
    /// What to tell the user about the file `path` this basis was read from.
    pub fn messages(&self, path: &Path) -> Vec<BasisMessage> {
        let id = self.discretization.id();
        let mut messages = vec![BasisMessage::Note(format!(
            "using basis {} ({} fields, {id}, loaded in {:.2} s)",
            path.display(),
            self.basis.len(),
            self.seconds
        ))];
        if let Some(version) = self.unchecked_version {
            messages.push(BasisMessage::Note(format!(
                "{}: basis file format version {version} predates matrix hashes, so it cannot be \
                 checked against the matrices of {id} (only against its id and the mesh); \
                 recompute it with `tvf basis` to have it checked",
                path.display(),
            )));
        }
        messages
    }
}

/// Where computed bases are kept.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum BasisCache {
    /// Nowhere: compute every time.
    Off,
    /// A folder the user chose: used as given.
    Chosen(PathBuf),
    /// A folder the program picked: created private and used only if safe
    /// ([`prepare_private_folder`]).
    Default(PathBuf),
}

impl BasisCache {
    /// The store of the cache: `Ok(None)` for [`BasisCache::Off`], `Err` with a warning if a
    /// default folder is not safe to use (then the basis is computed without the cache).
    pub fn store(&self) -> Result<Option<BasisStore>, BasisMessage> {
        match self {
            BasisCache::Off => Ok(None),
            BasisCache::Chosen(folder) => Ok(Some(BasisStore::new(folder))),
            BasisCache::Default(folder) => match prepare_private_folder(folder) {
                Ok(()) => Ok(Some(BasisStore::new(folder))),
                Err(problem) => Err(BasisMessage::Warning(format!(
                    "not using the basis cache {}: {problem}; computing without it",
                    folder.display()
                ))),
            },
        }
    }
}

/// A basis from a cache, or computed, and where it came from.
pub struct CachedBasis {
    /// The basis.
    pub basis: SpectralBasis,
    /// Read from or computed into the store (`None`: computed without a store).
    pub origin: Option<StoredBasisOrigin>,
}

impl CachedBasis {
    /// What was computed ([`computed_basis_summary`]), unless the basis was read from the
    /// cache.
    pub fn computed_summary(&self, complex: &BoxedComplex, size: BasisSize) -> Option<String> {
        let read = matches!(self.origin, Some(StoredBasisOrigin::Read { .. }));
        (!read).then(|| computed_basis_summary(complex, size, &self.basis))
    }

    /// What to tell the user about the cache ([`cache_messages`]; nothing without a store).
    pub fn messages(&self, complex: &BoxedComplex) -> Vec<BasisMessage> {
        match &self.origin {
            Some(origin) => cache_messages(origin, &self.basis, complex),
            None => Vec::new(),
        }
    }
}

/// The basis of `size` for `complex` on `mesh`: from `store` if it holds a usable one, else
/// computed with seed 0 (reporting to `progress`) and saved there. The origin is `None` when
/// there is no store.
pub fn cached_or_computed_basis(
    store: Option<&BasisStore>,
    mesh: &SurfaceMesh,
    complex: &BoxedComplex,
    size: BasisSize,
    progress: Option<&dyn Fn(&BasisProgress)>,
) -> Result<CachedBasis, BasisError> {
    Ok(match store {
        Some(store) => {
            let (basis, origin) = store.basis(mesh, complex.as_ref(), size, progress)?;
            CachedBasis {
                basis,
                origin: Some(origin),
            }
        }
        None => CachedBasis {
            basis: compute_basis_of_size(complex.as_ref(), size, progress)?,
            origin: None,
        },
    })
}

/// What to tell the user about a basis of the cache: where it was read from, or why the cached
/// file was unusable and where the computed one was saved.
pub fn cache_messages(
    origin: &StoredBasisOrigin,
    basis: &SpectralBasis,
    complex: &BoxedComplex,
) -> Vec<BasisMessage> {
    match origin {
        StoredBasisOrigin::Read { file, seconds } => vec![BasisMessage::Note(format!(
            "using cached basis {} ({} fields, {}, loaded in {seconds:.2} s)",
            file.display(),
            basis.len(),
            complex.id(),
        ))],
        StoredBasisOrigin::Computed {
            unusable_file,
            saved,
        } => {
            let mut messages = Vec::new();
            if let Some(problem) = unusable_file {
                messages.push(BasisMessage::Warning(format!(
                    "cached basis is unusable ({problem}); recomputed"
                )));
            }
            messages.push(match saved {
                Ok(file) => BasisMessage::Note(format!("cached basis in {}", file.display())),
                Err(problem) => BasisMessage::Warning(format!(
                    "cannot cache the basis ({problem}); continuing without the cache"
                )),
            });
            messages
        }
    }
}

/// One line saying what was computed: the number of fields of each family, what was asked
/// (`-k K`, the complete basis if `K ≥ n1`, the field dimension), the discretization and the
/// computing time.
pub fn computed_basis_summary(
    complex: &BoxedComplex,
    size: BasisSize,
    basis: &SpectralBasis,
) -> String {
    let dimension = complex.field_dimension();
    let asked = match size {
        BasisSize::Fields(k) if k >= dimension => {
            format!("-k {k} ≥ n1 = {dimension}: the complete basis")
        }
        BasisSize::Fields(k) => format!("-k {k}"),
        BasisSize::Pairs(p) => format!("{p} pairs + harmonic"),
        BasisSize::MaxEigenvalue(bound) => format!("λ ≤ {bound}"),
        BasisSize::Complete => "the complete basis".to_string(),
    };
    format!(
        "{} fields ({asked}; {} harmonic, {} integrable, {} co-integrable; {}) computed in {:.2} s",
        basis.len(),
        basis.count(FieldFamily::Harmonic),
        basis.count(FieldFamily::Integrable),
        basis.count(FieldFamily::Cointegrable),
        complex.id(),
        basis.report().map_or(0.0, |r| r.seconds)
    )
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

/// On Unix: the folder belongs to the user running the program and is not writable by
/// everyone.
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
