//! [`IntrinsicPrimalFormComplex`]: primal forms on an intrinsic triangulation with masses chosen by
//! a marker (a [`SampledComplex`]) — the one type behind [`crate::IntrinsicDec`] and
//! [`crate::IntrinsicWhitneyGalerkin`], as [`crate::PrimalFormComplex`] is behind DEC and Whitney
//! forms on the input mesh.

use crate::boundary_conditions::{
    component_boundary_loops, drop_columns, drop_rows, mesh_topology,
};
use crate::intrinsic_delaunay::IntrinsicInput;
use crate::intrinsic_nodes::{intrinsic_boundary_nodes, node_spaces};
use crate::intrinsic_sampling::IntrinsicEvaluation;
use crate::intrinsic_whitney_sampling::IntrinsicWhitneySampling;
use crate::sampled_complex::SampledComplex;
use sprs::CsMat;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::discretization::{
    BoundaryCondition, ComplexParts, DiscretizationError, Mass, NodeKind, NodeSpace,
};
use tvf_core::TriangleMesh;

/// The complex of primal forms on an intrinsic triangulation,
///
/// ```text
/// 0-forms (intrinsic V) --d0--> 1-forms (intrinsic E) --d1--> 2-forms (intrinsic F)
///          M0                        M1                            M2
/// ```
///
/// with masses chosen by the marker `M` ([`crate::HodgeStars`] for DEC,
/// [`crate::GalerkinMasses`] for Whitney forms with Galerkin masses):
///
/// - `d0` (`E × V`): row `e` has `−1` at the first and `+1` at the second vertex of the edge's
///   reference direction ([`IntrinsicTriangulation::edge_vertices`]; an edge from a vertex to
///   itself has an empty row); `d1` (`F × E`): `±1` per side of a face, `+1` where the face runs
///   along the edge's reference direction. `d1 d0 = 0` exactly.
/// - Boundary conditions as [`crate::DecComplex`]: absolute forms for
///   [`BoundaryCondition::Tangential`], relative forms (zero on the intrinsic boundary vertices
///   and edges) for [`BoundaryCondition::Normal`]. The harmonic dimension is the input's (the
///   same surface).
/// - Node positions are places on the input surface: vertices where they sit (inserted ones
///   included), edge midpoints and face centroids mapped through the correspondence.
///
/// Sampling and point evaluation take points of the **input** faces ([`IntrinsicWhitneySampling`],
/// [`IntrinsicEvaluation`]): field files hold one vector per input face.
///
/// [`IntrinsicTriangulation::edge_vertices`]: tvf_core::intrinsic::IntrinsicTriangulation::edge_vertices
pub type IntrinsicPrimalFormComplex<M> =
    SampledComplex<IntrinsicWhitneySampling, IntrinsicEvaluation, M>;

impl<M> IntrinsicPrimalFormComplex<M> {
    /// Assembles the complex with id `id` on the intrinsic triangulation `input` of `mesh` with
    /// boundary condition `boundary` (on a mesh with boundary); `masses` gives `[M0, M1, M2]`
    /// (intrinsic `V × V`, `E × E`, `F × F`) from the node spaces of the 0-, 1- and 2-forms. Fails
    /// with the masses' error, when a node cannot be placed on the input, or when
    /// [`ComplexParts::new`] refuses the parts.
    pub fn assemble(
        mesh: &TriangleMesh,
        input: &IntrinsicInput,
        id: &str,
        boundary: BoundaryCondition,
        masses: impl FnOnce(&[NodeSpace; 3]) -> Result<[Mass; 3], DiscretizationError>,
    ) -> Result<Self, DiscretizationError> {
        let (d0, d1, nodes) = intrinsic_forms(mesh, input, boundary)?;
        let masses = masses(&nodes)?;
        let fixed_edges = nodes[1].dirichlet.clone();
        let parts = ComplexParts::new(id, d0, d1, masses, nodes, mesh_topology(mesh, boundary))?;
        Ok(Self::from_intrinsic_parts(
            parts,
            IntrinsicWhitneySampling::new(mesh, input, fixed_edges)?,
            IntrinsicEvaluation::new(input),
            input.triangulation.clone(),
        ))
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
        vertices.dirichlet = intrinsic_boundary_nodes(tri, NodeKind::Vertices);
        vertices.constant_kernel = closed_components;
        edges.dirichlet = intrinsic_boundary_nodes(tri, NodeKind::Edges);
        d0 = drop_rows(&drop_columns(&d0, &vertices.dirichlet), &edges.dirichlet);
        d1 = drop_columns(&d1, &edges.dirichlet);
    } else {
        faces.constant_kernel = closed_components;
    }
    Ok((d0, d1, [vertices, edges, faces]))
}
