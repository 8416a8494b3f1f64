//! Boundary conditions of a complex on a mesh with boundary (Poelke & Polthier 2016): which nodes
//! a space fixes to zero, the matching restriction of `d0` or `d1`, and the harmonic dimension the
//! theory gives.

use sprs::CsMat;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::discretization::{BoundaryCondition, ComplexTopology, NodeKind, NodeSpace};
use tvf_core::mesh::Mesh;

/// The topology of `mesh` as a complex with boundary condition `condition` sees it: components,
/// boundary, and the harmonic dimension summed over the components — `2g` on a closed component,
/// `2g + b − 1` on a component with `b ≥ 1` boundary loops (for both boundary conditions).
pub fn mesh_topology<M: Mesh + ?Sized>(mesh: &M, condition: BoundaryCondition) -> ComplexTopology {
    let loops = component_boundary_loops(mesh);
    let topology = mesh.topology();
    let harmonic_dimension = topology
        .component_genera(mesh.face_corners())
        .iter()
        .zip(&loops)
        .map(|(&g, &b)| if b == 0 { 2 * g } else { 2 * g + b - 1 })
        .sum();
    ComplexTopology {
        component_count: topology.component_count(),
        harmonic_dimension,
        has_boundary: !topology.is_closed(),
        boundary_condition: condition,
    }
}

/// Number of boundary loops of every connected component (`component_count` entries).
pub fn component_boundary_loops<M: Mesh + ?Sized>(mesh: &M) -> Vec<usize> {
    let topology = mesh.topology();
    let mut loops = vec![0; topology.component_count()];
    let vertex_component = topology.vertex_components(mesh.face_corners());
    for cycle in topology.boundary_loops() {
        loops[vertex_component[cycle[0]]] += 1;
    }
    loops
}

/// The nodes of kind `kind` that lie on the boundary (`n` entries): vertices of boundary edges,
/// boundary edges; never faces.
pub fn boundary_nodes<M: Mesh + ?Sized>(mesh: &M, kind: NodeKind) -> Vec<bool> {
    let topology = mesh.topology();
    let face_count = mesh.face_corners().face_count();
    match kind {
        NodeKind::Vertices => {
            let mut on_boundary = vec![false; mesh.positions().len()];
            for e in topology.boundary_edges() {
                for v in topology.edges()[e] {
                    on_boundary[v] = true;
                }
            }
            on_boundary
        }
        NodeKind::Edges => (0..topology.edges().len())
            .map(|e| topology.is_boundary_edge(e))
            .collect(),
        NodeKind::Faces => vec![false; face_count],
        NodeKind::FaceFrames => vec![false; 2 * face_count],
    }
}

/// `space` with every boundary node of `mesh` made a Dirichlet node (value fixed to zero); the
/// constants stay in the kernel only on closed components.
pub fn with_dirichlet_boundary<M: Mesh + ?Sized>(mut space: NodeSpace, mesh: &M) -> NodeSpace {
    space.dirichlet = boundary_nodes(mesh, space.kind);
    let loops = component_boundary_loops(mesh);
    space.constant_kernel = loops.iter().map(|&b| b == 0).collect();
    space
}

/// `a` with the columns `j` where `drop[j]` removed from its pattern (set to zero; the shape is
/// kept).
pub fn drop_columns(a: &CsMat<f64>, drop: &[bool]) -> CsMat<f64> {
    filter(a, |_, j| !drop[j])
}

/// `a` with the rows `i` where `drop[i]` removed from its pattern (set to zero; the shape is
/// kept).
pub fn drop_rows(a: &CsMat<f64>, drop: &[bool]) -> CsMat<f64> {
    filter(a, |i, _| !drop[i])
}

fn filter(a: &CsMat<f64>, keep: impl Fn(usize, usize) -> bool) -> CsMat<f64> {
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for (&value, (i, j)) in a.iter() {
        if keep(i, j) {
            rows.push(i);
            cols.push(j);
            values.push(value);
        }
    }
    from_triplets(a.rows(), a.cols(), rows, cols, values)
}
