//! [`IntrinsicWhitneyGalerkin`]: Whitney forms with Galerkin masses on an intrinsic triangulation
//! — the complex of `whitney-galerkin` built from edge lengths.

use crate::consistent_mass::assemble_consistent_p1_mass;
use crate::intrinsic_delaunay::IntrinsicInput;
use crate::intrinsic_primal_forms::IntrinsicPrimalFormComplex;
use crate::planar_triangle::PlanarTriangle;
use crate::whitney_mass::assemble_whitney_mass;
use crate::GalerkinMasses;
use tvf_core::discretization::{BoundaryCondition, DiscretizationError, Mass};
use tvf_core::TriangleMesh;

/// Whitney forms with their `L²` (Galerkin) inner products on an intrinsic triangulation
/// (`whitney-galerkin` with the intrinsic Delaunay modifier): the incidences, boundary
/// conditions, nodes, Whitney sampling through the correspondence and point evaluation of
/// [`IntrinsicPrimalFormComplex`], with the masses of [`crate::WhitneyGalerkin`] assembled from
/// each intrinsic face laid out from its three lengths ([`PlanarTriangle::from_lengths`]):
///
/// - `M0`: the consistent P1 mass `Σ_T |T| (1 + δ_ij)/12` over the intrinsic faces (sparse).
/// - `M1`: the Whitney mass `Σ_T ∫_T ⟨W_e, W_f⟩`, each `W_e` oriented along its edge's reference
///   direction (sparse, positive definite: no Delaunay condition, so flips only suffice on
///   every mesh).
/// - `M2 = 1/area` per intrinsic face.
///
/// Every entry depends only on the areas and the inner products of the barycentric gradients,
/// which the lengths fix: on a mesh that is its own intrinsic Delaunay triangulation the
/// matrices are those of [`crate::WhitneyGalerkin`] to round-off (up to the signs of the boundary
/// edges whose reference direction is reversed, see [`tvf_core::intrinsic::IntrinsicTriangulation`]).
pub type IntrinsicWhitneyGalerkin = IntrinsicPrimalFormComplex<GalerkinMasses>;

impl IntrinsicPrimalFormComplex<GalerkinMasses> {
    /// The complex with id `id` on the intrinsic triangulation `input` of `mesh` with boundary
    /// condition `boundary` (on a mesh with boundary).
    pub fn new(
        mesh: &TriangleMesh,
        input: &IntrinsicInput,
        id: &str,
        boundary: BoundaryCondition,
    ) -> Result<Self, DiscretizationError> {
        let tri = &input.triangulation;
        let triangles = PlanarTriangle::of_intrinsic_faces(tri);
        let areas: Vec<f64> = triangles.iter().map(|t| t.area).collect();
        let m0 = assemble_consistent_p1_mass(tri.vertex_count(), tri.faces(), &areas);
        let signs = (0..tri.face_count()).map(|t| {
            tri.face_edge_orientations(t)
                .map(|forward| if forward { 1.0 } else { -1.0 })
        });
        let m1 = assemble_whitney_mass(
            tri.edge_count(),
            (0..tri.face_count()).map(|t| tri.face_edges(t)),
            signs,
            triangles.into_iter(),
        );
        Self::assemble(mesh, input, id, boundary, |[_, _, faces]| {
            Ok([
                Mass::sparse("M0 (the consistent P1 mass)", m0)?,
                Mass::sparse("M1 (the Whitney 1-form mass)", m1)?,
                Mass::diagonal_positive_on_used_nodes(
                    "M2 (inverse face areas)",
                    areas.iter().map(|a| 1.0 / a).collect(),
                    &faces.components,
                )?,
            ])
        })
    }
}
