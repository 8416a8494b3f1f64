//! [`IntrinsicFiniteElement`]: the paper's finite element complexes (conforming and
//! nonconforming, lumped or consistent masses) on an intrinsic triangulation — the complexes of
//! the `conforming-*` and `nonconforming-*` entries built from edge lengths.

use crate::boundary_conditions::{
    component_boundary_loops, drop_columns, drop_rows, mesh_topology,
};
use crate::consistent_mass::assemble_consistent_p1_mass;
use crate::crouzeix_raviart::edge_basis_gradients;
use crate::finite_element_complex::inverse_co_potential_mass;
use crate::gradient_assembly::assemble_gradient;
use crate::intrinsic_delaunay::IntrinsicInput;
use crate::intrinsic_face_sampling::IntrinsicFaceSampling;
use crate::intrinsic_nodes::{intrinsic_boundary_nodes, node_spaces};
use crate::intrinsic_sampling::IntrinsicEvaluation;
use crate::mass_lumping::lumped_masses;
use crate::planar_triangle::PlanarTriangle;
use crate::{MassLumping, SpaceMasses};
use sprs::CsMat;
use std::sync::Arc;
use tvf_core::discretization::sparse::{product, scale_cols, transpose};
use tvf_core::discretization::{
    BoundaryCondition, ComplexParts, DiscretizationError, FieldRotation, FieldSampling,
    HodgeComplex, Mass, NodeKind, NodeSpace, PointEvaluation,
};
use tvf_core::intrinsic::IntrinsicTriangulation;
use tvf_core::TriangleMesh;

/// Which function space holds the potentials: the paper's two decompositions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElementFamily {
    /// Potentials P1 (vertices), co-potentials Crouzeix–Raviart (edges): [`crate::Conforming`].
    Conforming,
    /// Potentials Crouzeix–Raviart, co-potentials P1: [`crate::Nonconforming`].
    Nonconforming,
}

/// The finite element complex `P --d0--> X_h --d1--> Q` of [`crate::FiniteElementComplex`] on an
/// intrinsic triangulation: P1 on the intrinsic vertices (inserted ones included),
/// Crouzeix–Raviart on the intrinsic edges, `X_h` one vector per intrinsic face, with
/// `d0 = G_P`, `d1 = G_Qᵀ J M_X`, `M0 = mass(P)`, `M1 = M_X = diag(A_t, A_t)`,
/// `M2 = mass(Q)⁻¹` as there.
///
/// Each intrinsic face is laid out in the plane from its three edge lengths
/// ([`PlanarTriangle::from_lengths`]: corner 0 at the origin, corner 1 on the `e1` axis), which
/// is the frame a face of a mesh has (`e1 = normalize(p_{i1} − p_{i0})`, `e2 = n × e1`): the
/// hat-function gradients, the lumped shares (barycentric, mixed Voronoi, midpoint Voronoi) and
/// the consistent P1 mass are the formulas of the mesh's spaces on that layout. Every matrix
/// depends only on the metric, so on a mesh that is its own intrinsic Delaunay triangulation it
/// is the input complex's to round-off.
///
/// Boundary conditions as [`crate::FiniteElementComplex::from_spaces_with_boundary`]:
/// [`BoundaryCondition::Tangential`] fixes the co-potentials at their intrinsic boundary nodes,
/// [`BoundaryCondition::Normal`] the potentials. Fields are sampled at points of the **input**
/// faces ([`IntrinsicFaceSampling`]), potentials and co-potentials evaluated there
/// ([`IntrinsicEvaluation`]); the rotation `J` is the +π/2 rotation in every intrinsic face.
pub struct IntrinsicFiniteElement {
    parts: ComplexParts,
    sampling: IntrinsicFaceSampling,
    rotation: CsMat<f64>,
    evaluation: IntrinsicEvaluation,
    triangulation: Arc<IntrinsicTriangulation>,
}

/// A function space on the intrinsic triangulation: its node kind, gradient (`2F × n`) and mass
/// over every node.
struct LengthSpace {
    kind: NodeKind,
    gradient: CsMat<f64>,
    /// The mass, unrestricted: lumped (diagonal) or consistent (sparse).
    mass: Mass,
}

