//! Where the values of a complex live: [`NodeKind`], [`NodeSpace`] and the mesh facts a complex
//! carries ([`ComplexTopology`]).

/// The mesh element a node (degree of freedom) of a space belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NodeKind {
    /// One node per vertex (P1 potentials, DEC 0-forms), numbered as the mesh's vertices.
    Vertices,
    /// One node per edge (Crouzeix–Raviart functions at edge midpoints, DEC 1-forms), numbered
    /// as `SurfaceMesh::edges` (lexicographic `(a, b)`, `a < b`).
    Edges,
    /// One node per face (DEC 2-forms), numbered as the mesh's faces.
    Faces,
    /// Two nodes per face: the coefficients `(x[2t], x[2t+1])` of a tangent vector in the frame
    /// `(e1, e2)` of face `t` (piecewise constant face fields).
    FaceFrames,
}

impl NodeKind {
    /// Lower-case name for messages and file headers: `vertices`, `edges`, `faces`,
    /// `face-frames`.
    pub fn name(self) -> &'static str {
        match self {
            NodeKind::Vertices => "vertices",
            NodeKind::Edges => "edges",
            NodeKind::Faces => "faces",
            NodeKind::FaceFrames => "face-frames",
        }
    }
}

/// One space of a complex: what its nodes are, where they sit and which connected component each
/// belongs to.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeSpace {
    /// The mesh element of each node.
    pub kind: NodeKind,
    /// Position of every node in space (`n` entries): vertex, edge midpoint or face centroid.
    pub positions: Vec<[f64; 3]>,
    /// Connected component of every node (`n` entries, in `0..component_count`), or
    /// [`super::NO_COMPONENT`] for a node no face uses.
    pub components: Vec<usize>,
}

impl NodeSpace {
    /// Number of nodes `n`.
    pub fn len(&self) -> usize {
        self.components.len()
    }

    /// Whether the space has no node.
    pub fn is_empty(&self) -> bool {
        self.components.is_empty()
    }
}

/// The mesh facts a complex needs besides its matrices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ComplexTopology {
    /// Number of connected components of the mesh.
    pub component_count: usize,
    /// Dimension of the harmonic space `ker L` (`2g` summed over the components of a closed
    /// mesh).
    pub harmonic_dimension: usize,
    /// Whether the mesh has boundary edges.
    pub has_boundary: bool,
}
