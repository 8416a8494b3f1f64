//! The discretizations papers/ runs: every entry of the built-in catalog of
//! `tvf-discretizations` ([`tvf_discretizations::Catalog::builtin`]); a discretization added
//! there is compared here without another line. The comparison itself
//! ([`crate::discretization_comparison::run`]) takes any entries, e.g. a catalog of one's own
//! (`catalog.entries()`).

use std::time::Instant;
use tvf_core::SurfaceMesh;
use tvf_discretizations::{builtin_catalog, CatalogEntry};
use tvf_figures::FigureError;
use tvf_spectral::{compute_basis, BasisRequest, SpectralBasis};

/// A basis and the wall-clock seconds it took, complex assembly included.
#[derive(Debug)]
pub struct TimedBasis {
    /// The basis.
    pub basis: SpectralBasis,
    /// Seconds for assembling the complex and computing the basis.
    pub seconds: f64,
}

/// The discretizations of the comparison: the whole built-in catalog.
pub fn compared_discretizations() -> &'static [CatalogEntry] {
    builtin_catalog().entries()
}

/// Builds `entry`'s complex on `mesh` and computes the requested basis, timing both together.
pub fn basis_of(
    entry: &CatalogEntry,
    mesh: &SurfaceMesh,
    request: &BasisRequest<'_>,
) -> Result<TimedBasis, FigureError> {
    let start = Instant::now();
    let complex = entry.build(mesh)?;
    let basis = compute_basis(complex.as_ref(), request)?;
    Ok(TimedBasis {
        basis,
        seconds: start.elapsed().as_secs_f64(),
    })
}
