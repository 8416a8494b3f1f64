//! The constructors of the paper's two finite element complexes, [`crate::Conforming`] and
//! [`crate::Nonconforming`], from a mesh: [`SpaceMasses`] picks the mass matrices, [`PaperSpace`]
//! builds each function space with them and [`PaperPair`] names the complex.

use crate::complex_id::complex_id;
use crate::face_geometry::FaceGeometry;
use crate::{
    CrouzeixRaviart, FaceFields, FiniteElementComplex, FunctionSpace, LagrangeP1, MassLumping,
};
use tvf_core::discretization::{BoundaryCondition, DiscretizationError};
use tvf_core::TriangleMesh;

/// The mass matrices of the two function spaces of a paper complex.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpaceMasses {
    /// Both spaces lumped by this rule.
    Lumped(MassLumping),
    /// The consistent (Galerkin) P1 mass `Σ_T |T| (1 + δ_ij)/12` (sparse); the Crouzeix–Raviart
    /// mass `|T|/3` per face and edge is the consistent one already (its basis is
    /// `L²`-orthogonal).
    Consistent,
}

impl SpaceMasses {
    /// The name in catalog ids: the lumping's name, or `consistent`.
    pub fn name(self) -> &'static str {
        match self {
            SpaceMasses::Lumped(lumping) => lumping.name(),
            SpaceMasses::Consistent => "consistent",
        }
    }
}

/// A function space of the paper's complexes, built on a mesh with its [`SpaceMasses`].
pub trait PaperSpace: FunctionSpace + Sized {
    /// The space on `mesh` (face geometry `geometry`) with the mass matrix `masses` selects.
    fn build(mesh: &TriangleMesh, geometry: &FaceGeometry, masses: SpaceMasses) -> Self;

    /// The space on `mesh` with its mass lumped by `lumping`; fails on a degenerate face.
    fn new(mesh: &TriangleMesh, lumping: MassLumping) -> Result<Self, DiscretizationError> {
        let geometry = FaceGeometry::new(mesh)?;
        Ok(Self::build(mesh, &geometry, SpaceMasses::Lumped(lumping)))
    }
}

impl PaperSpace for LagrangeP1 {
    fn build(mesh: &TriangleMesh, geometry: &FaceGeometry, masses: SpaceMasses) -> Self {
        match masses {
            SpaceMasses::Lumped(lumping) => Self::from_geometry(mesh, geometry, lumping),
            SpaceMasses::Consistent => Self::with_consistent_mass(mesh, geometry),
        }
    }
}

impl PaperSpace for CrouzeixRaviart {
    fn build(mesh: &TriangleMesh, geometry: &FaceGeometry, masses: SpaceMasses) -> Self {
        let lumping = match masses {
            SpaceMasses::Lumped(lumping) => lumping,
            SpaceMasses::Consistent => MassLumping::Barycentric,
        };
        Self::from_geometry(mesh, geometry, lumping)
    }
}

/// A (potential, co-potential) pair of the paper: its family name in catalog ids.
pub trait PaperPair {
    /// `conforming` (P1, Crouzeix–Raviart) or `nonconforming` (Crouzeix–Raviart, P1).
    const FAMILY: &'static str;
}

impl PaperPair for (LagrangeP1, CrouzeixRaviart) {
    const FAMILY: &'static str = "conforming";
}

impl PaperPair for (CrouzeixRaviart, LagrangeP1) {
    const FAMILY: &'static str = "nonconforming";
}

impl<P: PaperSpace, Q: PaperSpace> FiniteElementComplex<P, Q>
where
    (P, Q): PaperPair,
{
    /// The complex of `mesh` with the given mass lumping (for both function spaces), catalog id
    /// `{family}-{lumping}` (`conforming-barycentric`, `nonconforming-voronoi`, ...), default
    /// boundary condition. Fails on a degenerate face.
    pub fn new(mesh: &TriangleMesh, lumping: MassLumping) -> Result<Self, DiscretizationError> {
        Self::from_mesh(
            mesh,
            SpaceMasses::Lumped(lumping),
            BoundaryCondition::default(),
        )
    }

    /// [`FiniteElementComplex::new`] with boundary condition `boundary` (the decompositions it
    /// gives: [`crate::Conforming`], [`crate::Nonconforming`]); `+{boundary}` is appended to
    /// the id on a mesh with boundary.
    pub fn with_boundary(
        mesh: &TriangleMesh,
        lumping: MassLumping,
        boundary: BoundaryCondition,
    ) -> Result<Self, DiscretizationError> {
        Self::from_mesh(mesh, SpaceMasses::Lumped(lumping), boundary)
    }

    /// The complex with the consistent (Galerkin) P1 mass ([`SpaceMasses::Consistent`]),
    /// catalog id `{family}-consistent`, default boundary condition.
    pub fn consistent(mesh: &TriangleMesh) -> Result<Self, DiscretizationError> {
        Self::from_mesh(mesh, SpaceMasses::Consistent, BoundaryCondition::default())
    }

    /// [`FiniteElementComplex::consistent`] with boundary condition `boundary` (`+{boundary}`
    /// appended to the id on a mesh with boundary). Fails on a degenerate face.
    pub fn consistent_with_boundary(
        mesh: &TriangleMesh,
        boundary: BoundaryCondition,
    ) -> Result<Self, DiscretizationError> {
        Self::from_mesh(mesh, SpaceMasses::Consistent, boundary)
    }

    /// The complex of both spaces built on `mesh` with `masses`, boundary condition `boundary`,
    /// catalog id `{family}-{masses}` (`+{boundary}` on a mesh with boundary). Fails on a
    /// degenerate face.
    pub fn from_mesh(
        mesh: &TriangleMesh,
        masses: SpaceMasses,
        boundary: BoundaryCondition,
    ) -> Result<Self, DiscretizationError> {
        let geometry = FaceGeometry::new(mesh)?;
        let family = <(P, Q) as PaperPair>::FAMILY;
        Self::from_spaces_with_boundary(
            complex_id(
                &format!("{family}-{}", masses.name()),
                mesh.topology(),
                boundary,
            ),
            mesh,
            P::build(mesh, &geometry, masses),
            Q::build(mesh, &geometry, masses),
            FaceFields::from_geometry(&geometry),
            boundary,
        )
    }
}
