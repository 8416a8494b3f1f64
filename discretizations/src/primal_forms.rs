//! [`PrimalForms`]: what every complex of primal forms shares — the signed incidences `d0`, `d1`,
//! the node spaces of vertices, edges and faces with a boundary condition (absolute or relative
//! forms), on triangle and polygon meshes alike — and point evaluation of 0- and 2-forms on
//! triangles. DEC ([`crate::DecComplex`]) and Whitney forms with Galerkin masses
//! ([`crate::WhitneyGalerkin`]) differ only in their masses; polygonal DEC
//! ([`crate::PolygonDec`]) shares the incidences and nodes.

use crate::boundary_conditions::{
    boundary_nodes, component_boundary_loops, drop_columns, drop_rows, mesh_topology,
    with_dirichlet_boundary,
};
use crate::complex_id::complex_id;
use sprs::CsMat;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::discretization::{
    BoundaryCondition, ComplexParts, DiscretizationError, Mass, NodeKind, NodeSpace,
    PointEvaluation,
};
use tvf_core::mesh::Mesh;
use tvf_core::{SurfacePoint, TriangleMesh};

/// The complex `0-forms (V) --d0--> 1-forms (E) --d1--> 2-forms (F)` without its masses.
///
/// - A 1-form is `x_e = ∫_e ⟨v, t⟩`, the field integrated along edge `e = (a, b)`, `a < b`
///   (edges numbered as the mesh's: lexicographic), from `a` to `b` (units length × field).
/// - `d0` (`E × V`): row `e = (a, b)` has `−1` at `a` and `+1` at `b` (`(d0 f)_e = f_b − f_a`).
/// - `d1` (`F × E`): row `t` has `±1` at each of its edges, `+1` where the counter-clockwise
///   boundary of `t` runs `a → b` (the circulation around `t`). `d1 d0 = 0` exactly.
///
/// On a mesh with boundary, [`BoundaryCondition::Tangential`] gives **absolute** forms (every
/// vertex, edge and face free; the 2-forms have no constant kernel on a component with boundary)
/// and [`BoundaryCondition::Normal`] **relative** forms: boundary vertices are Dirichlet nodes of
/// the 0-forms (zero columns of `d0`), boundary edges Dirichlet nodes of the 1-forms (zero rows
/// of `d0`, zero columns of `d1`); every face stays and the 2-forms have the constants in their
/// kernel.
///
/// Public for discretizations of your own on primal forms ([`crate::PrimalFormComplex`]
/// assembles them with your masses).
#[derive(Debug, Clone)]
pub struct PrimalForms {
    /// `d0` (`E × V`).
    pub d0: CsMat<f64>,
    /// `d1` (`F × E`).
    pub d1: CsMat<f64>,
    /// The nodes of the 0-, 1- and 2-forms: vertices, edge midpoints, face centroids.
    pub nodes: [NodeSpace; 3],
}

impl PrimalForms {
    /// The incidences and node spaces of `mesh` with boundary condition `boundary` (ignored on a
    /// closed mesh). Face nodes sit at the faces' corner averages.
    pub fn new<M: Mesh + ?Sized>(mesh: &M, boundary: BoundaryCondition) -> Self {
        let positions = mesh.positions();
        let (topology, faces) = (mesh.topology(), mesh.face_corners());
        let components = topology.component_count();
        let mut potential_nodes = NodeSpace::with_constant_kernel(
            NodeKind::Vertices,
            positions.to_vec(),
            topology.vertex_components(faces),
            components,
        );
        let mut field_nodes = NodeSpace::with_constant_kernel(
            NodeKind::Edges,
            topology
                .edges()
                .iter()
                .map(|&[a, b]| std::array::from_fn(|k| (positions[a][k] + positions[b][k]) / 2.0))
                .collect(),
            topology.edge_components(),
            components,
        );
        let mut co_potential_nodes = NodeSpace::with_constant_kernel(
            NodeKind::Faces,
            (0..faces.face_count())
                .map(|f| {
                    let corners = faces.corners(f);
                    let n = corners.len() as f64;
                    std::array::from_fn(|k| {
                        corners.iter().map(|&i| positions[i][k]).sum::<f64>() / n
                    })
                })
                .collect(),
            topology.face_components().to_vec(),
            components,
        );
        let mut d0 = vertex_edge_incidence(mesh);
        let mut d1 = edge_face_incidence(mesh);
        let relative = !topology.is_closed() && boundary == BoundaryCondition::Normal;
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

    /// These incidences and nodes with the masses `masses` (`[M0, M1, M2]`, `V × V`, `E × E`,
    /// `F × F`) as the parts of the complex of `mesh` with boundary condition `boundary` (the one
    /// they were made with) and catalog id `id` (`+{boundary}` appended on a mesh with boundary).
    /// Fails when [`ComplexParts::new`] refuses them (shapes, `d1 d0 ≠ 0`).
    pub fn into_parts<M: Mesh + ?Sized>(
        self,
        id: &str,
        mesh: &M,
        boundary: BoundaryCondition,
        masses: [Mass; 3],
    ) -> Result<ComplexParts, DiscretizationError> {
        ComplexParts::new(
            complex_id(id, mesh.topology(), boundary),
            self.d0,
            self.d1,
            masses,
            self.nodes,
            mesh_topology(mesh, boundary),
        )
    }
}

/// Signed vertex → edge incidence (`E × V`): `−1` at `a`, `+1` at `b` for edge `(a, b)`.
fn vertex_edge_incidence<M: Mesh + ?Sized>(mesh: &M) -> CsMat<f64> {
    let edges = mesh.topology().edges();
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for (e, &[a, b]) in edges.iter().enumerate() {
        rows.extend([e, e]);
        cols.extend([a, b]);
        values.extend([-1.0, 1.0]);
    }
    from_triplets(edges.len(), mesh.positions().len(), rows, cols, values)
}

/// Signed edge → face incidence (`F × E`): `+1` where the face's counter-clockwise boundary runs
/// along the edge's orientation `a → b`, `−1` where it runs against it.
fn edge_face_incidence<M: Mesh + ?Sized>(mesh: &M) -> CsMat<f64> {
    let faces = mesh.face_corners();
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for f in 0..faces.face_count() {
        let corners = faces.corners(f);
        for (c, &from) in corners.iter().enumerate() {
            // Side c runs from corner c to corner c + 1.
            let to = corners[(c + 1) % corners.len()];
            rows.push(f);
            cols.push(mesh.face_edge(f, c));
            values.push(if from < to { 1.0 } else { -1.0 });
        }
    }
    let edge_count = mesh.topology().edges().len();
    from_triplets(faces.face_count(), edge_count, rows, cols, values)
}

/// Point evaluation of primal forms on a triangle mesh: a 0-form is interpolated linearly (the
/// Whitney 0-forms are the hat functions: weights the point's barycentric coordinates), a
/// 2-form's coefficient is constant on its face (weight 1 at the point's face). The
/// [`PointEvaluation`] of every [`crate::PrimalFormComplex`].
#[derive(Debug, Clone)]
pub struct PrimalFormEvaluation {
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
    fn potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)> {
        let (nodes, barycentric) = (self.faces[point.face], point.triangle_coordinates());
        (0..3).map(|c| (nodes[c], barycentric[c])).collect()
    }

    fn co_potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)> {
        vec![(point.face, 1.0)]
    }
}
