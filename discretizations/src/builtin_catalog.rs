//! tvf's own discretizations, one [`CatalogEntry`] each, in the order `tvf discretizations`
//! lists them ([`crate::Catalog::builtin`]). A new discretization of tvf's is one more entry
//! here (and one suite line in `conformance/tests/conformance/catalog_suites.rs`).

use crate::catalog_entry::{BoxedComplex, CatalogEntry};
use crate::MassLumping::{Barycentric, Voronoi};
use crate::SpaceMasses::{self, Lumped};
use crate::{
    Conforming, DecComplex, ElementFamily, IntrinsicDec, IntrinsicFiniteElement, IntrinsicInput,
    IntrinsicWhitneyGalerkin, Nonconforming, PolygonDec, WhitneyGalerkin, DEFAULT_STABILISATION,
};
use tvf_core::discretization::BoundaryCondition::{self, Normal, Tangential};
use tvf_core::discretization::DiscretizationError;
use tvf_core::TriangleMesh;

/// The family of an entry: what its boundary conditions fix (`tangential`, the default, then
/// `normal`) and what it needs of the mesh.
#[derive(Clone, Copy)]
enum Family {
    Conforming,
    Nonconforming,
    /// DEC: a diagonal `⋆1`, positive on Delaunay meshes only.
    Dec,
    /// Whitney forms with Galerkin masses: DEC's boundary conditions on any mesh.
    Whitney,
}

impl Family {
    /// What `tangential` and `normal` fix.
    fn boundary_meanings(self) -> [&'static str; 2] {
        match self {
            Family::Conforming => [
                "Crouzeix–Raviart co-potentials zero at boundary edge midpoints",
                "P1 potentials zero at boundary vertices",
            ],
            Family::Nonconforming => [
                "P1 co-potentials zero at boundary vertices",
                "Crouzeix–Raviart potentials zero at boundary edge midpoints",
            ],
            Family::Dec | Family::Whitney => [
                "absolute forms, nothing fixed",
                "relative forms: 0-forms zero at boundary vertices, 1-forms zero on boundary edges",
            ],
        }
    }
}

/// A constructor of tvf's own: the mesh and the boundary condition in, the complex out.
type Build = fn(&TriangleMesh, BoundaryCondition) -> Result<BoxedComplex, DiscretizationError>;

/// A constructor of tvf's own from edge lengths (see [`crate::IntrinsicConstructor`]).
type IntrinsicBuild = fn(
    &TriangleMesh,
    &IntrinsicInput,
    &str,
    BoundaryCondition,
) -> Result<BoxedComplex, DiscretizationError>;

/// One of tvf's entries: id, family, one-line description, constructor, and constructor from
/// edge lengths (every triangle entry of tvf's has one).
struct Builtin {
    id: &'static str,
    family: Family,
    description: &'static str,
    build: Build,
    intrinsic: IntrinsicBuild,
}

