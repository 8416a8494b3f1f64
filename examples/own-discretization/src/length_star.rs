//! The entry `dec-length-star`: a DEC-like discretization of your own — tvf's primal forms
//! (`tvf_discretizations::PrimalForms`: the incidences `d0`, `d1`, the node spaces with both
//! boundary conditions, Whitney sampling and point evaluation, all assembled by
//! `PrimalFormComplex::assemble`) with Hodge stars this crate computes itself:
//!
//! - `⋆1 = (cot α + cot β)/2` per edge, the ratio of circumcentric dual to primal edge length,
//!   from the **edge lengths alone** (intrinsic: `cot α = (b² + c² − a²) / 4A` in a triangle of
//!   sides `a`, `b`, `c`, `A` by Heron's formula in its stable form). Positive exactly on
//!   Delaunay meshes; other meshes are refused.
//! - `⋆0` the barycentric vertex areas (a third of each incident triangle), `⋆2 = 1/area`.
//!
//! On a triangle mesh in space these are `dec-barycentric`'s stars up to round-off (the tests
//! compare them); the point of the entry is the route: any star you compute from the mesh plugs
//! into the same complex, and the conformance suite — its accuracy checks included — checks it
//! as it checks the built-in entries.

use tvf_core::discretization::{BoundaryCondition, DiscretizationError, Mass};
use tvf_core::TriangleMesh;
use tvf_discretizations::face_geometry::FaceGeometry;
use tvf_discretizations::{
    inverse_face_areas, BoxedComplex, CatalogEntry, PrimalFormComplex, DELAUNAY_TOLERANCE,
};

/// The id of the entry.
pub const ID: &str = "dec-length-star";

/// The marker of the masses of [`LengthStarComplex`] (the masses themselves are stored in the
/// complex's parts).
#[derive(Debug, Clone, Copy)]
pub struct LengthStars;

/// DEC on primal forms with the stars of this module.
pub type LengthStarComplex = PrimalFormComplex<LengthStars>;

/// The catalog entry [`ID`], with both boundary conditions of primal forms.
pub fn length_star_entry() -> CatalogEntry {
    CatalogEntry::new(
        ID,
        "DEC 1-forms with ⋆1 computed from edge lengths alone, ⋆0 barycentric, ⋆2 = 1/area; \
         Whitney sampling (example crate own-discretization)",
        |mesh, boundary| -> Result<BoxedComplex, _> {
            Ok(Box::new(length_star_complex(mesh, boundary)?))
        },
    )
    .with_preconditions("a Delaunay mesh: cot α + cot β > 0 on every edge (⋆1 positive)")
    .needing_delaunay()
    .with_boundary_condition(
        BoundaryCondition::Tangential,
        "absolute forms: every vertex, edge and face free",
    )
    .with_boundary_condition(
        BoundaryCondition::Normal,
        "relative forms: 0- and 1-forms zero on the boundary",
    )
}

/// The complex of `mesh` under `boundary`; fails on a degenerate face or a mesh that is not
/// Delaunay.
pub fn length_star_complex(
    mesh: &TriangleMesh,
    boundary: BoundaryCondition,
) -> Result<LengthStarComplex, DiscretizationError> {
    let geometry = FaceGeometry::new(mesh)?;
    let star = edge_star_from_lengths(mesh);
    let not_delaunay = |s: f64| 2.0 * s <= DELAUNAY_TOLERANCE;
    if let Some(first) = star.iter().position(|&s| not_delaunay(s)) {
        return Err(DiscretizationError::NotDelaunay {
            count: star.iter().filter(|&&s| not_delaunay(s)).count(),
            first,
            value: 2.0 * star[first],
            tolerance: DELAUNAY_TOLERANCE,
        });
    }
    let mut vertex_areas = vec![0.0; mesh.vertex_count()];
    for (face, area) in mesh.faces().iter().zip(&geometry.areas) {
        for &v in face {
            vertex_areas[v] += area / 3.0;
        }
    }
    PrimalFormComplex::assemble(ID, mesh, &geometry, boundary, |[vertices, edges, faces]| {
        Ok([
            Mass::diagonal_positive_on_used_nodes(
                "M0 (⋆0, barycentric vertex areas)",
                vertex_areas,
                &vertices.components,
            )?,
            Mass::diagonal_positive_on_used_nodes(
                "M1 (⋆1 from edge lengths)",
                star,
                &edges.components,
            )?,
            inverse_face_areas("M2 (⋆2, inverse face areas)", &geometry, faces)?,
        ])
    })
}

/// `(cot α + cot β)/2` per edge (one cotangent on a boundary edge) from the edge lengths: in a
/// triangle with sides `a` (opposite the corner), `b`, `c`, `cot = (b² + c² − a²) / 4A`.
pub fn edge_star_from_lengths(mesh: &TriangleMesh) -> Vec<f64> {
    let p = mesh.positions();
    let length = |e: usize| {
        let [a, b] = mesh.edges()[e];
        (0..3)
            .map(|k| (p[a][k] - p[b][k]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let mut star = vec![0.0; mesh.edge_count()];
    for edges in mesh.face_edges() {
        // face_edges()[t][c] is the edge opposite corner c.
        let l = edges.map(length);
        let area = heron(l);
        for c in 0..3 {
            let (a, b, d) = (l[c], l[(c + 1) % 3], l[(c + 2) % 3]);
            star[edges[c]] += (b * b + d * d - a * a) / (4.0 * area) / 2.0;
        }
    }
    star
}

/// The area of a triangle with sides `l`, by Heron's formula in the form that is stable for
/// thin triangles (sides sorted `a ≥ b ≥ c`).
fn heron(mut l: [f64; 3]) -> f64 {
    l.sort_by(|x, y| y.total_cmp(x));
    let [a, b, c] = l;
    0.25 * ((a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c)))
        .max(0.0)
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_conformance::corpus::delaunay_flips;
    use tvf_core::discretization::HodgeComplex;
    use tvf_core::generate::{hemisphere, icosphere, torus};
    use tvf_discretizations::build_complex;

    /// On meshes in space the stars are `dec-barycentric`'s (to round-off), closed and open,
    /// and a mesh that is not Delaunay is refused as DEC refuses it.
    #[test]
    fn the_stars_are_dec_barycentric_s() {
        for mesh in [icosphere(2), delaunay_flips(&hemisphere(4))] {
            for boundary in BoundaryCondition::ALL {
                let own = length_star_complex(&mesh, boundary).unwrap();
                let dec = build_complex("dec-barycentric", Some(boundary), &mesh).unwrap();
                assert_eq!(own.d0(), dec.d0());
                assert_eq!(own.d1(), dec.d1());
                for (ours, theirs) in [(own.m0(), dec.m0()), (own.m1(), dec.m1())] {
                    let (a, b) = (
                        ours.diagonal_values().unwrap(),
                        theirs.diagonal_values().unwrap(),
                    );
                    for (x, y) in a.iter().zip(b) {
                        assert!((x - y).abs() <= 1e-12 * y.abs().max(1e-3), "{x} vs {y}");
                    }
                }
            }
        }
        let thin = torus(1.0, 0.4, 8, 5).unwrap();
        let refused = length_star_complex(&thin, BoundaryCondition::Tangential);
        assert!(
            matches!(refused, Err(DiscretizationError::NotDelaunay { .. })),
            "{refused:?}"
        );
    }
}
