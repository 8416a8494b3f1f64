//! The discretizations the comparison runs: [`DISCRETIZATIONS`], one entry per discretization.
//!
//! To compare a new discretization, add **one line** to [`DISCRETIZATIONS`]: a name and a
//! function that builds its basis through [`basis_of`] from any
//! [`HodgeComplex`](tvf_core::discretization::HodgeComplex), e.g. one assembled from a new
//! function space with `FiniteElementComplex::from_spaces` (see `papers/README.md`).

use crate::error::PaperError;
use std::time::Instant;
use tvf_core::discretization::{DiscretizationError, HodgeComplex};
use tvf_core::SurfaceMesh;
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};
use tvf_spectral::{compute_basis, BasisRequest, SpectralBasis};

/// A basis and the wall-clock seconds it took, complex assembly included.
#[derive(Debug)]
pub struct TimedBasis {
    /// The basis.
    pub basis: SpectralBasis,
    /// Seconds for assembling the complex and computing the basis.
    pub seconds: f64,
}

/// Builds the basis of a mesh for a request, timing assembly and eigensolve together.
pub type BasisBuilder = fn(&SurfaceMesh, &BasisRequest<'_>) -> Result<TimedBasis, PaperError>;

/// One discretization of the comparison.
#[derive(Clone, Copy)]
pub struct Discretization {
    /// Name in tables and plots.
    pub name: &'static str,
    /// Assembles the complex and computes the requested basis.
    pub build: BasisBuilder,
}

impl std::fmt::Debug for Discretization {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Discretization")
            .field("name", &self.name)
            .finish()
    }
}

/// Times `assemble` (a complex constructor) and [`compute_basis`] on its result.
pub fn basis_of<H: HodgeComplex>(
    assemble: impl FnOnce() -> Result<H, DiscretizationError>,
    request: &BasisRequest<'_>,
) -> Result<TimedBasis, PaperError> {
    let start = Instant::now();
    let complex = assemble()?;
    let basis = compute_basis(&complex, request)?;
    Ok(TimedBasis {
        basis,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// Every discretization of the comparison: the paper's two decompositions with both mass
/// lumpings. **Add a discretization here, one line.**
#[rustfmt::skip]
pub const DISCRETIZATIONS: &[Discretization] = &[
    Discretization { name: "conforming, barycentric", build: |m, r| basis_of(|| Conforming::new(m, MassLumping::Barycentric), r) },
    Discretization { name: "conforming, Voronoi", build: |m, r| basis_of(|| Conforming::new(m, MassLumping::Voronoi), r) },
    Discretization { name: "nonconforming, barycentric", build: |m, r| basis_of(|| Nonconforming::new(m, MassLumping::Barycentric), r) },
    Discretization { name: "nonconforming, Voronoi", build: |m, r| basis_of(|| Nonconforming::new(m, MassLumping::Voronoi), r) },
];
