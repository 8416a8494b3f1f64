//! [`DecComplex`]: discrete exterior calculus on primal forms — potentials on vertices, fields
//! as 1-forms on edges, co-potentials on faces, with diagonal Hodge stars.

use crate::face_geometry::FaceGeometry;
use crate::primal_form_complex::{inverse_face_areas, PrimalFormComplex};
use crate::MassLumping;
use tvf_core::discretization::{BoundaryCondition, DiscretizationError, Mass};
use tvf_core::TriangleMesh;

/// The DEC complex of primal forms (Desbrun, Kanso, Tong 2008; the setting of Fisher et al.
/// 2007):
///
/// ```text
/// 0-forms (V) --d0--> 1-forms (E) --d1--> 2-forms (F)
///     ⋆0                ⋆1                 ⋆2
/// ```
///
/// - A field is a 1-form: `x_e = ∫_e ⟨v, t⟩`, the field integrated along edge `e = (a, b)`,
///   `a < b`, from `a` to `b` (units length × field).
/// - `d0` (`E × V`): row `e = (a, b)` has `−1` at `a` and `+1` at `b` (`(d0 f)_e = f_b − f_a`).
/// - `d1` (`F × E`): row `t` has `±1` at its three edges, `+1` where the counter-clockwise
///   boundary of `t` runs `a → b` (the circulation around `t`).
/// - `M0 = ⋆0`: vertex areas, a [`MassLumping`] rule (barycentric thirds, or mixed Voronoi, which
///   is the circumcentric dual area on non-obtuse triangles).
/// - `M1 = ⋆1 = (cot α + cot β)/2` per edge (one cotangent on a boundary edge): the ratio of dual
///   to primal edge length. Positive exactly on (edge-)Delaunay meshes; construction fails with
///   [`DiscretizationError::NotDelaunay`] when some edge has `cot α + cot β ≤`
///   [`DELAUNAY_TOLERANCE`].
/// - `M2 = ⋆2 = 1/area` per face.
///
/// The exact eigenproblem `(d0ᵀ ⋆1 d0, ⋆0)` is the cotan Laplacian; the co-exact one
/// `(d1 ⋆1⁻¹ d1ᵀ, ⋆2⁻¹)` lives on faces. Sampling is Whitney interpolation
/// ([`WhitneySampling`]); there is no rotation `J` on 1-forms, hence no "other family".
///
/// On a mesh with boundary:
///
/// - [`BoundaryCondition::Tangential`]: **absolute** forms (every vertex, edge and face). The
///   co-exact problem has no constant kernel on a component with boundary (a boundary edge couples
///   its face to a zero outside, a Dirichlet condition on the dual graph) and the harmonic 1-forms
///   are the `2g + b − 1` Neumann fields.
/// - [`BoundaryCondition::Normal`]: **relative** forms, the cochains that vanish on the boundary.
///   Boundary vertices are Dirichlet nodes of the 0-forms (zero columns of `d0`) and boundary
///   edges Dirichlet nodes of the 1-forms (zero rows of `d0`, zero columns of `d1`, zero weight
///   in sampling); every face stays. The exact problem is the cotan Laplacian with Dirichlet
///   conditions, the co-exact one has the constants in its kernel (Neumann on the dual graph), and
///   the harmonic 1-forms are the `2g + b − 1` Dirichlet fields (relative cohomology, by
///   Lefschetz duality of the same dimension as the absolute one). A relative 1-form's Whitney
///   field has no component along the boundary: it is normal there.
pub type DecComplex = PrimalFormComplex<HodgeStars>;

/// The masses of [`DecComplex`]: the diagonal Hodge stars `⋆0`, `⋆1`, `⋆2`.
#[derive(Debug, Clone, Copy)]
pub struct HodgeStars;

/// Smallest `cot α + cot β` (dimensionless) an edge of a DEC mesh may have. A cyclic
/// quadrilateral split by a diagonal (a rectangle, a cell of a quad torus) has exactly 0 there,
/// which round-off turns into values like ±3e-17; accepting those would give `⋆1⁻¹ ≈ 1e16` and a
/// meaningless co-exact stiffness, so they are refused with the truly negative ones.
pub const DELAUNAY_TOLERANCE: f64 = 1e-12;

impl PrimalFormComplex<HodgeStars> {
    /// The DEC complex of `mesh` with vertex areas `⋆0` by `lumping`, catalog id
    /// `dec-barycentric` or `dec-circumcentric` (for [`MassLumping::Voronoi`]). Fails on a
    /// degenerate face or a mesh that is not Delaunay.
    pub fn new(mesh: &TriangleMesh, lumping: MassLumping) -> Result<Self, DiscretizationError> {
        Self::with_boundary(mesh, lumping, BoundaryCondition::default())
    }

    /// [`DecComplex::new`] with boundary condition `boundary`: on a mesh with boundary absolute
    /// forms for [`BoundaryCondition::Tangential`], relative forms for
    /// [`BoundaryCondition::Normal`] (see [`DecComplex`]). The id gets `+{boundary}` appended on a
    /// mesh with boundary.
    pub fn with_boundary(
        mesh: &TriangleMesh,
        lumping: MassLumping,
        boundary: BoundaryCondition,
    ) -> Result<Self, DiscretizationError> {
        let id = match lumping {
            MassLumping::Barycentric => "dec-barycentric",
            MassLumping::Voronoi => "dec-circumcentric",
        };
        let geometry = FaceGeometry::new(mesh)?;
        let edge_star = edge_hodge_star(mesh, &geometry);
        let not_delaunay = |s: f64| 2.0 * s <= DELAUNAY_TOLERANCE;
        if let Some(first) = edge_star.iter().position(|&s| not_delaunay(s)) {
            return Err(DiscretizationError::NotDelaunay {
                count: edge_star.iter().filter(|&&s| not_delaunay(s)).count(),
                first,
                value: 2.0 * edge_star[first],
                tolerance: DELAUNAY_TOLERANCE,
            });
        }
        Self::assemble(id, mesh, &geometry, boundary, |[vertices, edges, faces]| {
            Ok([
                Mass::diagonal_positive_on_used_nodes(
                    "M0 (⋆0, vertex areas)",
                    lumping.vertex_masses(mesh, &geometry),
                    &vertices.components,
                )?,
                Mass::diagonal_positive_on_used_nodes(
                    "M1 (⋆1, the edge Hodge star)",
                    edge_star,
                    &edges.components,
                )?,
                inverse_face_areas("M2 (⋆2, inverse face areas)", &geometry, faces)?,
            ])
        })
    }
}

/// `(cot α + cot β)/2` per edge: the cotangents of the corners opposite the edge in its faces.
pub fn edge_hodge_star(mesh: &TriangleMesh, geometry: &FaceGeometry) -> Vec<f64> {
    let mut star = vec![0.0; mesh.edge_count()];
    for (t, edges) in mesh.face_edges().iter().enumerate() {
        let cot = geometry.triangle(t).cotangents();
        for c in 0..3 {
            star[edges[c]] += cot[c] / 2.0;
        }
    }
    star
}
