//! tvf's own discretizations, one [`CatalogEntry`] each, in the order `tvf discretizations`
//! lists them ([`crate::Catalog::builtin`]). A new discretization of tvf's is one more entry
//! here (and one suite line in `conformance/tests/conformance/catalog_suites.rs`).

use crate::catalog_entry::{BoxedComplex, CatalogEntry};
use crate::{
    Conforming, DecComplex, MassLumping, Nonconforming, PolygonDec, WhitneyGalerkin,
    DEFAULT_STABILISATION,
};
use tvf_core::discretization::BoundaryCondition::{Normal, Tangential};

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

const DELAUNAY: &str = "a Delaunay mesh: cot α + cot β > 0 on every edge (⋆1 positive)";

/// An entry offering both boundary conditions, `tangential` (the default) and `normal`, with
/// what each fixes.
fn both_conditions(entry: CatalogEntry, [tangential, normal]: [&str; 2]) -> CatalogEntry {
    entry
        .with_boundary_condition(Tangential, tangential)
        .with_boundary_condition(Normal, normal)
}

/// tvf's entries, [`crate::DEFAULT_DISCRETIZATION`] first.
pub(crate) fn builtin_entries() -> Vec<CatalogEntry> {
    use MassLumping::{Barycentric, Voronoi};
    vec![
        both_conditions(
            CatalogEntry::new(
                "conforming-barycentric",
                "the paper's conforming decomposition: P1 potentials, face fields, Crouzeix–Raviart co-potentials; barycentric lumped masses",
                |mesh, boundary| -> Result<BoxedComplex, _> {
                    Ok(Box::new(Conforming::with_boundary(mesh, Barycentric, boundary)?))
                },
            ),
            CONFORMING_BOUNDARY,
        ),
        both_conditions(
            CatalogEntry::new(
                "conforming-voronoi",
                "the conforming decomposition with mixed-Voronoi vertex and midpoint-Voronoi edge masses",
                |mesh, boundary| -> Result<BoxedComplex, _> {
                    Ok(Box::new(Conforming::with_boundary(mesh, Voronoi, boundary)?))
                },
            ),
            CONFORMING_BOUNDARY,
        ),
        both_conditions(
            CatalogEntry::new(
                "conforming-consistent",
                "the conforming decomposition with Galerkin masses: the consistent P1 mass ∫φᵢφⱼ (sparse) as M0, the Crouzeix–Raviart mass (diagonal, already consistent)",
                |mesh, boundary| -> Result<BoxedComplex, _> {
                    Ok(Box::new(Conforming::consistent_with_boundary(mesh, boundary)?))
                },
            ),
            CONFORMING_BOUNDARY,
        ),
        both_conditions(
            CatalogEntry::new(
                "nonconforming-barycentric",
                "the nonconforming decomposition: Crouzeix–Raviart potentials, face fields, P1 co-potentials; barycentric lumped masses",
                |mesh, boundary| -> Result<BoxedComplex, _> {
                    Ok(Box::new(Nonconforming::with_boundary(mesh, Barycentric, boundary)?))
                },
            ),
            NONCONFORMING_BOUNDARY,
        ),
        both_conditions(
            CatalogEntry::new(
                "nonconforming-voronoi",
                "the nonconforming decomposition with mixed-Voronoi vertex and midpoint-Voronoi edge masses",
                |mesh, boundary| -> Result<BoxedComplex, _> {
                    Ok(Box::new(Nonconforming::with_boundary(mesh, Voronoi, boundary)?))
                },
            ),
            NONCONFORMING_BOUNDARY,
        ),
        both_conditions(
            CatalogEntry::new(
                "nonconforming-consistent",
                "the nonconforming decomposition with Galerkin masses: the Crouzeix–Raviart mass (diagonal, already consistent) as M0, the consistent P1 mass as co-potential mass (M2 stored as its sparse inverse)",
                |mesh, boundary| -> Result<BoxedComplex, _> {
                    Ok(Box::new(Nonconforming::consistent_with_boundary(mesh, boundary)?))
                },
            ),
            NONCONFORMING_BOUNDARY,
        ),
        both_conditions(
            CatalogEntry::new(
                "dec-barycentric",
                "DEC 1-forms: 0-forms on vertices, 1-forms on edges, 2-forms on faces; ⋆0 barycentric vertex areas, ⋆1 cotan weights, ⋆2 = 1/area; Whitney sampling",
                |mesh, boundary| -> Result<BoxedComplex, _> {
                    Ok(Box::new(DecComplex::with_boundary(mesh, Barycentric, boundary)?))
                },
            )
            .with_preconditions(DELAUNAY)
            .needing_delaunay(),
            DEC_BOUNDARY,
        ),
        both_conditions(
            CatalogEntry::new(
                "dec-circumcentric",
                "DEC 1-forms with ⋆0 the mixed-Voronoi (circumcentric on non-obtuse triangles) vertex areas; ⋆1 cotan weights, ⋆2 = 1/area; Whitney sampling",
                |mesh, boundary| -> Result<BoxedComplex, _> {
                    Ok(Box::new(DecComplex::with_boundary(mesh, Voronoi, boundary)?))
                },
            )
            .with_preconditions(DELAUNAY)
            .needing_delaunay(),
            DEC_BOUNDARY,
        ),
        both_conditions(
            CatalogEntry::new(
                "whitney-galerkin",
                "Whitney forms with Galerkin masses (FEEC's lowest order): DEC's d0, d1 and Whitney sampling; M0 the consistent P1 mass, M1 the Whitney mass ∫⟨W_e, W_f⟩ (sparse, positive definite on every mesh), M2 = 1/area",
                |mesh, boundary| -> Result<BoxedComplex, _> {
                    Ok(Box::new(WhitneyGalerkin::with_boundary(mesh, boundary)?))
                },
            ),
            DEC_BOUNDARY,
        ),
        polygon_dec_entry(DEFAULT_STABILISATION),
    ]
}

/// The catalog entry of polygonal DEC ([`PolygonDec`]) with stabilisation weight `beta`, id
/// [`crate::polygon_dec_id`]`(beta)` (`polygon-dec` for the built-in `β = 1`); it builds on
/// triangle and polygon meshes. Add it to a catalog for another `β`.
pub fn polygon_dec_entry(beta: f64) -> CatalogEntry {
    both_conditions(
        CatalogEntry::on_any_mesh(
            crate::polygon_dec_id(beta),
            format!(
                "polygonal DEC (de Goes, Butts, Desbrun 2020) on polygon and triangle meshes: 0-forms on vertices, 1-forms on edges, 2-forms on faces; ⋆0 polygon areas split among corners, ⋆1 = Σ A_f U_fᵀU_f + β P_fᵀP_f (sparse, β = {beta}), ⋆2 = 1/area; one vector per polygon (the sharp)"
            ),
            move |mesh, boundary| -> Result<BoxedComplex, _> {
                Ok(Box::new(PolygonDec::with_boundary(mesh, boundary, beta)?))
            },
        ),
        DEC_BOUNDARY,
    )
}
