//! The catalog: every discretization tvf ships, listed once. The CLI, the editor, papers/, basis
//! files and the cache key read it; nothing else names a discretization.

use crate::{Conforming, DecComplex, MassLumping, Nonconforming, WhitneyGalerkin};
use thiserror::Error;
use tvf_core::discretization::{BoundaryCondition, DiscretizationError, HodgeComplex};
use tvf_core::SurfaceMesh;

/// A complex built by the catalog, behind the object-safe seam.
pub type BoxedComplex = Box<dyn HodgeComplex>;

/// One discretization: a stable id, what it is, what it needs of the mesh, and its constructor.
#[derive(Clone, Copy)]
pub struct CatalogEntry {
    /// Stable id, lower-case kebab-case (`conforming-barycentric`): command lines, basis files,
    /// cache names.
    pub id: &'static str,
    /// One line: potentials, fields, co-potentials and masses.
    pub description: &'static str,
    /// What the mesh must satisfy beyond being a valid oriented manifold triangle mesh.
    pub preconditions: &'static str,
    /// Whether construction needs a Delaunay mesh (the conformance suite's corpus for it is the
    /// Delaunay part).
    pub needs_delaunay: bool,
    /// Builds the complex of a mesh (on a mesh with boundary with the default boundary
    /// condition, [`BoundaryCondition::Tangential`]).
    pub build: fn(&SurfaceMesh) -> Result<BoxedComplex, DiscretizationError>,
    /// Builds the complex of a mesh with the given boundary condition (the same complex as
    /// `build` on a closed mesh). Fails with
    /// [`DiscretizationError::UnsupportedBoundaryCondition`] for a condition not in
    /// `boundary_conditions` on a mesh with boundary.
    pub build_with_boundary:
        fn(&SurfaceMesh, BoundaryCondition) -> Result<BoxedComplex, DiscretizationError>,
    /// The boundary conditions the entry offers on meshes with boundary, the default first.
    pub boundary_conditions: &'static [BoundaryCondition],
    /// What each boundary condition of [`BoundaryCondition::ALL`] (in that order) fixes in this
    /// complex, one phrase each, for listings.
    pub boundary_meanings: [&'static str; 2],
}

impl CatalogEntry {
    /// `build_with_boundary(mesh, boundary)`.
    pub fn build_with(
        &self,
        mesh: &SurfaceMesh,
        boundary: BoundaryCondition,
    ) -> Result<BoxedComplex, DiscretizationError> {
        (self.build_with_boundary)(mesh, boundary)
    }

    /// What `boundary` fixes in this complex (one phrase, e.g. "P1 potentials zero at boundary
    /// vertices").
    pub fn boundary_meaning(&self, boundary: BoundaryCondition) -> &'static str {
        match boundary {
            BoundaryCondition::Tangential => self.boundary_meanings[0],
            BoundaryCondition::Normal => self.boundary_meanings[1],
        }
    }
}

const CONFORMING_BOUNDARY: [&str; 2] = [
    "Crouzeix–Raviart co-potentials zero at boundary edge midpoints",
    "P1 potentials zero at boundary vertices",
];
const NONCONFORMING_BOUNDARY: [&str; 2] = [
    "P1 co-potentials zero at boundary vertices",
    "Crouzeix–Raviart potentials zero at boundary edge midpoints",
];
const DEC_BOUNDARY: [&str; 2] = [
    "absolute forms, nothing fixed",
    "relative forms: 0-forms zero at boundary vertices, 1-forms zero on boundary edges",
];

const BOTH: &[BoundaryCondition] = &BoundaryCondition::ALL;

impl std::fmt::Debug for CatalogEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CatalogEntry")
            .field("id", &self.id)
            .finish()
    }
}

/// The id used when none is given: the paper's conforming decomposition, barycentric masses.
pub const DEFAULT_DISCRETIZATION: &str = "conforming-barycentric";

const ANY_MESH: &str = "none (any valid mesh without degenerate faces)";
const DELAUNAY: &str = "a Delaunay mesh: cot α + cot β > 0 on every edge (⋆1 positive)";