/// tvf's entries, [`crate::DEFAULT_DISCRETIZATION`] first.
const BUILTIN: [Builtin; 9] = [
    Builtin {
        id: "conforming-barycentric",
        family: Family::Conforming,
        description: "the paper's conforming decomposition: P1 potentials, face fields, Crouzeix–Raviart co-potentials; barycentric lumped masses",
        build: |mesh, boundary| Ok(Box::new(Conforming::with_boundary(mesh, Barycentric, boundary)?)),
        intrinsic: |mesh, input, id, boundary| Ok(Box::new(IntrinsicFiniteElement::new(mesh, input, id, ElementFamily::Conforming, Lumped(Barycentric), boundary)?)),
    },
    Builtin {
        id: "conforming-voronoi",
        family: Family::Conforming,
        description: "the conforming decomposition with mixed-Voronoi vertex and midpoint-Voronoi edge masses",
        build: |mesh, boundary| Ok(Box::new(Conforming::with_boundary(mesh, Voronoi, boundary)?)),
        intrinsic: |mesh, input, id, boundary| Ok(Box::new(IntrinsicFiniteElement::new(mesh, input, id, ElementFamily::Conforming, Lumped(Voronoi), boundary)?)),
    },
    Builtin {
        id: "conforming-consistent",
        family: Family::Conforming,
        description: "the conforming decomposition with Galerkin masses: the consistent P1 mass ∫φᵢφⱼ (sparse) as M0, the Crouzeix–Raviart mass (diagonal, already consistent)",
        build: |mesh, boundary| Ok(Box::new(Conforming::consistent_with_boundary(mesh, boundary)?)),
        intrinsic: |mesh, input, id, boundary| Ok(Box::new(IntrinsicFiniteElement::new(mesh, input, id, ElementFamily::Conforming, SpaceMasses::Consistent, boundary)?)),
    },
    Builtin {
        id: "nonconforming-barycentric",
        family: Family::Nonconforming,
        description: "the nonconforming decomposition: Crouzeix–Raviart potentials, face fields, P1 co-potentials; barycentric lumped masses",
        build: |mesh, boundary| Ok(Box::new(Nonconforming::with_boundary(mesh, Barycentric, boundary)?)),
        intrinsic: |mesh, input, id, boundary| Ok(Box::new(IntrinsicFiniteElement::new(mesh, input, id, ElementFamily::Nonconforming, Lumped(Barycentric), boundary)?)),
    },
    Builtin {
        id: "nonconforming-voronoi",
        family: Family::Nonconforming,
        description: "the nonconforming decomposition with mixed-Voronoi vertex and midpoint-Voronoi edge masses",
        build: |mesh, boundary| Ok(Box::new(Nonconforming::with_boundary(mesh, Voronoi, boundary)?)),
        intrinsic: |mesh, input, id, boundary| Ok(Box::new(IntrinsicFiniteElement::new(mesh, input, id, ElementFamily::Nonconforming, Lumped(Voronoi), boundary)?)),
    },
    Builtin {
        id: "nonconforming-consistent",
        family: Family::Nonconforming,
        description: "the nonconforming decomposition with Galerkin masses: the Crouzeix–Raviart mass (diagonal, already consistent) as M0, the consistent P1 mass as co-potential mass (M2 stored as its sparse inverse)",
        build: |mesh, boundary| Ok(Box::new(Nonconforming::consistent_with_boundary(mesh, boundary)?)),
        intrinsic: |mesh, input, id, boundary| Ok(Box::new(IntrinsicFiniteElement::new(mesh, input, id, ElementFamily::Nonconforming, SpaceMasses::Consistent, boundary)?)),
    },
    Builtin {
        id: "dec-barycentric",
        family: Family::Dec,
        description: "DEC 1-forms: 0-forms on vertices, 1-forms on edges, 2-forms on faces; ⋆0 barycentric vertex areas, ⋆1 cotan weights, ⋆2 = 1/area; Whitney sampling",
        build: |mesh, boundary| Ok(Box::new(DecComplex::with_boundary(mesh, Barycentric, boundary)?)),
        intrinsic: |mesh, input, id, boundary| Ok(Box::new(IntrinsicDec::new(mesh, input, id, Barycentric, boundary)?)),
    },
    Builtin {
        id: "dec-circumcentric",
        family: Family::Dec,
        description: "DEC 1-forms with ⋆0 the mixed-Voronoi (circumcentric on non-obtuse triangles) vertex areas; ⋆1 cotan weights, ⋆2 = 1/area; Whitney sampling",
        build: |mesh, boundary| Ok(Box::new(DecComplex::with_boundary(mesh, Voronoi, boundary)?)),
        intrinsic: |mesh, input, id, boundary| Ok(Box::new(IntrinsicDec::new(mesh, input, id, Voronoi, boundary)?)),
    },
    Builtin {
        id: "whitney-galerkin",
        family: Family::Whitney,
        description: "Whitney forms with Galerkin masses (FEEC's lowest order): DEC's d0, d1 and Whitney sampling; M0 the consistent P1 mass, M1 the Whitney mass ∫⟨W_e, W_f⟩ (sparse, positive definite on every mesh), M2 = 1/area",
        build: |mesh, boundary| Ok(Box::new(WhitneyGalerkin::with_boundary(mesh, boundary)?)),
        intrinsic: |mesh, input, id, boundary| Ok(Box::new(IntrinsicWhitneyGalerkin::new(mesh, input, id, boundary)?)),
    },
];

/// What a DEC entry needs of the mesh.
const DELAUNAY: &str = "a Delaunay mesh: cot α + cot β > 0 on every edge (⋆1 positive); any mesh with --intrinsic-delaunay";

/// tvf's entries as catalog entries, [`crate::DEFAULT_DISCRETIZATION`] first and polygonal DEC
/// last: both boundary conditions each, with what they fix.
pub(crate) fn builtin_entries() -> Vec<CatalogEntry> {
    BUILTIN
        .iter()
        .map(|builtin| {
            let entry = CatalogEntry::new(builtin.id, builtin.description, builtin.build)
                .with_intrinsic_constructor(builtin.intrinsic);
            let entry = with_both_conditions(entry, builtin.family);
            match builtin.family {
                Family::Dec => entry.with_preconditions(DELAUNAY).needing_delaunay(),
                _ => entry,
            }
        })
        .chain([polygon_dec_entry(DEFAULT_STABILISATION)])
        .collect()
}

/// `entry` offering both boundary conditions, `tangential` (the default) and `normal`, with
/// what each fixes in `family`.
fn with_both_conditions(entry: CatalogEntry, family: Family) -> CatalogEntry {
    let [tangential, normal] = family.boundary_meanings();
    entry
        .with_boundary_condition(Tangential, tangential)
        .with_boundary_condition(Normal, normal)
}

/// The catalog entry of polygonal DEC ([`PolygonDec`]) with stabilisation weight `beta`, id
/// [`crate::polygon_dec_id`]`(beta)` (`polygon-dec` for the built-in `β = 1`); it builds on
/// triangle and polygon meshes and has DEC's boundary conditions. Add it to a catalog for
/// another `β`.
pub fn polygon_dec_entry(beta: f64) -> CatalogEntry {
    let entry = CatalogEntry::on_any_mesh(
        crate::polygon_dec_id(beta),
        format!(
            "polygonal DEC (de Goes, Butts, Desbrun 2020) on polygon and triangle meshes: 0-forms on vertices, 1-forms on edges, 2-forms on faces; ⋆0 polygon areas split among corners, ⋆1 = Σ A_f U_fᵀU_f + β P_fᵀP_f (sparse, β = {beta}), ⋆2 = 1/area; one vector per polygon (the sharp)"
        ),
        move |mesh, boundary| -> Result<BoxedComplex, _> {
            Ok(Box::new(PolygonDec::with_boundary(mesh, boundary, beta)?))
        },
    );
    with_both_conditions(entry, Family::Dec)
}
