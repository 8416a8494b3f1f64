//! Where a subcommand's spectral basis comes from: a given `.tvfb` file, or computed once and
//! cached.
//!
//! Flags (the same in every subcommand that takes a basis):
//! - `--basis FILE`: load this basis file; it must belong to the mesh (fingerprint) and, if
//!   `--decomposition` / `--mass` are given, to that discretization;
//! - `-k K`: otherwise compute the basis of the `K` eigenfields of lowest eigenvalue of the
//!   Hodge–Laplacian, harmonic ones included, whichever family they belong to (the paper's `d`;
//!   [`DEFAULT_FIELDS`] if not given). `K ≥ 2F` asks for the complete basis (dense
//!   eigensolvers, small meshes only). `-k` means this in every subcommand (`tvf spectrum -k K`
//!   lists the same `K` eigenvalues);
//! - `--discretization ID` (a catalog id; shorthands `--decomposition NAME`, `--mass NAME`): the
//!   discretization (default conforming-barycentric);
//! - `--cache-dir DIR`, `--no-cache`: where computed bases are kept.
//!
//! The cache: a computed basis is saved as `{fingerprint}-{discretization id}-{size}.tvfb` in
//! `--cache-dir`, else `$TVF_CACHE_DIR`, else `.tvf-cache/` next to the mesh file; for a built-in
//! `--example` mesh (no file to sit next to) in `tvf-cache/` under the system temporary folder.
//! `{size}` is `d{K}` for `K` fields, `p{P}` for the `P` pairs a compressed file needs when no
//! `-k` is given, `complete` for the complete basis. The key is the mesh fingerprint (vertices
//! and faces), the discretization's catalog id and the size (the seed is fixed, so equal
//! keys mean bit-identical bases). A cached basis is reused and stderr says so; a damaged or
//! mismatching cache file is recomputed with a warning.

use crate::discretization_flags::{build_discretization, Discretization, DiscretizationFlags};
use crate::mesh_input::MeshInput;
use crate::progress::{note, warn, Progress};
use anyhow::{bail, Context, Result};
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tvf_core::discretization::HodgeOperators;
use tvf_core::SurfaceMesh;
use tvf_discretizations::split_complex_id;
use tvf_spectral::{
    compute_basis, load_basis, mesh_fingerprint, read_basis_header, save_basis, BasisFileKey,
    BasisRequest, FieldFamily, SpectralBasis,
};

/// Eigenfields computed when neither `--basis` nor `-k` is given.
pub const DEFAULT_FIELDS: usize = 200;

/// The size of a computed basis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BasisSize {
    /// The `K` eigenfields of lowest eigenvalue, harmonic ones included (`-k K`); `K ≥ 2F`
    /// means the complete basis.
    Fields(usize),
    /// The harmonic fields plus `P` integrable and `P` co-integrable eigenfields: what a
    /// compressed file keeping `P` pairs needs (used only when no `-k` is given).
    Pairs(usize),
}

/// Environment variable naming the basis cache folder.
pub const CACHE_DIR_VARIABLE: &str = "TVF_CACHE_DIR";

/// Basis flags without `-k`; see the module documentation.
#[derive(Args, Debug, Clone, Default)]
pub struct BasisOptions {
    /// A basis file (.tvfb, `tvf basis`) of this mesh; without it a basis is computed once and
    /// cached.
    #[arg(long, value_name = "FILE")]
    pub basis: Option<PathBuf>,
    #[command(flatten)]
    pub discretization: DiscretizationFlags,
    /// Folder of cached bases [default: $TVF_CACHE_DIR, else .tvf-cache/ next to the mesh, else
    /// tvf-cache/ in the temporary folder for --example meshes].
    #[arg(long, value_name = "DIR", conflicts_with = "basis")]
    pub cache_dir: Option<PathBuf>,
    /// Compute the basis without reading or writing the cache (overrides --cache-dir).
    #[arg(long, conflicts_with = "basis")]
    pub no_cache: bool,
}

/// Basis flags: [`BasisOptions`] plus `-k` (the number of eigenfields to compute).
#[derive(Args, Debug, Clone, Default)]
pub struct BasisSource {
    #[command(flatten)]
    pub options: BasisOptions,
    /// Basis size: compute the K lowest eigenfields of the Hodge–Laplacian, harmonic ones
    /// included (the paper's d), when no --basis is given; K ≥ 2F gives the complete basis
    /// [default: 200].
    #[arg(short = 'k', value_name = "K", conflicts_with = "basis")]
    pub fields: Option<usize>,
}

