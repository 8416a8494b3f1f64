//! [`BasisStore`]: a folder of computed Fourier bases (`.tvfb` files), so that a basis is
//! computed once per mesh, complex and size and then read back.
//!
//! A basis is kept as `{fingerprint}-{complex id}-{matrix hash}-{size}.tvfb`: the mesh
//! fingerprint ([`SurfaceMesh::fingerprint`], 16 hex digits), the complex's
//! [`HodgeComplex::id`] (a catalog id, or `{catalog id}+{boundary}` on a mesh with boundary), the
//! value of the complex's [`HodgeComplex::matrix_hash`] (16 hex digits: its five matrices and
//! fixed nodes) and the size: `d{K}` for the `K` lowest fields, `p{P}` for `P` pairs, `l{bits}`
//! for an eigenvalue bound, `complete` for the complete basis. The seed is fixed (0), so equal
//! names mean bit-identical bases; a complex whose assembly changed has another name, and its
//! basis is computed afresh. A file that is damaged, carries no matrix hash (format versions 1
//! and 2) or does not hold what its name promises is recomputed (and the problem reported),
//! never used; so is anything under a basis's name that is not a regular file of the user (a
//! link, a FIFO, another user's file: not followed, not read, replaced by a rename, see
//! `basis_cache_file`). Files under the names of earlier versions (`{fingerprint}-{complex id}-{size}`)
//! are never read; they may be deleted.
use crate::basis_cache_file::{open_cache_file, put_cache_file, CacheEntry};
use crate::formats::basis_file::{load_basis_from_file, read_basis_header_from};
use crate::{
    compute_basis, save_eigenfunction_basis, BasisError, BasisFileKey, BasisProgress, BasisRequest,
    BasisSize, FieldFamily, SpectralBasis,
};
use std::fs::File;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::mesh::Mesh;

/// A folder of computed bases (see the module documentation for the file names).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BasisStore {
    folder: PathBuf,
}

/// Where a basis handed out by [`BasisStore::basis`] came from.
#[derive(Debug)]
pub enum StoredBasisOrigin {
    /// Read from this file of the store in `seconds`.
    Read {
        /// The basis file.
        file: PathBuf,
        /// Wall-clock time of the read.
        seconds: f64,
    },
    /// Computed now.
    Computed {
        /// Why the stored file could not be used, if there was one (it was replaced).
        unusable_file: Option<String>,
        /// The file the basis was saved to, or why it could not be saved (the basis is
        /// still returned: the store is a cache).
        saved: Result<PathBuf, String>,
    },
}

impl BasisStore {
    /// The store kept in `folder` (created when the first basis is saved).
    pub fn new(folder: impl Into<PathBuf>) -> Self {
        Self {
            folder: folder.into(),
        }
    }

    /// The folder of the store.
    pub fn folder(&self) -> &Path {
        &self.folder
    }

    /// The file a basis of `size` for `complex` on `mesh` is kept in.
    pub fn file<M: Mesh + ?Sized, H: HodgeComplex + ?Sized>(
        &self,
        mesh: &M,
        complex: &H,
        size: BasisSize,
    ) -> PathBuf {
        let size_name = match effective_size(size, complex.field_dimension()) {
            BasisSize::Fields(k) => format!("d{k}"),
            BasisSize::Pairs(p) => format!("p{p}"),
            BasisSize::MaxEigenvalue(bound) => format!("l{:016x}", bound.to_bits()),
            BasisSize::Complete => "complete".to_string(),
        };
        self.folder.join(format!(
            "{:016x}-{}-{:016x}-{size_name}.tvfb",
            mesh.fingerprint(),
            complex.id(),
            complex.matrix_hash().value()
        ))
    }