impl LengthSpace {
    /// P1 on the intrinsic vertices with the mass `masses` selects, named `what` in errors.
    fn lagrange_p1(
        tri: &IntrinsicTriangulation,
        triangles: &[PlanarTriangle],
        masses: SpaceMasses,
        node_components: &[usize],
        what: &'static str,
    ) -> Result<Self, DiscretizationError> {
        let n = tri.vertex_count();
        let gradient = assemble_gradient(
            n,
            tri.faces().iter().copied(),
            triangles.iter().map(PlanarTriangle::hat_gradients),
        );
        let mass = match masses {
            SpaceMasses::Lumped(lumping) => Mass::diagonal_positive_on_used_nodes(
                what,
                lumped_masses(
                    n,
                    tri.faces().iter().copied(),
                    triangles.iter().map(|t| lumping.vertex_shares(t)),
                ),
                node_components,
            )?,
            SpaceMasses::Consistent => {
                let areas: Vec<f64> = triangles.iter().map(|t| t.area).collect();
                Mass::sparse(what, assemble_consistent_p1_mass(n, tri.faces(), &areas))?
            }
        };
        Ok(Self {
            kind: NodeKind::Vertices,
            gradient,
            mass,
        })
    }

    /// Crouzeix–Raviart on the intrinsic edges, lumped by `masses` (its consistent mass is the
    /// barycentric lumped one), named `what` in errors.
    fn crouzeix_raviart(
        tri: &IntrinsicTriangulation,
        triangles: &[PlanarTriangle],
        masses: SpaceMasses,
        node_components: &[usize],
        what: &'static str,
    ) -> Result<Self, DiscretizationError> {
        let n = tri.edge_count();
        let face_edges = || (0..tri.face_count()).map(|t| tri.face_edges(t));
        let gradient =
            assemble_gradient(n, face_edges(), triangles.iter().map(edge_basis_gradients));
        let lumping = match masses {
            SpaceMasses::Lumped(lumping) => lumping,
            SpaceMasses::Consistent => MassLumping::Barycentric,
        };
        let values = lumped_masses(
            n,
            face_edges(),
            triangles.iter().map(|t| lumping.edge_shares(t)),
        );
        Ok(Self {
            kind: NodeKind::Edges,
            gradient,
            mass: Mass::diagonal_positive_on_used_nodes(what, values, node_components)?,
        })
    }
}