impl BasisSource {
    /// The size to compute: `-k K` fields, else `default`.
    pub fn size_or(&self, default: BasisSize) -> BasisSize {
        self.fields.map_or(default, BasisSize::Fields)
    }

    /// The size to compute: `-k K` fields, else [`DEFAULT_FIELDS`].
    pub fn size(&self) -> BasisSize {
        self.size_or(BasisSize::Fields(DEFAULT_FIELDS))
    }

    /// The basis for `mesh` (see [`BasisOptions::resolve`]) of [`BasisSource::size`].
    pub fn resolve(&self, mesh: &SurfaceMesh, input: &MeshInput) -> Result<ResolvedBasis> {
        self.options.resolve(mesh, input, self.size())
    }
}

/// A basis ready for use, with the discretization it belongs to.
pub struct ResolvedBasis {
    /// The discretization (named by the basis file, or chosen by the flags).
    pub discretization: Discretization,
    /// The basis.
    pub basis: SpectralBasis,
    /// [`mesh_fingerprint`] of the mesh.
    pub mesh_fingerprint: u64,
}

impl BasisOptions {
    /// The basis for `mesh`: loads `--basis` (checking mesh and discretization) or computes a
    /// basis of `size`, through the cache unless `--no-cache`.
    pub fn resolve(
        &self,
        mesh: &SurfaceMesh,
        input: &MeshInput,
        size: BasisSize,
    ) -> Result<ResolvedBasis> {
        let fingerprint = mesh_fingerprint(mesh);
        if let Some(path) = &self.basis {
            return self.load_file(mesh, path, fingerprint);
        }
        match size {
            BasisSize::Fields(0) => bail!("-k 0: ask for at least one eigenfield"),
            BasisSize::Pairs(0) => bail!("0 pairs: ask for at least one pair of eigenfields"),
            _ => {}
        }
        let discretization = self.discretization.build(mesh, &input.label())?;
        let size_name = match size {
            BasisSize::Fields(k) if k >= discretization.field_dimension() => "complete".to_string(),
            BasisSize::Fields(k) => format!("d{k}"),
            BasisSize::Pairs(p) => format!("p{p}"),
        };
        let key = BasisFileKey::new(mesh, discretization.as_ref());
        let cache_file = if self.no_cache {
            None
        } else {
            let name = format!(
                "{fingerprint:016x}-{}-{size_name}.tvfb",
                discretization.id()
            );
            Some(self.cache_folder(input).join(name))
        };
        if let Some(file) = cache_file.as_ref().filter(|f| f.exists()) {
            let start = Instant::now();
            let dimension = discretization.field_dimension();
            let loaded = load_basis(file, &key)
                .map_err(anyhow::Error::from)
                .and_then(|b| {
                    size_mismatch(size, dimension, &b).map_or(Ok(b), |problem| bail!(problem))
                });
            match loaded {
                Ok(basis) => {
                    note(format!(
                        "using cached basis {} ({} fields, {}, loaded in {:.2} s)",
                        file.display(),
                        basis.len(),
                        key.discretization,
                        start.elapsed().as_secs_f64()
                    ));
                    return Ok(ResolvedBasis {
                        discretization,
                        basis,
                        mesh_fingerprint: fingerprint,
                    });
                }
                Err(error) => warn(format!(
                    "cached basis is unusable ({}: {error}); recomputing",
                    file.display()
                )),
            }
        }
        let basis = compute(&discretization, size)
            .with_context(|| format!("{}: cannot compute the basis", input.label()))?;
        if let Some(file) = &cache_file {
            let saved = file
                .parent()
                .map_or(Ok(()), std::fs::create_dir_all)
                .map_err(anyhow::Error::from)
                .and_then(|()| save_basis(file, &basis, &key).map_err(anyhow::Error::from));
            match saved {
                Ok(()) => note(format!("cached basis in {}", file.display())),
                Err(error) => warn(format!(
                    "cannot cache the basis in {} ({error}); continuing without the cache",
                    file.display()
                )),
            }
        }
        Ok(ResolvedBasis {
            discretization,
            basis,
            mesh_fingerprint: fingerprint,
        })
    }

    /// The cache folder for `input`: `--cache-dir`, `$TVF_CACHE_DIR`, `.tvf-cache/` next to the
    /// mesh file, or `tvf-cache/` in the temporary folder for built-in examples.
    pub fn cache_folder(&self, input: &MeshInput) -> PathBuf {
        if let Some(dir) = &self.cache_dir {
            return dir.clone();
        }
        if let Some(dir) = std::env::var_os(CACHE_DIR_VARIABLE).filter(|d| !d.is_empty()) {
            return PathBuf::from(dir);
        }
        match &input.mesh {
            Some(path) => path
                .parent()
                .filter(|p| !p.as_os_str().is_empty())
                .unwrap_or(Path::new("."))
                .join(".tvf-cache"),
            None => std::env::temp_dir().join("tvf-cache"),
        }
    }

