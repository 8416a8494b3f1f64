//! Resolving the spectral basis a program works with: a given basis file, checked against the
//! mesh and its discretization ([`open_checked_basis_file`]), or a basis of a requested size
//! read from or computed into a cache folder ([`BasisCache`], [`cached_or_computed_basis`]).
//! What happened is said by [`BasisMessage`]s the caller prints. Which cache folder, and
//! whether it is safe to use, is decided by [`BasisCache`].

use crate::{
    compute_basis_of_size, open_basis_file, open_basis_file_with, read_basis_header, BasisError,
    BasisFileUseError, BasisProgress, BasisSize, BasisStore, FieldFamily, SpectralBasis,
    StoredBasisOrigin,
};
use std::path::Path;
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
