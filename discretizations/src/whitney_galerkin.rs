//! [`WhitneyGalerkin`]: primal forms with Galerkin masses — the lowest-order finite element
//! complex of exterior calculus (P1, Whitney 1-forms, P0) on a triangle mesh.

use crate::consistent_mass::consistent_p1_mass;
use crate::face_geometry::FaceGeometry;
use crate::primal_form_complex::{inverse_face_areas, PrimalFormComplex};
use crate::whitney_mass::whitney_mass;
use tvf_core::discretization::{BoundaryCondition, DiscretizationError, Mass};
use tvf_core::TriangleMesh;

/// The complex of Whitney forms with their `L²` (Galerkin) inner products, catalog id
/// `whitney-galerkin`:
///
/// ```text
/// P1 (V) --d0--> Whitney 1-forms (E) --d1--> P0 (F)
///   M0              M1                        M2
/// ```
///
/// - `d0`, `d1`, the orientation of the edges (`a → b`, `a < b`), the 1-forms (`x_e` the
///   integral of the field along edge `e`) and the boundary conditions are DEC's
///   ([`crate::DecComplex`]); so are the sampling (Whitney interpolation, [`crate::WhitneySampling`])
///   and point evaluation (0-forms linear, 2-forms constant per face).
/// - `M0` is the consistent P1 mass `Σ_T |T| (1 + δ_ij)/12` ([`crate::consistent_p1_mass`],
///   sparse, area).
/// - `M1` is the Whitney mass `Σ_T ∫_T ⟨W_e, W_f⟩` ([`crate::whitney_mass`], sparse,
///   dimensionless): the field's `L²` norm is `xᵀ M1 x` exactly.
/// - `M2 = 1/area` per face (diagonal, as DEC's `⋆2`): a 2-form is stored by its integral, and
///   `M2⁻¹ = |T|` is the `L²` mass of the piecewise constants.
///
/// `M1` is positive definite on every mesh without degenerate faces: unlike DEC's `⋆1`, no
/// Delaunay condition. The exact eigenproblem `(d0ᵀ M1 d0, M0)` is P1 (the cotan matrix with the
/// consistent mass); the co-exact problem `(d1 M1⁻¹ d1ᵀ, M2⁻¹)` is the mixed RT0–P0 Laplacian
/// on faces (rotated by +π/2 in each face, the Whitney forms are the lowest-order
/// Raviart–Thomas functions, `d1` their divergence), dense in `d1 M1⁻¹ d1ᵀ` and solved in mixed
/// form downstream. There is no rotation `J` on 1-forms, hence no "other family".
///
/// On a mesh with boundary, [`BoundaryCondition::Tangential`] gives absolute forms and
/// [`BoundaryCondition::Normal`] relative forms (boundary vertices and edges fixed to zero),
/// exactly as for DEC. The seam restricts every mass to the free nodes of its space, so `M1⁻¹`
/// is the inverse of the Whitney mass of the interior edges and nothing leaks into a fixed edge.
pub type WhitneyGalerkin = PrimalFormComplex<GalerkinMasses>;

/// The masses of [`WhitneyGalerkin`]: the `L²` (Galerkin) inner products of P1, Whitney 1-forms
/// and P0.
#[derive(Debug, Clone, Copy)]
pub struct GalerkinMasses;

impl PrimalFormComplex<GalerkinMasses> {
    /// The complex of `mesh` (the default boundary condition on a mesh with boundary). Fails on
    /// a degenerate face.
    pub fn new(mesh: &TriangleMesh) -> Result<Self, DiscretizationError> {
        Self::with_boundary(mesh, BoundaryCondition::default())
    }

    /// The complex with boundary condition `boundary`: absolute forms for
    /// [`BoundaryCondition::Tangential`], relative forms for [`BoundaryCondition::Normal`]. The
    /// id gets `+{boundary}` appended on a mesh with boundary.
    pub fn with_boundary(
        mesh: &TriangleMesh,
        boundary: BoundaryCondition,
    ) -> Result<Self, DiscretizationError> {
        let geometry = FaceGeometry::new(mesh)?;
        Self::assemble(
            "whitney-galerkin",
            mesh,
            &geometry,
            boundary,
            |[_, _, faces]| {
                Ok([
                    Mass::sparse(
                        "M0 (the consistent P1 mass)",
                        consistent_p1_mass(mesh, &geometry),
                    )?,
                    Mass::sparse(
                        "M1 (the Whitney 1-form mass)",
                        whitney_mass(mesh, &geometry),
                    )?,
                    inverse_face_areas("M2 (inverse face areas)", &geometry, faces)?,
                ])
            },
        )
    }
}