impl IntrinsicFiniteElement {
    /// The complex of `family` with masses `masses` and id `id` on the intrinsic triangulation
    /// `input` of `mesh`, boundary condition `boundary` (on a mesh with boundary). Fails when a
    /// mass is not positive on a used node, a node cannot be placed on the input, or
    /// [`ComplexParts::new`] refuses the parts.
    pub fn new(
        mesh: &TriangleMesh,
        input: &IntrinsicInput,
        id: &str,
        family: ElementFamily,
        masses: SpaceMasses,
        boundary: BoundaryCondition,
    ) -> Result<Self, DiscretizationError> {
        let tri = &input.triangulation;
        let triangles = PlanarTriangle::of_intrinsic_faces(tri);
        let [vertex_nodes, edge_nodes, face_nodes] = node_spaces(mesh, input)?;
        let p1 = |what| {
            LengthSpace::lagrange_p1(tri, &triangles, masses, &vertex_nodes.components, what)
        };
        let cr = |what| {
            LengthSpace::crouzeix_raviart(tri, &triangles, masses, &edge_nodes.components, what)
        };
        let ((potentials, mut potential_nodes), (co_potentials, mut co_potential_nodes)) =
            match family {
                ElementFamily::Conforming => (
                    (p1("M0 (potential mass)")?, vertex_nodes.clone()),
                    (cr("co-potential mass")?, edge_nodes.clone()),
                ),
                ElementFamily::Nonconforming => (
                    (cr("M0 (potential mass)")?, edge_nodes.clone()),
                    (p1("co-potential mass")?, vertex_nodes.clone()),
                ),
            };
        let (field_mass, rotation) = face_field_mass_and_rotation(&triangles);
        let mut d0 = potentials.gradient.clone();
        let rotated_mass = scale_cols(&rotation, &field_mass);
        let mut d1 = product(&transpose(&co_potentials.gradient), &rotated_mass);
        if !mesh.is_closed() {
            let closed: Vec<bool> = component_boundary_loops(mesh)
                .iter()
                .map(|&b| b == 0)
                .collect();
            let fixed = match boundary {
                BoundaryCondition::Tangential => &mut co_potential_nodes,
                BoundaryCondition::Normal => &mut potential_nodes,
            };
            fixed.dirichlet = intrinsic_boundary_nodes(tri, fixed.kind);
            fixed.constant_kernel = closed;
            match boundary {
                BoundaryCondition::Tangential => d1 = drop_rows(&d1, &co_potential_nodes.dirichlet),
                BoundaryCondition::Normal => d0 = drop_columns(&d0, &potential_nodes.dirichlet),
            }
        }
        let field_nodes = face_frame_nodes(&face_nodes);
        let masses = [
            potentials.mass,
            Mass::diagonal_positive_on_used_nodes(
                "M1 (field mass)",
                field_mass,
                &field_nodes.components,
            )?,
            inverse_co_potential_mass(co_potentials.mass)?,
        ];
        let nodes = [potential_nodes, field_nodes, co_potential_nodes];
        Ok(Self {
            parts: ComplexParts::new(id, d0, d1, masses, nodes, mesh_topology(mesh, boundary))?,
            sampling: IntrinsicFaceSampling::new(mesh, input, triangles)?,
            rotation,
            evaluation: IntrinsicEvaluation::with_node_kinds(
                input,
                [potentials.kind, co_potentials.kind],
            ),
            triangulation: tri.clone(),
        })
    }
}

/// `M_X = diag(A_t, A_t)` (`2F` entries, area) and the rotation `J`, block diagonal with blocks
/// `[[0, −1], [1, 0]]`, of the face fields on the faces `triangles`.
fn face_field_mass_and_rotation(triangles: &[PlanarTriangle]) -> (Vec<f64>, CsMat<f64>) {
    let f = triangles.len();
    let mass = triangles.iter().flat_map(|t| [t.area, t.area]).collect();
    // Row 2t: (−1 at column 2t+1); row 2t+1: (+1 at column 2t).
    let indptr = (0..=2 * f).collect();
    let indices = (0..f).flat_map(|t| [2 * t + 1, 2 * t]).collect();
    let data = (0..f).flat_map(|_| [-1.0, 1.0]).collect();
    (mass, CsMat::new((2 * f, 2 * f), indptr, indices, data))
}

/// The `2F` field nodes, two per intrinsic face at the face node's place (its centroid on the
/// input), from the face nodes `faces`.
fn face_frame_nodes(faces: &NodeSpace) -> NodeSpace {
    NodeSpace::with_constant_kernel(
        NodeKind::FaceFrames,
        faces.positions.iter().flat_map(|&p| [p, p]).collect(),
        faces.components.iter().flat_map(|&c| [c, c]).collect(),
        faces.constant_kernel.len(),
    )
}

impl HodgeComplex for IntrinsicFiniteElement {
    fn parts(&self) -> &ComplexParts {
        &self.parts
    }

    fn sampling(&self) -> Option<&dyn FieldSampling> {
        Some(&self.sampling)
    }

    fn rotation(&self) -> Option<&dyn FieldRotation> {
        Some(self)
    }

    fn point_evaluation(&self) -> Option<&dyn PointEvaluation> {
        Some(&self.evaluation)
    }

    fn intrinsic_triangulation(&self) -> Option<&IntrinsicTriangulation> {
        Some(&self.triangulation)
    }
}

impl FieldRotation for IntrinsicFiniteElement {
    /// Block diagonal with blocks `[[0, −1], [1, 0]]`, i.e. `(a, b) ↦ (−b, a)` in every
    /// intrinsic face's frame.
    fn rotation(&self) -> &CsMat<f64> {
        &self.rotation
    }
}