static CATALOG: [CatalogEntry; 9] = [
    CatalogEntry {
        id: "conforming-barycentric",
        description: "the paper's conforming decomposition: P1 potentials, face fields, Crouzeix–Raviart co-potentials; barycentric lumped masses",
        preconditions: ANY_MESH,
        needs_delaunay: false,
        build: |mesh| Ok(Box::new(Conforming::new(mesh, MassLumping::Barycentric)?)),
        build_with_boundary: |mesh, boundary| {
            Ok(Box::new(Conforming::with_boundary(mesh, MassLumping::Barycentric, boundary)?))
        },
        boundary_conditions: BOTH,
        boundary_meanings: CONFORMING_BOUNDARY,
    },
    CatalogEntry {
        id: "conforming-voronoi",
        description: "the conforming decomposition with mixed-Voronoi vertex and midpoint-Voronoi edge masses",
        preconditions: ANY_MESH,
        needs_delaunay: false,
        build: |mesh| Ok(Box::new(Conforming::new(mesh, MassLumping::Voronoi)?)),
        build_with_boundary: |mesh, boundary| {
            Ok(Box::new(Conforming::with_boundary(mesh, MassLumping::Voronoi, boundary)?))
        },
        boundary_conditions: BOTH,
        boundary_meanings: CONFORMING_BOUNDARY,
    },
    CatalogEntry {
        id: "conforming-consistent",
        description: "the conforming decomposition with Galerkin masses: the consistent P1 mass ∫φᵢφⱼ (sparse) as M0, the Crouzeix–Raviart mass (diagonal, already consistent)",
        preconditions: ANY_MESH,
        needs_delaunay: false,
        build: |mesh| Ok(Box::new(Conforming::consistent(mesh)?)),
        build_with_boundary: |mesh, boundary| {
            Ok(Box::new(Conforming::consistent_with_boundary(mesh, boundary)?))
        },
        boundary_conditions: BOTH,
        boundary_meanings: CONFORMING_BOUNDARY,
    },
    CatalogEntry {
        id: "nonconforming-barycentric",
        description: "the nonconforming decomposition: Crouzeix–Raviart potentials, face fields, P1 co-potentials; barycentric lumped masses",
        preconditions: ANY_MESH,
        needs_delaunay: false,
        build: |mesh| Ok(Box::new(Nonconforming::new(mesh, MassLumping::Barycentric)?)),
        build_with_boundary: |mesh, boundary| {
            Ok(Box::new(Nonconforming::with_boundary(mesh, MassLumping::Barycentric, boundary)?))
        },
        boundary_conditions: BOTH,
        boundary_meanings: NONCONFORMING_BOUNDARY,
    },
    CatalogEntry {
        id: "nonconforming-voronoi",
        description: "the nonconforming decomposition with mixed-Voronoi vertex and midpoint-Voronoi edge masses",
        preconditions: ANY_MESH,
        needs_delaunay: false,
        build: |mesh| Ok(Box::new(Nonconforming::new(mesh, MassLumping::Voronoi)?)),
        build_with_boundary: |mesh, boundary| {
            Ok(Box::new(Nonconforming::with_boundary(mesh, MassLumping::Voronoi, boundary)?))
        },
        boundary_conditions: BOTH,
        boundary_meanings: NONCONFORMING_BOUNDARY,
    },
    CatalogEntry {
        id: "nonconforming-consistent",
        description: "the nonconforming decomposition with Galerkin masses: the Crouzeix–Raviart mass (diagonal, already consistent) as M0, the consistent P1 mass as co-potential mass (M2 stored as its sparse inverse)",
        preconditions: ANY_MESH,
        needs_delaunay: false,
        build: |mesh| Ok(Box::new(Nonconforming::consistent(mesh)?)),
        build_with_boundary: |mesh, boundary| {
            Ok(Box::new(Nonconforming::consistent_with_boundary(mesh, boundary)?))
        },
        boundary_conditions: BOTH,
        boundary_meanings: NONCONFORMING_BOUNDARY,
    },
    CatalogEntry {
        id: "dec-barycentric",
        description: "DEC 1-forms: 0-forms on vertices, 1-forms on edges, 2-forms on faces; ⋆0 barycentric vertex areas, ⋆1 cotan weights, ⋆2 = 1/area; Whitney sampling",
        preconditions: DELAUNAY,
        needs_delaunay: true,
        build: |mesh| Ok(Box::new(DecComplex::new(mesh, MassLumping::Barycentric)?)),
        build_with_boundary: |mesh, boundary| {
            Ok(Box::new(DecComplex::with_boundary(mesh, MassLumping::Barycentric, boundary)?))
        },
        boundary_conditions: BOTH,
        boundary_meanings: DEC_BOUNDARY,
    },
    CatalogEntry {
        id: "dec-circumcentric",
        description: "DEC 1-forms with ⋆0 the mixed-Voronoi (circumcentric on non-obtuse triangles) vertex areas; ⋆1 cotan weights, ⋆2 = 1/area; Whitney sampling",
        preconditions: DELAUNAY,
        needs_delaunay: true,
        build: |mesh| Ok(Box::new(DecComplex::new(mesh, MassLumping::Voronoi)?)),
        build_with_boundary: |mesh, boundary| {
            Ok(Box::new(DecComplex::with_boundary(mesh, MassLumping::Voronoi, boundary)?))
        },
        boundary_conditions: BOTH,
        boundary_meanings: DEC_BOUNDARY,
    },
    CatalogEntry {
        id: "whitney-galerkin",
        description: "Whitney forms with Galerkin masses (FEEC's lowest order): DEC's d0, d1 and Whitney sampling; M0 the consistent P1 mass, M1 the Whitney mass ∫⟨W_e, W_f⟩ (sparse, positive definite on every mesh), M2 = 1/area",
        preconditions: ANY_MESH,
        needs_delaunay: false,
        build: |mesh| Ok(Box::new(WhitneyGalerkin::new(mesh)?)),
        build_with_boundary: |mesh, boundary| {
            Ok(Box::new(WhitneyGalerkin::with_boundary(mesh, boundary)?))
        },
        boundary_conditions: BOTH,
        boundary_meanings: DEC_BOUNDARY,
    },
];