    /// The basis of `size` for `complex` on `mesh`: read from the store if it holds a usable
    /// one, else computed with seed 0 (reporting to `progress`) and saved.
    ///
    /// `size` [`BasisSize::Fields`]`(K)` with `K ≥ n1` (the field dimension) is the complete
    /// basis. Errors are those of [`compute_basis`]; problems of the store itself (unreadable
    /// or mismatching files, a folder that cannot be written) are reported in the returned
    /// [`StoredBasisOrigin`], not as errors.
    pub fn basis<M: Mesh + ?Sized, H: HodgeComplex + ?Sized>(
        &self,
        mesh: &M,
        complex: &H,
        size: BasisSize,
        progress: Option<&dyn Fn(&BasisProgress)>,
    ) -> Result<(SpectralBasis, StoredBasisOrigin), BasisError> {
        let file = self.file(mesh, complex, size);
        let key = BasisFileKey::new(mesh, complex);
        let mut unusable_file = None;
        match open_cache_file(&file) {
            CacheEntry::Missing => {}
            CacheEntry::Unusable(problem) => {
                unusable_file = Some(format!("{}: {problem}", file.display()))
            }
            CacheEntry::Usable(handle) => {
                let start = Instant::now();
                match read_stored(&handle, &file, &key, complex, size) {
                    Ok(basis) => {
                        let origin = StoredBasisOrigin::Read {
                            file,
                            seconds: start.elapsed().as_secs_f64(),
                        };
                        return Ok((basis, origin));
                    }
                    Err(problem) => unusable_file = Some(problem),
                }
            }
        }
        let mut request = size_request(size, complex.field_dimension(), progress);
        request.keep_eigenfunctions = true;
        let mut basis = compute_basis(complex, &request)?;
        // Saved in compact form (smaller, see `save_eigenfunction_basis`), which is then dropped
        // from memory: the basis handed out carries only its dense fields.
        // Written under a private name and renamed onto the cache name, replacing whatever
        // is there (see `basis_cache_file`).
        let saved = match basis.take_eigenfunctions() {
            Some(compact) => std::fs::create_dir_all(&self.folder)
                .map_err(|e| format!("{}: {e}", self.folder.display()))
                .and_then(|()| {
                    put_cache_file(&self.folder, &file, |staged| {
                        save_eigenfunction_basis(staged, &compact, complex, &key)
                            .map_err(|e| e.to_string())
                    })
                }),
            None => Err(format!(
                "{}: the compact basis was not kept",
                file.display()
            )),
        };
        Ok((
            basis,
            StoredBasisOrigin::Computed {
                unusable_file,
                saved,
            },
        ))
    }
}

/// The basis in the cache file `handle` (opened from `path`), if it carries a matrix hash,
/// belongs to `key` and `complex` and has the size its name promises; else why not.
fn read_stored<H: HodgeComplex + ?Sized>(
    handle: &File,
    path: &Path,
    key: &BasisFileKey,
    complex: &H,
    size: BasisSize,
) -> Result<SpectralBasis, String> {
    let header = read_basis_header_from(handle, path).map_err(|e| e.to_string())?;
    if header.key.matrix_hash.is_none() {
        return Err(format!(
            "{}: format version {} predates matrix hashes",
            path.display(),
            header.version
        ));
    }
    let handle = handle
        .try_clone()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let basis = load_basis_from_file(handle, path, key, complex).map_err(|e| e.to_string())?;
    match size_mismatch(size, complex.field_dimension(), &basis) {
        Some(problem) => Err(format!("{}: {problem}", path.display())),
        None => Ok(basis),
    }
}

/// Computes the basis of `size` for `complex` with seed 0, reporting to `progress`;
/// [`BasisSize::Fields`]`(K)` with `K ≥ n1` is the complete basis (dense eigensolvers).
pub fn compute_basis_of_size<H: HodgeComplex + ?Sized>(
    complex: &H,
    size: BasisSize,
    progress: Option<&dyn Fn(&BasisProgress)>,
) -> Result<SpectralBasis, BasisError> {
    compute_basis(
        complex,
        &size_request(size, complex.field_dimension(), progress),
    )
}

/// The request of a basis of `size` with seed 0, reporting to `progress`.
fn size_request<'a>(
    size: BasisSize,
    field_dimension: usize,
    progress: Option<&'a dyn Fn(&BasisProgress)>,
) -> BasisRequest<'a> {
    let mut request = BasisRequest::new(effective_size(size, field_dimension));
    request.progress = progress;
    request
}

/// `size`, with `K ≥ field_dimension` fields read as the complete basis.
fn effective_size(size: BasisSize, field_dimension: usize) -> BasisSize {
    match size {
        BasisSize::Fields(k) if k >= field_dimension => BasisSize::Complete,
        other => other,
    }
}

/// Why a stored basis does not have the size its file name promises (`None` if it has): `K`
/// fields for `K`, all `dimension` fields for the complete basis, at most `P` fields of each
/// non-harmonic family (and `P` of one, unless the basis is complete) for `P` pairs.
fn size_mismatch(size: BasisSize, dimension: usize, basis: &SpectralBasis) -> Option<String> {
    let fields = basis.len();
    match effective_size(size, dimension) {
        BasisSize::Fields(k) => (fields != k).then(|| format!("it holds {fields} fields, not {k}")),
        BasisSize::Complete => (fields != dimension)
            .then(|| format!("it holds {fields} fields, not the complete {dimension}")),
        BasisSize::Pairs(p) => {
            let integrable = basis.count(FieldFamily::Integrable);
            let cointegrable = basis.count(FieldFamily::Cointegrable);
            let fits = integrable <= p
                && cointegrable <= p
                && (integrable == p || cointegrable == p || fields == dimension);
            (!fits).then(|| {
                format!(
                    "it holds {integrable} integrable and {cointegrable} co-integrable fields, \
                     not {p} pairs"
                )
            })
        }
        BasisSize::MaxEigenvalue(bound) => basis
            .eigenvalues()
            .iter()
            .any(|&lambda| lambda > bound)
            .then(|| format!("it holds eigenvalues above the bound {bound:e}")),
    }
}
