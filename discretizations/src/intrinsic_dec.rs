//! [`IntrinsicDec`]: discrete exterior calculus on an intrinsic triangulation — the complex of
//! `dec-barycentric` and `dec-circumcentric` built from edge lengths, with sampling and point
//! evaluation on the input mesh through the correspondence.

use crate::boundary_conditions::{
    component_boundary_loops, drop_columns, drop_rows, mesh_topology,
};
use crate::intrinsic_delaunay::IntrinsicInput;
use crate::intrinsic_sampling::{IntrinsicEvaluation, IntrinsicWhitneySampling};
use crate::{MassLumping, DELAUNAY_TOLERANCE};
use sprs::CsMat;
use std::sync::Arc;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::discretization::{
    BoundaryCondition, ComplexParts, DiscretizationError, FieldSampling, HodgeComplex, Mass,
    NodeKind, NodeSpace, PointEvaluation,
};
use tvf_core::intrinsic::{InputLocation, IntrinsicTriangulation, TrianglePoint};
use tvf_core::mesh::Mesh;
use tvf_core::TriangleMesh;

/// The DEC complex of primal forms on an intrinsic triangulation (`dec-barycentric` or
/// `dec-circumcentric` with the intrinsic Delaunay modifier):
///
/// ```text
/// 0-forms (intrinsic V) --d0--> 1-forms (intrinsic E) --d1--> 2-forms (intrinsic F)
///          ⋆0                        ⋆1                            ⋆2
/// ```
///
/// - `d0` (`E × V`): row `e` has `−1` at the first and `+1` at the second vertex of the edge's
///   reference direction ([`IntrinsicTriangulation::edge_vertices`]; an edge from a vertex to
///   itself has an empty row); `d1` (`F × E`): `±1` per side of a face, `+1` where the face runs
///   along the edge's reference direction. `d1 d0 = 0` exactly.
/// - `⋆0`: barycentric or mixed-Voronoi vertex areas from the lengths
///   ([`IntrinsicTriangulation::barycentric_vertex_areas`],
///   [`IntrinsicTriangulation::mixed_voronoi_vertex_areas`]); inserted vertices are nodes like
///   the input's.
/// - `⋆1 = (cot α + cot β)/2` from the lengths ([`IntrinsicTriangulation::edge_hodge_star`]):
///   construction fails with [`DiscretizationError::NotDelaunay`] if some edge has
///   `cot α + cot β ≤` [`DELAUNAY_TOLERANCE`] (after flips only: cocircular neighbours, boundary
///   edges opposite an obtuse angle; never after refinement).
/// - `⋆2 = 1/area` per intrinsic face.
///
/// Boundary conditions as [`crate::DecComplex`]: absolute forms for
/// [`BoundaryCondition::Tangential`], relative forms (zero on the intrinsic boundary vertices and
/// edges) for [`BoundaryCondition::Normal`]. The harmonic dimension is the input's (the same
/// surface). Node positions are places on the input surface: vertices where they sit, edge
/// midpoints and face centroids mapped through the correspondence.
///
/// Sampling and point evaluation take points of the **input** faces ([`IntrinsicWhitneySampling`],
/// [`IntrinsicEvaluation`]): field files hold one vector per input face.
pub struct IntrinsicDec {
    parts: ComplexParts,
    sampling: IntrinsicWhitneySampling,
    evaluation: IntrinsicEvaluation,
    triangulation: Arc<IntrinsicTriangulation>,
}

