//! The [`TriangleMesh`] type: an oriented, edge-manifold triangle mesh with its topology.

use super::any_mesh::Mesh;
use super::error::MeshError;
use super::face_list::FaceCorners;
use super::topology::{build_topology, MeshTopology};
use crate::geometry::{cross, norm, sub};

/// An oriented, edge-manifold triangle mesh and the topology the discrete operators need.
///
/// Conventions (see `docs/conventions.md`):
/// - faces are counter-clockwise seen from the outside, normal `(p1−p0)×(p2−p0)/|…|`;
/// - edge `e` is `(a, b)` with `a < b`, and edges are numbered in **lexicographic order of
///   `(a, b)`** (tools outside tvf rely on this);
/// - in face `t = (i0, i1, i2)`, corner `c` is opposite the edge `{i_{c+1}, i_{c+2}}`, and
///   [`TriangleMesh::face_edges`]`[t][c]` is that edge.
#[derive(Debug, Clone)]
pub struct TriangleMesh {
    positions: Vec<[f64; 3]>,
    faces: Vec<[usize; 3]>,
    face_edges: Vec<[usize; 3]>,
    topology: MeshTopology,
}

impl TriangleMesh {
    /// Builds a mesh from vertex positions and counter-clockwise faces (0-based indices).
    ///
    /// Fails on non-finite coordinates, out-of-range or repeated indices, non-manifold edges and
    /// inconsistently oriented neighbours. Geometric quality (zero areas, slivers) and vertex
    /// manifoldness are checked by the validation layer, not here.
    pub fn new(positions: Vec<[f64; 3]>, faces: Vec<[usize; 3]>) -> Result<Self, MeshError> {
        if let Some(vertex) = positions
            .iter()
            .position(|p| p.iter().any(|x| !x.is_finite()))
        {
            return Err(MeshError::NonFiniteCoordinate { vertex });
        }
        let built = build_topology(positions.len(), faces.as_slice())?;
        // The general topology numbers the edge from corner c to corner c + 1; a triangle's
        // edge opposite corner c is the one from corner c + 1.
        let face_edges = built
            .corner_edges
            .chunks_exact(3)
            .map(|e| [e[1], e[2], e[0]])
            .collect();
        Ok(Self {
            positions,
            faces,
            face_edges,
            topology: built.topology,
        })
    }

    /// The topology: edges, their faces, components, boundary loops, genus.
    pub fn topology(&self) -> &MeshTopology {
        &self.topology
    }

    /// Number of vertices `V`.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of edges `E`.
    pub fn edge_count(&self) -> usize {
        self.topology.edges().len()
    }

    /// Number of faces `F`.
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }

    /// Vertex positions, `V` entries.
    pub fn positions(&self) -> &[[f64; 3]] {
        &self.positions
    }

    /// Faces as counter-clockwise vertex triples, `F` entries.
    pub fn faces(&self) -> &[[usize; 3]] {
        &self.faces
    }

    /// Edges `(a, b)`, `a < b`, in lexicographic order, `E` entries.
    pub fn edges(&self) -> &[[usize; 2]] {
        self.topology.edges()
    }

    /// `face_edges()[t][c]`: the edge opposite corner `c` of face `t`.
    pub fn face_edges(&self) -> &[[usize; 3]] {
        &self.face_edges
    }

    /// `edge_faces()[e] = [left, right]`: `left` traverses edge `(a, b)` as `a → b`, `right` as
    /// `b → a`; [`NO_FACE`] on the missing side of a boundary edge.
    pub fn edge_faces(&self) -> &[[usize; 2]] {
        self.topology.edge_faces()
    }

    /// Position of corner `c` of face `t`.
    pub fn corner(&self, t: usize, c: usize) -> [f64; 3] {
        self.positions[self.faces[t][c]]
    }

    /// Non-normalised normal `(p1−p0)×(p2−p0)` of face `t`; its length is twice the area.
    pub fn face_normal_scaled(&self, t: usize) -> [f64; 3] {
        let [p0, p1, p2] = self.faces[t].map(|i| self.positions[i]);
        cross(sub(p1, p0), sub(p2, p0))
    }

    /// Unit normal of face `t` (counter-clockwise orientation).
    pub fn face_normal(&self, t: usize) -> [f64; 3] {
        let n = self.face_normal_scaled(t);
        let len = norm(n);
        [n[0] / len, n[1] / len, n[2] / len]
    }

    /// Area of face `t` (units of length²).
    pub fn face_area(&self, t: usize) -> f64 {
        0.5 * norm(self.face_normal_scaled(t))
    }

    /// Areas of all faces, `F` entries.
    pub fn face_areas(&self) -> Vec<f64> {
        (0..self.face_count()).map(|t| self.face_area(t)).collect()
    }

    /// Total surface area.
    pub fn total_area(&self) -> f64 {
        self.face_areas().iter().sum()
    }

    /// Whether edge `e` has only one face.
    pub fn is_boundary_edge(&self, e: usize) -> bool {
        self.topology.is_boundary_edge(e)
    }

    /// Indices of the boundary edges, ascending.
    pub fn boundary_edges(&self) -> Vec<usize> {
        self.topology.boundary_edges()
    }

    /// Whether the mesh has no boundary edge.
    pub fn is_closed(&self) -> bool {
        self.topology.is_closed()
    }

    /// Boundary loops as closed vertex cycles, each following the boundary orientation
    /// (the surface on the left).
    pub fn boundary_loops(&self) -> Vec<Vec<usize>> {
        self.topology.boundary_loops()
    }

    /// Number of edge-connected components.
    pub fn component_count(&self) -> usize {
        self.topology.component_count()
    }

    /// Component id of every face, `F` entries, in `0..component_count()`.
    pub fn face_components(&self) -> &[usize] {
        self.topology.face_components()
    }

    /// Component id of every vertex (`usize::MAX` for a vertex no face uses), `V` entries.
    pub fn vertex_components(&self) -> Vec<usize> {
        self.topology.vertex_components(self.faces.as_slice())
    }

    /// Component id of every edge, `E` entries.
    pub fn edge_components(&self) -> Vec<usize> {
        self.topology.edge_components()
    }

    /// Euler characteristic `V − E + F` over referenced vertices.
    pub fn euler_characteristic(&self) -> i64 {
        self.component_euler_characteristics().iter().sum()
    }

    /// Euler characteristic of every component.
    pub fn component_euler_characteristics(&self) -> Vec<i64> {
        self.topology
            .component_euler_characteristics(self.faces.as_slice())
    }

    /// Genus of every component, `(2 − b − χ)/2` with `b` its boundary loops.
    pub fn component_genera(&self) -> Vec<usize> {
        self.topology.component_genera(self.faces.as_slice())
    }

    /// Total genus, summed over components. On a closed mesh the harmonic fields number `2·genus()`.
    pub fn genus(&self) -> usize {
        self.component_genera().iter().sum()
    }
}

impl Mesh for TriangleMesh {
    fn positions(&self) -> &[[f64; 3]] {
        &self.positions
    }

    fn face_corners(&self) -> &dyn FaceCorners {
        &self.faces
    }

    fn face_edge(&self, f: usize, c: usize) -> usize {
        self.face_edges[f][(c + 2) % 3]
    }

    fn topology(&self) -> &MeshTopology {
        &self.topology
    }

    fn as_triangles(&self) -> Option<&TriangleMesh> {
        Some(self)
    }

    fn fingerprint(&self) -> u64 {
        TriangleMesh::fingerprint(self)
    }
}
