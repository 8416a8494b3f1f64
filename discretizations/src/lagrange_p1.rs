//! [`LagrangeP1`]: continuous piecewise linear functions, one value per vertex (`S_h`).

use crate::consistent_mass::consistent_p1_mass;
use crate::face_geometry::FaceGeometry;
use crate::gradient_assembly::assemble_gradient;
use crate::FunctionSpace;
use crate::MassLumping;
use sprs::CsMat;
use tvf_core::discretization::{DiscretizationError, Mass, NodeKind};
use tvf_core::TriangleMesh;

/// The conforming space `S_h`: nodal values at the `V` vertices, hat-function basis.
///
/// Gradient (`2F × V`): the hat function of corner `c` of face `t` has gradient
/// `n_t × (p_{c+2} − p_{c+1}) / (2 A_t)` (pointwise, 1/length). Mass: a [`MassLumping`] rule,
/// or the consistent mass `∫ φ_i φ_j` ([`LagrangeP1::with_consistent_mass`]).
#[derive(Debug, Clone)]
pub struct LagrangeP1 {
    faces: Vec<[usize; 3]>,
    positions: Vec<[f64; 3]>,
    mass: Vec<f64>,
    /// The consistent mass (`V × V`), if the complex is to use it instead of `mass`.
    consistent_mass: Option<CsMat<f64>>,
    gradient: CsMat<f64>,
    components: Vec<usize>,
    component_count: usize,
}

impl LagrangeP1 {
    /// Builds `S_h` from precomputed face geometry (from the mesh alone:
    /// [`crate::PaperSpace::new`]).
    pub fn from_geometry(
        mesh: &TriangleMesh,
        geometry: &FaceGeometry,
        lumping: MassLumping,
    ) -> Self {
        let gradient = assemble_gradient(
            mesh.vertex_count(),
            mesh.faces().iter().copied(),
            (0..mesh.face_count()).map(|t| geometry.triangle(t).hat_gradients()),
        );
        Self {
            faces: mesh.faces().to_vec(),
            positions: mesh.positions().to_vec(),
            mass: lumping.vertex_masses(mesh, geometry),
            consistent_mass: None,
            gradient,
            components: mesh.vertex_components(),
            component_count: mesh.component_count(),
        }
    }

    /// `S_h` with the consistent (Galerkin) mass `M[i, j] = Σ_T |T| (1 + δ_ij)/12`
    /// ([`crate::consistent_p1_mass`]) as its mass matrix; [`FunctionSpace::mass`] is then the
    /// barycentric lumped mass, the row sums of the consistent one.
    pub fn with_consistent_mass(mesh: &TriangleMesh, geometry: &FaceGeometry) -> Self {
        Self {
            consistent_mass: Some(consistent_p1_mass(mesh, geometry)),
            ..Self::from_geometry(mesh, geometry, MassLumping::Barycentric)
        }
    }
}

impl FunctionSpace for LagrangeP1 {
    fn name(&self) -> &str {
        match self.consistent_mass {
            Some(_) => "Lagrange P1, consistent mass",
            None => "Lagrange P1",
        }
    }

    fn node_kind(&self) -> NodeKind {
        NodeKind::Vertices
    }

    fn dimension(&self) -> usize {
        self.positions.len()
    }

    fn mass(&self) -> &[f64] {
        &self.mass
    }

    /// The consistent mass as a sparse matrix if the space has one, else the lumped diagonal.
    fn mass_matrix(&self, what: &'static str) -> Result<Mass, DiscretizationError> {
        match &self.consistent_mass {
            Some(matrix) => Mass::sparse(what, matrix.clone()),
            None => {
                Mass::diagonal_positive_on_used_nodes(what, self.mass.clone(), &self.components)
            }
        }
    }

    fn gradient(&self) -> &CsMat<f64> {
        &self.gradient
    }

    /// The three corner vertices with the barycentric coordinates as weights.
    fn interpolation_weights(&self, face: usize, barycentric: [f64; 3]) -> Vec<(usize, f64)> {
        let nodes = self.faces[face];
        (0..3).map(|c| (nodes[c], barycentric[c])).collect()
    }

    fn node_positions(&self) -> Vec<[f64; 3]> {
        self.positions.clone()
    }

    fn node_components(&self) -> &[usize] {
        &self.components
    }

    fn component_count(&self) -> usize {
        self.component_count
    }
}