/// Every discretization, in the order `tvf discretizations` lists them.
pub fn catalog() -> &'static [CatalogEntry] {
    &CATALOG
}

/// An id the catalog does not know.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("unknown discretization '{id}'; the catalog has: {known}")]
pub struct UnknownDiscretization {
    /// The id asked for.
    pub id: String,
    /// The known ids, comma-separated.
    pub known: String,
}

/// The entry with id `id`. A complex's id on a mesh with boundary, `{entry id}+{boundary}`, also
/// finds its entry (see [`split_complex_id`]).
pub fn catalog_entry(id: &str) -> Result<&'static CatalogEntry, UnknownDiscretization> {
    let id = split_complex_id(id).0;
    CATALOG
        .iter()
        .find(|entry| entry.id == id)
        .ok_or_else(|| UnknownDiscretization {
            id: id.to_string(),
            known: CATALOG.iter().map(|e| e.id).collect::<Vec<_>>().join(", "),
        })
}

/// Splits a complex id into the catalog id and the boundary condition it names:
/// `conforming-barycentric+normal` → (`conforming-barycentric`, `Some(Normal)`);
/// `conforming-barycentric` → (`conforming-barycentric`, `None`) (a closed mesh).
pub fn split_complex_id(id: &str) -> (&str, Option<BoundaryCondition>) {
    match id.split_once('+') {
        Some((entry, boundary)) => match BoundaryCondition::from_name(boundary) {
            Some(condition) => (entry, Some(condition)),
            None => (id, None),
        },
        None => (id, None),
    }
}

/// Why [`build_complex`] could not build a complex.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CatalogBuildError {
    /// The id names no catalog entry.
    #[error(transparent)]
    Unknown(#[from] UnknownDiscretization),
    /// The entry refused the mesh (a precondition or the boundary condition).
    #[error("cannot build the discretization '{id}' (needs: {preconditions}): {source}")]
    Refused {
        /// The entry's id.
        id: &'static str,
        /// What the entry needs of the mesh ([`CatalogEntry::preconditions`]).
        preconditions: &'static str,
        /// The entry's error.
        source: DiscretizationError,
    },
}

/// Builds the complex named by `id` on `mesh`: a catalog id (built with `boundary`, the
/// default if `None`), or a complex id `{catalog id}+{condition}` as basis files store it,
/// whose own condition is used.
pub fn build_complex(
    id: &str,
    boundary: Option<BoundaryCondition>,
    mesh: &SurfaceMesh,
) -> Result<BoxedComplex, CatalogBuildError> {
    let (entry_id, named_boundary) = split_complex_id(id);
    let entry = catalog_entry(entry_id)?;
    let boundary = named_boundary.or(boundary).unwrap_or_default();
    entry
        .build_with(mesh, boundary)
        .map_err(|source| CatalogBuildError::Refused {
            id: entry.id,
            preconditions: entry.preconditions,
            source,
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_unique_kebab_case_and_match_the_built_complex() {
        let mesh = tvf_core::generate::icosphere(1);
        let mut seen = std::collections::HashSet::new();
        for entry in catalog() {
            assert!(seen.insert(entry.id), "duplicate id {}", entry.id);
            assert!(entry
                .id
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'));
            let complex = (entry.build)(&mesh).unwrap();
            assert_eq!(complex.id(), entry.id);
        }
        assert!(catalog_entry(DEFAULT_DISCRETIZATION).is_ok());
        let unknown = catalog_entry("nope").unwrap_err().to_string();
        assert!(unknown.contains("dec-circumcentric"), "{unknown}");
    }
}
