//! [`LagrangeP1`]: continuous piecewise linear functions, one value per vertex (`S_h`).

use crate::face_geometry::FaceGeometry;
use crate::gradient_assembly::assemble_gradient;
use crate::FunctionSpace;
use crate::MassLumping;
use sprs::CsMat;
use tvf_core::discretization::{DiscretizationError, NodeKind};
use tvf_core::SurfaceMesh;

/// The conforming space `S_h`: nodal values at the `V` vertices, hat-function basis.
///
/// Gradient (`2F × V`): the hat function of corner `c` of face `t` has gradient
/// `n_t × (p_{c+2} − p_{c+1}) / (2 A_t)` (pointwise, 1/length). Mass: a [`MassLumping`] rule.
#[derive(Debug, Clone)]
pub struct LagrangeP1 {
    faces: Vec<[usize; 3]>,
    positions: Vec<[f64; 3]>,
    mass: Vec<f64>,
    gradient: CsMat<f64>,
    components: Vec<usize>,
    component_count: usize,
}

impl LagrangeP1 {
    /// Builds `S_h` on `mesh`; fails on a degenerate face.
    pub fn new(mesh: &SurfaceMesh, lumping: MassLumping) -> Result<Self, DiscretizationError> {
        Ok(Self::from_geometry(
            mesh,
            &FaceGeometry::new(mesh)?,
            lumping,
        ))
    }

    /// Builds `S_h` from precomputed face geometry.
    pub fn from_geometry(
        mesh: &SurfaceMesh,
        geometry: &FaceGeometry,
        lumping: MassLumping,
    ) -> Self {
        let gradient = assemble_gradient(
            mesh.vertex_count(),
            mesh.faces().iter().copied(),
            (0..mesh.face_count()).map(|t| geometry.hat_gradients(t)),
        );
        Self {
            faces: mesh.faces().to_vec(),
            positions: mesh.positions().to_vec(),
            mass: lumping.vertex_masses(mesh, geometry),
            gradient,
            components: mesh.vertex_components(),
            component_count: mesh.component_count(),
        }
    }
}

impl FunctionSpace for LagrangeP1 {
    fn name(&self) -> &str {
        "Lagrange P1"
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
