//! The node spaces of a [`crate::MatrixComplex`]: the node kind of each space (as stated, else
//! from its size when only one kind has it), the nodes a boundary condition fixes
//! ([`FixedNodes`], checked against the matrices), and which constants lie in the kernel of each
//! stiffness, computed from the matrices.

use sprs::CsMat;
use tvf_core::discretization::sparse::transpose;
use tvf_core::discretization::{DiscretizationError, NodeKind, NodeSpace};
use tvf_core::SurfaceMesh;

/// The nodes of each space of a complex that its boundary condition fixes to zero (indices into
/// the space, any order). Their column of `d0` (potentials), row of `d0` and column of `d1`
/// (fields), row of `d1` (co-potentials) must be empty (no nonzero entry). Empty on a closed
/// mesh, and for a complex that imposes no boundary condition.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct FixedNodes {
    /// Fixed potential nodes (indices `< n0`).
    pub potentials: Vec<usize>,
    /// Fixed field nodes (indices `< n1`).
    pub fields: Vec<usize>,
    /// Fixed co-potential nodes (indices `< n2`).
    pub co_potentials: Vec<usize>,
}

impl FixedNodes {
    /// The fixed nodes of a complex's three spaces (its Dirichlet nodes).
    pub fn of(spaces: [&NodeSpace; 3]) -> Self {
        let fixed = |space: &NodeSpace| {
            (0..space.len())
                .filter(|&i| space.dirichlet.get(i) == Some(&true))
                .collect()
        };
        Self {
            potentials: fixed(spaces[0]),
            fields: fixed(spaces[1]),
            co_potentials: fixed(spaces[2]),
        }
    }
}

/// The node kind of each space of a complex (potentials, fields, co-potentials) where it is
/// stated (`info.json`'s `nodes`, Python's `nodes=`, or the sampling's field nodes); a space
/// whose kind is `None` gets the one kind of its size.
pub type StatedNodeKinds = [Option<NodeKind>; 3];

/// The three node spaces of `d0` (`n1 × n0`) and `d1` (`n2 × n1`) on `mesh`, of the `stated`
/// kinds (the others inferred from their sizes), with `fixed` as their Dirichlet nodes and the
/// constant kernels computed ([`constant_kernel`]). Errors: a size that is no node kind of the
/// mesh, not the stated kind's, or several kinds' with none stated; a fixed index out of range;
/// a fixed node whose row or column is not empty.
pub fn matrix_node_spaces(
    mesh: &SurfaceMesh,
    d0: &CsMat<f64>,
    d1: &CsMat<f64>,
    stated: &StatedNodeKinds,
    fixed: &FixedNodes,
) -> Result<[NodeSpace; 3], DiscretizationError> {
    let (n1, n0) = d0.shape();
    let n2 = d1.rows();
    let mut spaces = [
        node_space(mesh, n0, stated[0], "potential space (columns of d0)")?,
        node_space(mesh, n1, stated[1], "field space (rows of d0)")?,
        node_space(mesh, n2, stated[2], "co-potential space (rows of d1)")?,
    ];
    let lists = [&fixed.potentials, &fixed.fields, &fixed.co_potentials];
    for ((space, list), name) in spaces.iter_mut().zip(lists).zip(SPACE_NAMES) {
        for &i in list {
            if i >= space.len() {
                return Err(DiscretizationError::Inconsistent(format!(
                    "fixed {name} node {i} is out of range (the space has {} nodes)",
                    space.len()
                )));
            }
            space.dirichlet[i] = true;
        }
    }
    let (d0t, d1t) = (transpose(d0), transpose(d1));
    check_empty(&d0t, &spaces[0].dirichlet, "potential", "column of d0")?;
    check_empty(d0, &spaces[1].dirichlet, "field", "row of d0")?;
    check_empty(&d1t, &spaces[1].dirichlet, "field", "column of d1")?;
    check_empty(d1, &spaces[2].dirichlet, "co-potential", "row of d1")?;
    spaces[0].constant_kernel = constant_kernel(d0, &spaces[0]);
    spaces[2].constant_kernel = constant_kernel(&d1t, &spaces[2]);
    Ok(spaces)
}

/// Names of the three spaces in messages.
const SPACE_NAMES: [&str; 3] = ["potential", "field", "co-potential"];

/// Checks that the outer vectors (rows of a CSR matrix) of `a` marked in `fixed` hold no nonzero.
fn check_empty(
    a: &CsMat<f64>,
    fixed: &[bool],
    space: &str,
    what: &str,
) -> Result<(), DiscretizationError> {
    let a = tvf_core::discretization::sparse::to_csr(a);
    for (i, row) in a.outer_iterator().enumerate() {
        if fixed[i] {
            if let Some((j, value)) = row.iter().find(|(_, v)| **v != 0.0) {
                return Err(DiscretizationError::Inconsistent(format!(
                    "fixed {space} node {i} has a nonzero {what} (entry {j}: {value:e}); the \
                     boundary condition fixes it to zero, so its {what} must be empty"
                )));
            }
        }
    }
    Ok(())
}

