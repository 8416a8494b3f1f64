//! [`PrimalForms`]: what every complex of primal forms on a triangle mesh shares — the signed
//! incidences `d0`, `d1`, the node spaces of vertices, edges and faces with a boundary condition
//! (absolute or relative forms), and point evaluation of 0- and 2-forms. DEC
//! ([`crate::DecComplex`]) and Whitney forms with Galerkin masses ([`crate::WhitneyGalerkin`])
//! differ only in their masses.

use crate::boundary_conditions::{
    boundary_nodes, component_boundary_loops, drop_columns, drop_rows, with_dirichlet_boundary,
};
use sprs::CsMat;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::discretization::{BoundaryCondition, NodeKind, NodeSpace, PointEvaluation};
use tvf_core::TriangleMesh;

/// The complex `0-forms (V) --d0--> 1-forms (E) --d1--> 2-forms (F)` without its masses.
///
/// - A 1-form is `x_e = ∫_e ⟨v, t⟩`, the field integrated along edge `e = (a, b)`, `a < b`
///   (edges numbered as [`TriangleMesh::edges`]), from `a` to `b` (units length × field).
/// - `d0` (`E × V`): row `e = (a, b)` has `−1` at `a` and `+1` at `b` (`(d0 f)_e = f_b − f_a`).
/// - `d1` (`F × E`): row `t` has `±1` at its three edges, `+1` where the counter-clockwise
///   boundary of `t` runs `a → b` (the circulation around `t`). `d1 d0 = 0` exactly.
///
/// On a mesh with boundary, [`BoundaryCondition::Tangential`] gives **absolute** forms (every
/// vertex, edge and face free; the 2-forms have no constant kernel on a component with boundary)
/// and [`BoundaryCondition::Normal`] **relative** forms: boundary vertices are Dirichlet nodes of
/// the 0-forms (zero columns of `d0`), boundary edges Dirichlet nodes of the 1-forms (zero rows
/// of `d0`, zero columns of `d1`); every face stays and the 2-forms have the constants in their
/// kernel.
#[derive(Debug, Clone)]
pub(crate) struct PrimalForms {
    /// `d0` (`E × V`).
    pub d0: CsMat<f64>,
    /// `d1` (`F × E`).
    pub d1: CsMat<f64>,
    /// The nodes of the 0-, 1- and 2-forms: vertices, edge midpoints, face centroids.
    pub nodes: [NodeSpace; 3],
}

impl PrimalForms {
    /// The incidences and node spaces of `mesh` with boundary condition `boundary` (ignored on a
    /// closed mesh).
    pub fn new(mesh: &TriangleMesh, boundary: BoundaryCondition) -> Self {
        let positions = mesh.positions();
        let components = mesh.component_count();
        let mut potential_nodes = NodeSpace::with_constant_kernel(
            NodeKind::Vertices,
            positions.to_vec(),
            mesh.vertex_components(),
            components,
        );
        let mut field_nodes = NodeSpace::with_constant_kernel(
            NodeKind::Edges,
            mesh.edges()
                .iter()
                .map(|&[a, b]| std::array::from_fn(|k| (positions[a][k] + positions[b][k]) / 2.0))
                .collect(),
            mesh.edge_components(),
            components,
        );
        let mut co_potential_nodes = NodeSpace::with_constant_kernel(
            NodeKind::Faces,
            mesh.faces()
                .iter()
                .map(|f| {
                    let p = f.map(|i| positions[i]);
                    std::array::from_fn(|k| (p[0][k] + p[1][k] + p[2][k]) / 3.0)
                })
                .collect(),
            mesh.face_components().to_vec(),
            components,
        );
        let mut d0 = vertex_edge_incidence(mesh);
        let mut d1 = edge_face_incidence(mesh);
        let relative = !mesh.is_closed() && boundary == BoundaryCondition::Normal;
        if relative {
            // Relative forms: zero on boundary vertices and edges. A boundary edge joins two
            // boundary vertices, so dropping its row of d0 loses nothing; the face circulations
            // of a constant 2-form cancel on interior edges, so the constants are in the kernel.
            potential_nodes = with_dirichlet_boundary(potential_nodes, mesh);
            field_nodes.dirichlet = boundary_nodes(mesh, NodeKind::Edges);
            d0 = drop_rows(
                &drop_columns(&d0, &potential_nodes.dirichlet),
                &field_nodes.dirichlet,
            );
            d1 = drop_columns(&d1, &field_nodes.dirichlet);
        } else {
            // Absolute 2-forms: the constants are in the kernel only on closed components.
            co_potential_nodes.constant_kernel = component_boundary_loops(mesh)
                .iter()
                .map(|&b| b == 0)
                .collect();
        }
        Self {
            d0,
            d1,
            nodes: [potential_nodes, field_nodes, co_potential_nodes],
        }
    }
}

/// Signed vertex → edge incidence (`E × V`): `−1` at `a`, `+1` at `b` for edge `(a, b)`.
fn vertex_edge_incidence(mesh: &TriangleMesh) -> CsMat<f64> {
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for (e, &[a, b]) in mesh.edges().iter().enumerate() {
        rows.extend([e, e]);
        cols.extend([a, b]);
        values.extend([-1.0, 1.0]);
    }
    from_triplets(mesh.edge_count(), mesh.vertex_count(), rows, cols, values)
}

/// Signed edge → face incidence (`F × E`): `+1` where the face's counter-clockwise boundary runs
/// along the edge's orientation `a → b`, `−1` where it runs against it.
fn edge_face_incidence(mesh: &TriangleMesh) -> CsMat<f64> {
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for (t, (face, edges)) in mesh.faces().iter().zip(mesh.face_edges()).enumerate() {
        for c in 0..3 {
            // The edge opposite corner c runs from corner c+1 to corner c+2.
            let (from, to) = (face[(c + 1) % 3], face[(c + 2) % 3]);
            rows.push(t);
            cols.push(edges[c]);
            values.push(if from < to { 1.0 } else { -1.0 });
        }
    }
    from_triplets(mesh.face_count(), mesh.edge_count(), rows, cols, values)
}

/// Point evaluation of primal forms: a 0-form is interpolated linearly (the Whitney 0-forms are
/// the hat functions), a 2-form's pointwise value (`M2` times its integral) is constant on its
/// face.
#[derive(Debug, Clone)]
pub(crate) struct PrimalFormEvaluation {
    faces: Vec<[usize; 3]>,
}

impl PrimalFormEvaluation {
    /// The evaluation on the faces of `mesh`.
    pub fn new(mesh: &TriangleMesh) -> Self {
        Self {
            faces: mesh.faces().to_vec(),
        }
    }
}

impl PointEvaluation for PrimalFormEvaluation {
    fn potential_weights(&self, face: usize, barycentric: [f64; 3]) -> Vec<(usize, f64)> {
        let nodes = self.faces[face];
        (0..3).map(|c| (nodes[c], barycentric[c])).collect()
    }

    fn co_potential_weights(&self, face: usize, _barycentric: [f64; 3]) -> Vec<(usize, f64)> {
        vec![(face, 1.0)]
    }
}
