//! Where the values of a complex live: [`NodeKind`], [`NodeSpace`] and the mesh facts a complex
//! carries ([`ComplexTopology`]).

/// The mesh element a node (degree of freedom) of a space belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NodeKind {
    /// One node per vertex (P1 potentials, DEC 0-forms), numbered as the mesh's vertices.
    Vertices,
    /// One node per edge (Crouzeix–Raviart functions at edge midpoints, DEC 1-forms), numbered
    /// as `TriangleMesh::edges` (lexicographic `(a, b)`, `a < b`).
    Edges,
    /// One node per face (DEC 2-forms), numbered as the mesh's faces.
    Faces,
    /// Two nodes per face: the coefficients `(x[2t], x[2t+1])` of a tangent vector in the frame
    /// `(e1, e2)` of face `t` (piecewise constant face fields).
    FaceFrames,
}

impl NodeKind {
    /// Every kind, in the order a complex from matrices tries them by size.
    pub const ALL: [NodeKind; 4] = [
        NodeKind::Vertices,
        NodeKind::Edges,
        NodeKind::Faces,
        NodeKind::FaceFrames,
    ];

    /// The kind named `name` ([`NodeKind::name`]), if any.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|kind| kind.name() == name)
    }

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

/// One space of a complex: what its nodes are, where they sit, which connected component each
/// belongs to, and which values the boundary condition fixes.
///
/// On a mesh with boundary a space may have **Dirichlet nodes**: nodes whose value is zero by the
/// boundary condition (P1 at boundary vertices, Crouzeix–Raviart at boundary edge midpoints, DEC
/// relative forms at boundary vertices and edges). They keep their index (node `i` is still
/// vertex or edge `i`), but their column of `d0` (potential space), row of `d1` (co-potential
/// space), or row of `d0` and column of `d1` (field space) is zero, so they carry no degree of
/// freedom: Poisson solves and eigenproblems work on the **free** nodes ([`NodeSpace::is_free`]).
/// A field is zero on the Dirichlet field nodes: sampling gives them no weight, and the
/// decomposition refuses a field that is not zero there. `L` restricted to the free field nodes
/// has the harmonic fields as its kernel (each Dirichlet field node adds a zero row and column
/// to `S`).
#[derive(Debug, Clone, PartialEq)]
pub struct NodeSpace {
    /// The mesh element of each node.
    pub kind: NodeKind,
    /// Position of every node in space (`n` entries): vertex, edge midpoint or face centroid.
    pub positions: Vec<[f64; 3]>,
    /// Connected component of every node (`n` entries, in `0..component_count`), or
    /// [`super::NO_COMPONENT`] for a node no face uses.
    pub components: Vec<usize>,
    /// Whether each node's value is fixed to zero by the boundary condition (`n` entries; all
    /// `false` on a closed mesh and in a space with free boundary values).
    pub dirichlet: Vec<bool>,
    /// Whether the constants of each connected component (`component_count` entries) lie in the
    /// kernel of the space's stiffness (`d0ᵀ M1 d0` for potentials, `d1 M1⁻¹ d1ᵀ` for
    /// co-potentials): `true` on closed components and for free boundary values (Neumann),
    /// `false` where the boundary condition pins values (Dirichlet; DEC 2-forms on a component
    /// with boundary).
    pub constant_kernel: Vec<bool>,
}

impl NodeSpace {
    /// A space without Dirichlet nodes whose constants are in the kernel on every one of the
    /// `component_count` components (the spaces of a closed mesh).
    pub fn with_constant_kernel(
        kind: NodeKind,
        positions: Vec<[f64; 3]>,
        components: Vec<usize>,
        component_count: usize,
    ) -> Self {
        let n = components.len();
        Self {
            kind,
            positions,
            components,
            dirichlet: vec![false; n],
            constant_kernel: vec![true; component_count],
        }
    }

    /// Number of nodes `n`.
    pub fn len(&self) -> usize {
        self.components.len()
    }

    /// Whether the space has no node.
    pub fn is_empty(&self) -> bool {
        self.components.is_empty()
    }

    /// Whether node `i` is a degree of freedom: some face uses it and the boundary condition does
    /// not fix it.
    pub fn is_free(&self, i: usize) -> bool {
        self.components[i] != super::NO_COMPONENT
            && !self.dirichlet.get(i).copied().unwrap_or(false)
    }

    /// Number of free nodes.
    pub fn free_count(&self) -> usize {
        (0..self.len()).filter(|&i| self.is_free(i)).count()
    }

    /// Dimension of the kernel of the space's stiffness on the free nodes: the number of
    /// components whose constants are in it.
    pub fn kernel_dimension(&self) -> usize {
        self.constant_kernel.iter().filter(|&&k| k).count()
    }

    /// Number of Dirichlet nodes.
    pub fn dirichlet_count(&self) -> usize {
        self.dirichlet.iter().filter(|&&d| d).count()
    }
}

/// Which boundary condition a complex imposes on a mesh with boundary (Poelke & Polthier 2016).
/// Irrelevant on closed meshes, where both give the same complex.
///
/// | choice | potentials | co-potentials | fields at the boundary | harmonic fields |
/// |---|---|---|---|---|
/// | `Tangential` (default) | free (Neumann) | zero on the boundary (Dirichlet) | tangential | `H_N`, Neumann fields |
/// | `Normal` | zero on the boundary (Dirichlet) | free (Neumann) | normal | `H_D`, Dirichlet fields |
///
/// Both have `2g + b − 1` harmonic fields on a connected component of genus `g` with `b ≥ 1`
/// boundary loops. For DEC, `Tangential` is the complex of absolute forms and `Normal` that of
/// relative forms (zero on boundary vertices and edges).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum BoundaryCondition {
    /// Potentials free, co-potentials zero on the boundary: every eigenfield and harmonic field
    /// is tangential to the boundary (`X_h = ∇S_h ⊕ J∇S*_h,0 ⊕ H_N` for the conforming complex).
    #[default]
    Tangential,
    /// Potentials zero on the boundary, co-potentials free: every eigenfield and harmonic field
    /// is normal to the boundary (`X_h = ∇S_h,0 ⊕ J∇S*_h ⊕ H_D` for the conforming complex).
    Normal,
}

impl BoundaryCondition {
    /// Both choices, the default first.
    pub const ALL: [BoundaryCondition; 2] =
        [BoundaryCondition::Tangential, BoundaryCondition::Normal];

    /// Lower-case name, as on command lines and in ids: `tangential`, `normal`.
    pub fn name(self) -> &'static str {
        match self {
            BoundaryCondition::Tangential => "tangential",
            BoundaryCondition::Normal => "normal",
        }
    }

    /// The choice named `name` (`tangential` or `normal`).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|b| b.name() == name)
    }
}

/// The mesh facts a complex needs besides its matrices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ComplexTopology {
    /// Number of connected components of the mesh.
    pub component_count: usize,
    /// Dimension of the harmonic space `ker L`: summed over the components, `2g` on a closed
    /// component and `2g + b − 1` on one with `b ≥ 1` boundary loops.
    pub harmonic_dimension: usize,
    /// Whether the mesh has boundary edges.
    pub has_boundary: bool,
    /// The boundary condition the complex imposes (meaningful only if `has_boundary`).
    pub boundary_condition: BoundaryCondition,
}
