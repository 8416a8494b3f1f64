//! Where a subcommand's spectral basis comes from: a given `.tvfb` file, or computed once and
//! cached.
//!
//! Flags (the same in every subcommand that takes a basis):
//! - `--basis FILE`: load this basis file; it must belong to the mesh (fingerprint), to the
//!   matrices of its discretization as built now (the file's matrix hash: a file computed before
//!   an entry's assembly changed is refused, naming the matrices that differ) and, if
//!   `--decomposition` / `--mass` are given, to that discretization. A file of format version 1
//!   or 2 carries no matrix hash: it is used on mesh and id alone, with a note on stderr;
//! - `-k K`: otherwise compute the basis of the `K` eigenfields of lowest eigenvalue of the
//!   Hodge–Laplacian, harmonic ones included, whichever family they belong to (the paper's `d`;
//!   [`DEFAULT_FIELDS`] if not given). `K ≥ n1` (the field dimension: 2F for face fields, E
//!   for DEC/Whitney) asks for the complete basis (dense
//!   eigensolvers, small meshes only). `-k` means this in every subcommand (`tvf spectrum -k K`
//!   lists the same `K` eigenvalues);
//! - `--discretization ID` (an id of the program's catalog, the `RunContext`; shorthands
//!   `--decomposition NAME`, `--mass NAME`): the discretization (default
//!   conforming-barycentric). A `--basis` file's discretization is rebuilt through the same
//!   catalog, so a basis of a program's own entry reopens in that program; or `--complex DIR`,
//!   matrices read from a folder (a `--basis` file then must have been computed from the same
//!   matrices: a file made with `--complex` is reopened by giving `--complex` again);
//! - `--cache-dir DIR`, `--no-cache`: where computed bases are kept.
//!
//! The cache is a [`tvf_spectral::BasisStore`] (file names and keys are documented there) in
//! `--cache-dir`, else `$TVF_CACHE_DIR`, else the user's cache folder ([`user_cache_folder`]),
//! never next to the mesh. A cache folder is created private and used only if it is safe
//! ([`tvf_spectral::BasisCache`]: yours, not writable by everyone; otherwise a warning, and
//! the basis is computed without the cache). A cached basis is reused and stderr says so; a damaged or mismatching cache file is recomputed with a
//! warning. `-k` sizes are `BasisSize::Fields`; the pairs a compressed file needs when no `-k`
//! is given are `BasisSize::Pairs`.

use crate::discretization_flags::DiscretizationFlags;
use crate::mesh_input::MeshInput;
use crate::progress::{note, warn, Progress};
use anyhow::{bail, Context, Result};
use clap::Args;
use std::path::PathBuf;
use tvf_core::SurfaceMesh;
use tvf_discretizations::{BoxedComplex, Catalog};
use tvf_spectral::{
    basis_file_complex, cached_or_computed_basis, compute_basis_of_size, computed_basis_summary,
    open_checked_basis_file, user_cache_folder_from, BasisCache, BasisMessage, BasisSize,
    SpectralBasis,
};

/// Eigenfields computed when neither `--basis` nor `-k` is given.
pub const DEFAULT_FIELDS: usize = 200;

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
    /// Folder of cached bases, yours and not writable by everyone (created private if missing)
    /// [default: $TVF_CACHE_DIR, else the user's cache folder: $XDG_CACHE_HOME/tvf or
    /// ~/.cache/tvf].
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
    /// included (the paper's d), when no --basis is given; K ≥ n1 (the field dimension: 2F for
    /// face fields, E for DEC/Whitney) gives the complete basis [default: 200].
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
    pub fn resolve(
        &self,
        catalog: &Catalog,
        mesh: &SurfaceMesh,
        input: &MeshInput,
    ) -> Result<ResolvedBasis> {
        self.options.resolve(catalog, mesh, input, self.size())
    }
}

/// A basis ready for use, with the discretization it belongs to.
pub struct ResolvedBasis {
    /// The discretization (named by the basis file, or chosen by the flags).
    pub discretization: BoxedComplex,
    /// The basis.
    pub basis: SpectralBasis,
}

impl BasisOptions {
    /// The basis for `mesh`: loads `--basis` (checking mesh and discretization) or computes a
    /// basis of `size`, through the cache unless `--no-cache`; the discretization is an entry of
    /// `catalog`.
    pub fn resolve(
        &self,
        catalog: &Catalog,
        mesh: &SurfaceMesh,
        input: &MeshInput,
        size: BasisSize,
    ) -> Result<ResolvedBasis> {
        let discretization = match &self.basis {
            Some(_) => None,
            None => Some(self.discretization.build(catalog, mesh, input)?),
        };
        self.resolve_with(catalog, mesh, input, size, discretization)
    }

