//! The nodes of a complex on an intrinsic triangulation: where its vertices, edge midpoints and
//! face centroids lie on the input surface, which component each belongs to, and which lie on
//! the boundary.

use crate::intrinsic_delaunay::IntrinsicInput;
use tvf_core::discretization::{DiscretizationError, NodeKind, NodeSpace};
use tvf_core::intrinsic::{InputLocation, IntrinsicTriangulation, TrianglePoint};
use tvf_core::mesh::Mesh;
use tvf_core::TriangleMesh;

/// The intrinsic nodes of kind `kind` on the boundary (one flag per node): the boundary edges,
/// the vertices of boundary edges; never faces or face frames.
pub(crate) fn intrinsic_boundary_nodes(tri: &IntrinsicTriangulation, kind: NodeKind) -> Vec<bool> {
    let boundary_edges: Vec<bool> = (0..tri.edge_count())
        .map(|e| tri.is_boundary_edge(e))
        .collect();
    match kind {
        NodeKind::Edges => boundary_edges,
        NodeKind::Vertices => {
            let mut vertices = vec![false; tri.vertex_count()];
            for e in (0..tri.edge_count()).filter(|&e| boundary_edges[e]) {
                for v in tri.edge_vertices(e) {
                    vertices[v] = true;
                }
            }
            vertices
        }
        NodeKind::Faces => vec![false; tri.face_count()],
        NodeKind::FaceFrames => vec![false; 2 * tri.face_count()],
    }
}

/// The node spaces of the intrinsic vertices, edges and faces without boundary condition: each
/// node placed on the input surface and given the component of the input it lies in.
pub(crate) fn node_spaces(
    mesh: &TriangleMesh,
    input: &IntrinsicInput,
) -> Result<[NodeSpace; 3], DiscretizationError> {
    let tri = &input.triangulation;
    let topology = mesh.topology();
    let input_vertex_components = topology.vertex_components(mesh.face_corners());
    let input_face_components = topology.face_components();
    let positions = mesh.positions();
    let point_position = |p: TrianglePoint| -> [f64; 3] {
        let corners = mesh.faces()[p.face];
        std::array::from_fn(|k| {
            (0..3)
                .map(|c| p.barycentric[c] * positions[corners[c]][k])
                .sum()
        })
    };
    let on_input = |t: usize, barycentric: [f64; 3]| {
        input
            .overlay
            .to_input(TrianglePoint {
                face: t,
                barycentric,
            })
            .map(&point_position)
            .map_err(|error| DiscretizationError::Intrinsic(error.to_string()))
    };
    let mut vertex_positions = Vec::with_capacity(tri.vertex_count());
    let mut vertex_components = Vec::with_capacity(tri.vertex_count());
    for v in 0..tri.vertex_count() {
        let (position, component) = match tri.vertex_location(v) {
            InputLocation::Vertex(i) => (positions[i], input_vertex_components[i]),
            InputLocation::Edge { edge, t } => {
                let [a, b] = mesh.edges()[edge];
                let p = std::array::from_fn(|k| (1.0 - t) * positions[a][k] + t * positions[b][k]);
                (p, input_vertex_components[a])
            }
            InputLocation::Face(p) => (point_position(p), input_face_components[p.face]),
        };
        vertex_positions.push(position);
        vertex_components.push(component);
    }
    let mut edge_positions = Vec::with_capacity(tri.edge_count());
    for e in 0..tri.edge_count() {
        let t = tri.edge_faces(e)[0];
        let side = (0..3)
            .find(|&c| tri.face_edges(t)[c] == e && tri.face_edge_orientations(t)[c])
            .unwrap_or(0);
        let mut midpoint = [0.5; 3];
        midpoint[side] = 0.0;
        edge_positions.push(on_input(t, midpoint)?);
    }
    let face_positions = (0..tri.face_count())
        .map(|t| on_input(t, [1.0 / 3.0; 3]))
        .collect::<Result<Vec<_>, _>>()?;
    let components = topology.component_count();
    let edge_components = (0..tri.edge_count())
        .map(|e| vertex_components[tri.edge_vertices(e)[0]])
        .collect();
    let face_components = tri
        .faces()
        .iter()
        .map(|f| vertex_components[f[0]])
        .collect();
    Ok([
        NodeSpace::with_constant_kernel(
            NodeKind::Vertices,
            vertex_positions,
            vertex_components,
            components,
        ),
        NodeSpace::with_constant_kernel(
            NodeKind::Edges,
            edge_positions,
            edge_components,
            components,
        ),
        NodeSpace::with_constant_kernel(
            NodeKind::Faces,
            face_positions,
            face_components,
            components,
        ),
    ])
}
