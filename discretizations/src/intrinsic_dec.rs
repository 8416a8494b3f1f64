//! [`IntrinsicDec`]: discrete exterior calculus on an intrinsic triangulation — the complex of
//! `dec-barycentric` and `dec-circumcentric` built from edge lengths, with sampling and point
//! evaluation on the input mesh through the correspondence.

use crate::intrinsic_delaunay::IntrinsicInput;
use crate::intrinsic_primal_forms::IntrinsicPrimalFormComplex;
use crate::{HodgeStars, MassLumping, DELAUNAY_TOLERANCE};
use tvf_core::discretization::{BoundaryCondition, DiscretizationError, Mass};
use tvf_core::TriangleMesh;

/// The DEC complex of primal forms on an intrinsic triangulation (`dec-barycentric` or
/// `dec-circumcentric` with the intrinsic Delaunay modifier): the incidences, boundary
/// conditions, nodes, sampling and point evaluation of [`IntrinsicPrimalFormComplex`], with the
/// diagonal Hodge stars from the edge lengths:
///
/// - `⋆0`: barycentric or mixed-Voronoi vertex areas
///   ([`IntrinsicTriangulation::barycentric_vertex_areas`],
///   [`IntrinsicTriangulation::mixed_voronoi_vertex_areas`]); inserted vertices are nodes like
///   the input's.
/// - `⋆1 = (cot α + cot β)/2` ([`IntrinsicTriangulation::edge_hodge_star`]): construction fails
///   with [`DiscretizationError::NotDelaunay`] if some edge has `cot α + cot β ≤`
///   [`DELAUNAY_TOLERANCE`] (after flips only: cocircular neighbours, boundary edges opposite an
///   obtuse angle; never after refinement).
/// - `⋆2 = 1/area` per intrinsic face.
///
/// [`IntrinsicTriangulation::barycentric_vertex_areas`]: tvf_core::intrinsic::IntrinsicTriangulation::barycentric_vertex_areas
/// [`IntrinsicTriangulation::mixed_voronoi_vertex_areas`]: tvf_core::intrinsic::IntrinsicTriangulation::mixed_voronoi_vertex_areas
/// [`IntrinsicTriangulation::edge_hodge_star`]: tvf_core::intrinsic::IntrinsicTriangulation::edge_hodge_star
pub type IntrinsicDec = IntrinsicPrimalFormComplex<HodgeStars>;

impl IntrinsicPrimalFormComplex<HodgeStars> {
    /// The DEC complex with id `id` on the intrinsic triangulation `input` of `mesh`, vertex areas
    /// by `lumping`, boundary condition `boundary` (on a mesh with boundary).
    pub fn new(
        mesh: &TriangleMesh,
        input: &IntrinsicInput,
        id: &str,
        lumping: MassLumping,
        boundary: BoundaryCondition,
    ) -> Result<Self, DiscretizationError> {
        let tri = &input.triangulation;
        let edge_star = tri.edge_hodge_star();
        let not_delaunay = |s: f64| 2.0 * s <= DELAUNAY_TOLERANCE;
        if let Some(first) = edge_star.iter().position(|&s| not_delaunay(s)) {
            return Err(DiscretizationError::NotDelaunay {
                count: edge_star.iter().filter(|&&s| not_delaunay(s)).count(),
                first,
                value: 2.0 * edge_star[first],
                tolerance: DELAUNAY_TOLERANCE,
            });
        }
        let vertex_areas = match lumping {
            MassLumping::Barycentric => tri.barycentric_vertex_areas(),
            MassLumping::Voronoi => tri.mixed_voronoi_vertex_areas(),
        };
        Self::assemble(mesh, input, id, boundary, |[vertices, edges, faces]| {
            Ok([
                Mass::diagonal_positive_on_used_nodes(
                    "M0 (⋆0, vertex areas)",
                    vertex_areas,
                    &vertices.components,
                )?,
                Mass::diagonal_positive_on_used_nodes(
                    "M1 (⋆1, the edge Hodge star)",
                    edge_star,
                    &edges.components,
                )?,
                Mass::diagonal_positive_on_used_nodes(
                    "M2 (⋆2, inverse face areas)",
                    tri.face_areas().iter().map(|a| 1.0 / a).collect(),
                    &faces.components,
                )?,
            ])
        })
    }
}