    /// The discretization a basis would use, without computing or loading the basis: the
    /// `--basis` file's (read from its header, checked against the discretization flags), else
    /// the flags' (default conforming-barycentric).
    pub fn discretization(&self, mesh: &SurfaceMesh, input: &MeshInput) -> Result<Discretization> {
        match &self.basis {
            Some(path) => {
                build_discretization(&self.file_discretization(path)?, mesh, &input.label())
            }
            None => self.discretization.build(mesh, &input.label()),
        }
    }

    /// The catalog id named by the header of the basis file `path`, refused if it contradicts
    /// the discretization flags.
    fn file_discretization(&self, path: &Path) -> Result<String> {
        let stored = read_basis_header(path)?.key.discretization;
        // On a mesh with boundary the stored id is `{catalog id}+{boundary}`.
        let (stored_entry, stored_boundary) = split_complex_id(&stored);
        if let Some(wanted) = self
            .discretization
            .requested_id()
            .filter(|w| w != stored_entry)
        {
            bail!(
                "{}: the basis was computed with the discretization '{stored}', but '{wanted}' was asked for",
                path.display()
            );
        }
        if let (Some(stored_boundary), Some(wanted)) =
            (stored_boundary, self.discretization.boundary)
        {
            if stored_boundary != wanted {
                bail!(
                    "{}: the basis was computed with the boundary condition '{}', but '{}' was asked for",
                    path.display(),
                    stored_boundary.name(),
                    wanted.name()
                );
            }
        }
        Ok(stored)
    }

    fn load_file(
        &self,
        mesh: &SurfaceMesh,
        path: &Path,
        fingerprint: u64,
    ) -> Result<ResolvedBasis> {
        let start = Instant::now();
        let id = self.file_discretization(path)?;
        let discretization = build_discretization(&id, mesh, &path.display().to_string())?;
        let key = BasisFileKey::new(mesh, discretization.as_ref());
        let basis = load_basis(path, &key)?;
        note(format!(
            "using basis {} ({} fields, {}, loaded in {:.2} s)",
            path.display(),
            basis.len(),
            key.discretization,
            start.elapsed().as_secs_f64()
        ));
        Ok(ResolvedBasis {
            discretization,
            basis,
            mesh_fingerprint: fingerprint,
        })
    }
}

/// Why a loaded basis does not have the size its cache name promises (`None` if it has): `K`
/// fields for `-k K`, the complete basis (`dimension` fields) for `K ≥ dimension`, at most `P`
/// fields of each non-harmonic family (and `P` of one, unless the basis is complete) for `P`
/// pairs.
fn size_mismatch(size: BasisSize, dimension: usize, basis: &SpectralBasis) -> Option<String> {
    let fields = basis.len();
    match size {
        BasisSize::Fields(k) => {
            let wanted = k.min(dimension);
            (fields != wanted).then(|| format!("it holds {fields} fields, not {wanted}"))
        }
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
    }
}

/// Computes a basis of `size` with a progress bar: `K` fields (the complete basis if
/// `K ≥ 2F`) or `P` pairs plus the harmonic fields.
pub fn compute(discretization: &Discretization, size: BasisSize) -> Result<SpectralBasis> {
    let progress = Progress::new("basis");
    let callback = progress.basis_callback();
    let dimension = discretization.field_dimension();
    let (request, asked) = match size {
        BasisSize::Fields(k) if k >= dimension => (
            BasisRequest::complete(),
            format!("-k {k} ≥ 2F = {dimension}: the complete basis"),
        ),
        BasisSize::Fields(k) => (BasisRequest::fields(k), format!("-k {k}")),
        BasisSize::Pairs(p) => (BasisRequest::pairs(p), format!("{p} pairs + harmonic")),
    };
    let basis = compute_basis(discretization.as_ref(), &request.with_progress(&callback))?;
    progress.finish(format!(
        "{} fields ({asked}; {} harmonic, {} integrable, {} co-integrable; {}) computed in {:.2} s",
        basis.len(),
        basis.count(FieldFamily::Harmonic),
        basis.count(FieldFamily::Integrable),
        basis.count(FieldFamily::Cointegrable),
        discretization.id(),
        basis.report().map_or(0.0, |r| r.seconds)
    ));
    Ok(basis)
}