/// For each component of `space`: whether the constant on its free nodes is in the kernel of
/// `a` (`n × space.len()`; `d0` for potentials, `d1ᵀ` for co-potentials): `max |a 1_c|` at most
/// [`crate::COMPLEX_TOLERANCE`] times `max |a|`.
pub fn constant_kernel(a: &CsMat<f64>, space: &NodeSpace) -> Vec<bool> {
    let components = space.constant_kernel.len();
    let scale = a.data().iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let a = tvf_core::discretization::sparse::to_csr(a);
    let mut largest = vec![0.0_f64; components];
    for row in a.outer_iterator() {
        let mut sums = vec![0.0_f64; components];
        for (j, &value) in row.iter() {
            if space.is_free(j) {
                sums[space.components[j]] += value;
            }
        }
        for (m, s) in largest.iter_mut().zip(sums) {
            *m = m.max(s.abs());
        }
    }
    largest
        .into_iter()
        .map(|m| m <= crate::COMPLEX_TOLERANCE * scale)
        .collect()
}

/// The dimension of the harmonic space the node spaces imply: `n1 − rank d0 − rank d1` on the
/// free nodes, with the kernel of `d0` (of `d1ᵀ`) the constants of [`NodeSpace::constant_kernel`].
pub fn implied_harmonic_dimension(spaces: &[NodeSpace; 3]) -> i64 {
    let rank = |space: &NodeSpace| space.free_count() as i64 - space.kernel_dimension() as i64;
    spaces[1].free_count() as i64 - rank(&spaces[0]) - rank(&spaces[2])
}

/// How many nodes a space of `kind` has on `mesh`.
pub(crate) fn kind_size(mesh: &SurfaceMesh, kind: NodeKind) -> usize {
    match kind {
        NodeKind::Vertices => mesh.vertex_count(),
        NodeKind::Edges => mesh.edge_count(),
        NodeKind::Faces => mesh.face_count(),
        NodeKind::FaceFrames => 2 * mesh.face_count(),
    }
}

/// `n`'s node kind on `mesh`: `stated` if given (checked against `n`), else the one kind of
/// that size. Errors: a size that is no kind's, or the stated kind's size, or that is several
/// kinds' (`V = F` on a torus of quads, `E = 2F` on any closed quad mesh).
fn node_kind(
    mesh: &SurfaceMesh,
    n: usize,
    stated: Option<NodeKind>,
    what: &str,
) -> Result<NodeKind, DiscretizationError> {
    if let Some(kind) = stated {
        let size = kind_size(mesh, kind);
        return match n == size {
            true => Ok(kind),
            false => Err(DiscretizationError::Inconsistent(format!(
                "the {what} has {n} nodes, but its nodes are stated to be {}: the mesh has {size}",
                kind.name()
            ))),
        };
    }
    let candidates: Vec<NodeKind> = NodeKind::ALL
        .into_iter()
        .filter(|&kind| kind_size(mesh, kind) == n)
        .collect();
    match candidates[..] {
        [kind] => Ok(kind),
        [] => Err(DiscretizationError::Inconsistent(format!(
            "the {what} has {n} nodes: not the mesh's {} vertices, {} edges, {} faces or {} \
             face-frame coefficients",
            mesh.vertex_count(),
            mesh.edge_count(),
            mesh.face_count(),
            2 * mesh.face_count()
        ))),
        _ => {
            let kinds: Vec<String> = candidates
                .iter()
                .map(|kind| format!("{n} {}", kind.name()))
                .collect();
            Err(DiscretizationError::Inconsistent(format!(
                "the {what} has {n} nodes, which is ambiguous: the mesh has {}; state the node \
                 kind of each space ({AMBIGUITY_HINT})",
                kinds.join(" and ")
            )))
        }
    }
}

/// Where node kinds are stated, in an ambiguity error.
const AMBIGUITY_HINT: &str =
    "info.json's nodes/potentials, nodes/fields, nodes/co_potentials; nodes= in Python";

/// The node space of `n` nodes on `mesh`, of kind `stated` or inferred ([`node_kind`]).
fn node_space(
    mesh: &SurfaceMesh,
    n: usize,
    stated: Option<NodeKind>,
    what: &str,
) -> Result<NodeSpace, DiscretizationError> {
    let positions = mesh.positions();
    let face_count = mesh.face_count();
    let kind = node_kind(mesh, n, stated, what)?;
    let (positions, components) = match kind {
        NodeKind::Vertices => (positions.to_vec(), mesh.vertex_components()),
        NodeKind::Edges => {
            let midpoints = mesh
                .edges()
                .iter()
                .map(|&[a, b]| [0, 1, 2].map(|k| 0.5 * (positions[a][k] + positions[b][k])))
                .collect();
            (midpoints, mesh.topology().edge_components())
        }
        NodeKind::Faces => {
            let centroids = (0..face_count).map(|f| mesh.face_centroid(f)).collect();
            (centroids, mesh.face_components().to_vec())
        }
        NodeKind::FaceFrames => {
            let centroids = (0..face_count)
                .flat_map(|f| [mesh.face_centroid(f); 2])
                .collect();
            let components = mesh
                .face_components()
                .iter()
                .flat_map(|&c| [c; 2])
                .collect();
            (centroids, components)
        }
    };
    Ok(NodeSpace::with_constant_kernel(
        kind,
        positions,
        components,
        mesh.component_count(),
    ))
}
