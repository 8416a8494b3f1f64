//! [`CrouzeixRaviart`]: piecewise linear functions continuous at edge midpoints (`S*_h`).

use crate::face_geometry::FaceGeometry;
use crate::gradient_assembly::assemble_gradient;
use crate::planar_triangle::PlanarTriangle;
use crate::FunctionSpace;
use crate::MassLumping;
use sprs::CsMat;
use tvf_core::discretization::NodeKind;
use tvf_core::TriangleMesh;

/// The nonconforming space `S*_h`: nodal values at the `E` edge midpoints (edges numbered as in
/// [`TriangleMesh::edges`]).
///
/// In face `t` the basis function of the edge opposite corner `c` is `1 − 2 φ_c`, so its gradient
/// (`2F × E`, pointwise, 1/length) is `−2 grad φ_c`. Mass: a [`MassLumping`] rule.
#[derive(Debug, Clone)]
pub struct CrouzeixRaviart {
    face_edges: Vec<[usize; 3]>,
    midpoints: Vec<[f64; 3]>,
    mass: Vec<f64>,
    gradient: CsMat<f64>,
    components: Vec<usize>,
    component_count: usize,
}

impl CrouzeixRaviart {
    /// Builds `S*_h` from precomputed face geometry (from the mesh alone:
    /// [`crate::PaperSpace::new`]).
    pub fn from_geometry(
        mesh: &TriangleMesh,
        geometry: &FaceGeometry,
        lumping: MassLumping,
    ) -> Self {
        let gradient = assemble_gradient(
            mesh.edge_count(),
            mesh.face_edges().iter().copied(),
            (0..mesh.face_count()).map(|t| edge_basis_gradients(&geometry.triangle(t))),
        );
        let p = mesh.positions();
        let midpoints = mesh
            .edges()
            .iter()
            .map(|&[a, b]| std::array::from_fn(|k| (p[a][k] + p[b][k]) / 2.0))
            .collect();
        Self {
            face_edges: mesh.face_edges().to_vec(),
            midpoints,
            mass: lumping.edge_masses(mesh, geometry),
            gradient,
            components: mesh.edge_components(),
            component_count: mesh.component_count(),
        }
    }
}

/// In-frame gradients of the three Crouzeix–Raviart basis functions of `triangle`, that of the
/// side opposite corner `c` is `−2 grad φ_c` (1/length).
pub(crate) fn edge_basis_gradients(triangle: &PlanarTriangle) -> [[f64; 2]; 3] {
    triangle.hat_gradients().map(|g| [-2.0 * g[0], -2.0 * g[1]])
}

impl FunctionSpace for CrouzeixRaviart {
    fn name(&self) -> &str {
        "Crouzeix-Raviart"
    }

    fn node_kind(&self) -> NodeKind {
        NodeKind::Edges
    }

    fn dimension(&self) -> usize {
        self.midpoints.len()
    }

    fn mass(&self) -> &[f64] {
        &self.mass
    }

    fn gradient(&self) -> &CsMat<f64> {
        &self.gradient
    }

    /// The three edges of the face; the edge opposite corner `c` has weight `1 − 2 b_c`.
    fn interpolation_weights(&self, face: usize, barycentric: [f64; 3]) -> Vec<(usize, f64)> {
        let edges = self.face_edges[face];
        (0..3)
            .map(|c| (edges[c], 1.0 - 2.0 * barycentric[c]))
            .collect()
    }

    fn node_positions(&self) -> Vec<[f64; 3]> {
        self.midpoints.clone()
    }

    fn node_components(&self) -> &[usize] {
        &self.components
    }

    fn component_count(&self) -> usize {
        self.component_count
    }
}