    /// [`BasisOptions::resolve`] with the discretization already built (by
    /// [`BasisOptions::discretization`], to check the other inputs before the basis is
    /// computed); a `--basis` file brings its own, and `discretization` may then be `None`.
    pub fn resolve_with(
        &self,
        catalog: &Catalog,
        mesh: &SurfaceMesh,
        input: &MeshInput,
        size: BasisSize,
        discretization: Option<BoxedComplex>,
    ) -> Result<ResolvedBasis> {
        if let Some(path) = &self.basis {
            let given = match &self.discretization.complex {
                Some(_) => Some(self.discretization.build(catalog, mesh, input)?),
                None => None,
            };
            let requested = self.discretization.requested_id();
            let boundary = self.discretization.boundary;
            let file = open_checked_basis_file(
                catalog,
                path,
                mesh,
                requested.as_deref(),
                boundary,
                given,
            )?;
            file.messages(path).into_iter().for_each(tell);
            return Ok(ResolvedBasis {
                discretization: file.discretization,
                basis: file.basis,
            });
        }
        match size {
            BasisSize::Fields(0) => bail!("-k 0: ask for at least one eigenfield"),
            BasisSize::Pairs(0) => bail!("0 pairs: ask for at least one pair of eigenfields"),
            _ => {}
        }
        let discretization = match discretization {
            Some(discretization) => discretization,
            None => self.discretization.build(catalog, mesh, input)?,
        };
        let basis = self
            .cached(mesh, &discretization, size)
            .with_context(|| format!("{}: cannot compute the basis", input.label()))?;
        Ok(ResolvedBasis {
            discretization,
            basis,
        })
    }

    /// The basis of `size` from the cache (none with `--no-cache`), computed (with a progress
    /// bar) and cached if the cache does not hold a usable one; stderr says which.
    fn cached(
        &self,
        mesh: &SurfaceMesh,
        discretization: &BoxedComplex,
        size: BasisSize,
    ) -> Result<SpectralBasis> {
        let (store, messages) = self.cache().store();
        messages.into_iter().for_each(tell);
        let progress = Progress::new("basis");
        let callback = progress.basis_callback();
        let cached =
            cached_or_computed_basis(store.as_ref(), mesh, discretization, size, Some(&callback))?;
        drop(callback);
        if let Some(summary) = cached.computed_summary(discretization, size) {
            progress.finish(summary);
        }
        drop(progress);
        cached.messages(discretization).into_iter().for_each(tell);
        Ok(cached.basis)
    }

    /// The cache ([`BasisCache::choose`]): off with `--no-cache`; `--cache-dir` or
    /// `$TVF_CACHE_DIR` (chosen), else the user's cache folder (both checked before use).
    pub fn cache(&self) -> BasisCache {
        let from_environment = std::env::var_os(CACHE_DIR_VARIABLE).filter(|d| !d.is_empty());
        let chosen = self
            .cache_dir
            .clone()
            .or(from_environment.map(PathBuf::from));
        BasisCache::choose(self.no_cache, chosen, user_cache_folder)
    }

    /// The discretization a basis would use, without computing or loading the basis: the
    /// `--basis` file's (read from its header, checked against the discretization flags), else
    /// the flags' (default conforming-barycentric); built by the entry of `catalog`.
    pub fn discretization(
        &self,
        catalog: &Catalog,
        mesh: &SurfaceMesh,
        input: &MeshInput,
    ) -> Result<BoxedComplex> {
        match &self.basis {
            Some(path) if self.discretization.complex.is_none() => {
                let requested = self.discretization.requested_id();
                let boundary = self.discretization.boundary;
                let entry = requested.as_deref();
                Ok(basis_file_complex(catalog, path, mesh, entry, boundary)?)
            }
            _ => self.discretization.build(catalog, mesh, input),
        }
    }
}

/// Prints a message of the basis resolution on stderr.
fn tell(message: BasisMessage) {
    match message {
        BasisMessage::Note(text) => note(text),
        BasisMessage::Warning(text) => warn(text),
    }
}

/// The default cache folder: `$XDG_CACHE_HOME/tvf`, else
/// `~/.cache/tvf` on Unix and `%LOCALAPPDATA%\tvf` on Windows, else `tvf-cache-USER` in the
/// temporary folder ([`user_cache_folder_from`]).
pub fn user_cache_folder() -> PathBuf {
    let variable = |name| std::env::var_os(name).map(PathBuf::from);
    user_cache_folder_from(
        variable("XDG_CACHE_HOME"),
        variable("HOME"),
        variable("LOCALAPPDATA"),
        variable("USER").or_else(|| variable("USERNAME")),
    )
}

/// Computes a basis of `size` with a progress bar: `K` fields (the complete basis if
/// `K ≥ n1`, the field dimension) or `P` pairs plus the harmonic fields.
pub fn compute(discretization: &BoxedComplex, size: BasisSize) -> Result<SpectralBasis> {
    let progress = Progress::new("basis");
    let callback = progress.basis_callback();
    let basis = compute_basis_of_size(discretization.as_ref(), size, Some(&callback))?;
    progress.finish(computed_basis_summary(discretization, size, &basis));
    Ok(basis)
}