impl IntrinsicDec {
    /// The DEC complex with id `id` on the intrinsic triangulation `input` of `mesh`, vertex areas
    /// by `lumping`, boundary condition `boundary` (on a mesh with boundary).
    pub fn new(
        mesh: &TriangleMesh,
        input: &IntrinsicInput,
        id: &str,
        lumping: MassLumping,
        boundary: BoundaryCondition,
    ) -> Result<Self, DiscretizationError> {
        let tri = &input.triangulation;
        let edge_star = tri.edge_hodge_star();
        let not_delaunay = |s: f64| 2.0 * s <= DELAUNAY_TOLERANCE;
        if let Some(first) = edge_star.iter().position(|&s| not_delaunay(s)) {
            return Err(DiscretizationError::NotDelaunay {
                count: edge_star.iter().filter(|&&s| not_delaunay(s)).count(),
                first,
                value: 2.0 * edge_star[first],
                tolerance: DELAUNAY_TOLERANCE,
            });
        }
        let (d0, d1, nodes) = intrinsic_forms(mesh, input, boundary)?;
        let vertex_areas = match lumping {
            MassLumping::Barycentric => tri.barycentric_vertex_areas(),
            MassLumping::Voronoi => tri.mixed_voronoi_vertex_areas(),
        };
        let masses = [
            Mass::diagonal_positive_on_used_nodes(
                "M0 (⋆0, vertex areas)",
                vertex_areas,
                &nodes[0].components,
            )?,
            Mass::diagonal_positive_on_used_nodes(
                "M1 (⋆1, the edge Hodge star)",
                edge_star,
                &nodes[1].components,
            )?,
            Mass::diagonal_positive_on_used_nodes(
                "M2 (⋆2, inverse face areas)",
                tri.face_areas().iter().map(|a| 1.0 / a).collect(),
                &nodes[2].components,
            )?,
        ];
        let fixed_edges = nodes[1].dirichlet.clone();
        Ok(Self {
            parts: ComplexParts::new(id, d0, d1, masses, nodes, mesh_topology(mesh, boundary))?,
            sampling: IntrinsicWhitneySampling::new(mesh, input, fixed_edges)?,
            evaluation: IntrinsicEvaluation::new(input),
            triangulation: tri.clone(),
        })
    }
}

impl HodgeComplex for IntrinsicDec {
    fn parts(&self) -> &ComplexParts {
        &self.parts
    }

    fn sampling(&self) -> Option<&dyn FieldSampling> {
        Some(&self.sampling)
    }

    fn point_evaluation(&self) -> Option<&dyn PointEvaluation> {
        Some(&self.evaluation)
    }

    fn intrinsic_triangulation(&self) -> Option<&IntrinsicTriangulation> {
        Some(&self.triangulation)
    }
}

/// `d0`, `d1` and the node spaces of the 0-, 1- and 2-forms.
type Forms = (CsMat<f64>, CsMat<f64>, [NodeSpace; 3]);

/// `d0` (`E × V`), `d1` (`F × E`) and the node spaces of vertices, edges and faces of the
/// intrinsic triangulation, with boundary condition `boundary` as [`crate::DecComplex`] has it.
fn intrinsic_forms(
    mesh: &TriangleMesh,
    input: &IntrinsicInput,
    boundary: BoundaryCondition,
) -> Result<Forms, DiscretizationError> {
    let tri = &input.triangulation;
    let (v, e, f) = (tri.vertex_count(), tri.edge_count(), tri.face_count());
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for edge in 0..e {
        let [a, b] = tri.edge_vertices(edge);
        if a != b {
            rows.extend([edge, edge]);
            cols.extend([a, b]);
            values.extend([-1.0, 1.0]);
        }
    }
    let mut d0 = from_triplets(e, v, rows, cols, values);
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for t in 0..f {
        let forward = tri.face_edge_orientations(t);
        for (c, edge) in tri.face_edges(t).into_iter().enumerate() {
            rows.push(t);
            cols.push(edge);
            values.push(if forward[c] { 1.0 } else { -1.0 });
        }
    }
    let mut d1 = from_triplets(f, e, rows, cols, values);

    let [mut vertices, mut edges, mut faces] = node_spaces(mesh, input)?;
    let loops = component_boundary_loops(mesh);
    let closed_components: Vec<bool> = loops.iter().map(|&b| b == 0).collect();
    if !mesh.topology().is_closed() && boundary == BoundaryCondition::Normal {
        let boundary_edges: Vec<bool> = (0..e).map(|x| tri.is_boundary_edge(x)).collect();
        let mut boundary_vertices = vec![false; v];
        for x in (0..e).filter(|&x| boundary_edges[x]) {
            for w in tri.edge_vertices(x) {
                boundary_vertices[w] = true;
            }
        }
        vertices.dirichlet = boundary_vertices;
        vertices.constant_kernel = closed_components;
        edges.dirichlet = boundary_edges;
        d0 = drop_rows(&drop_columns(&d0, &vertices.dirichlet), &edges.dirichlet);
        d1 = drop_columns(&d1, &edges.dirichlet);
    } else {
        faces.constant_kernel = closed_components;
    }
    Ok((d0, d1, [vertices, edges, faces]))
}

/// The node spaces of the intrinsic vertices, edges and faces without boundary condition: each
/// node placed on the input surface and given the component of the input it lies in.
fn node_spaces(
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
