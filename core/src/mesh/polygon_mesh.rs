//! The [`PolygonMesh`] type: an oriented, edge-manifold mesh of polygons of any size ≥ 3,
//! possibly non-planar, with its topology and its display triangulation.

use super::any_mesh::Mesh;
use super::display_triangulation::DisplayTriangulation;
use super::error::MeshError;
use super::face_list::{FaceCorners, FaceList};
use super::topology::{build_topology, MeshTopology};
use super::validate::{polygon_centroid, polygon_vector_area};
use super::TriangleMesh;
use crate::geometry::{norm, scale};

/// An oriented, edge-manifold polygon mesh (de Goes, Butts, Desbrun 2020: faces of any size,
/// possibly non-planar).
///
/// Conventions (see `docs/conventions.md`):
/// - the corners of a face are listed counter-clockwise seen from the outside; its **vector
///   area** `a_f = ½ Σ_c p_c × p_{c+1}` gives its normal `a_f/|a_f|` and its area `|a_f|` (for a
///   planar polygon the area; for a non-planar one the area of its projection onto the plane
///   it is most spread in);
/// - edges `(a, b)`, `a < b`, numbered in lexicographic order, as for triangle meshes;
/// - edge `c` of face `f` joins corner `c` to corner `c + 1` ([`PolygonMesh::face_edge`]);
/// - the **display triangulation** ([`DisplayTriangulation`]) draws each polygon as the fan of
///   triangles `(centroid, p_c, p_{c+1})` around its corner average (a new vertex), and a
///   triangle face as itself.
#[derive(Debug, Clone)]
pub struct PolygonMesh {
    positions: Vec<[f64; 3]>,
    faces: FaceList,
    corner_edges: Vec<usize>,
    topology: MeshTopology,
    display: DisplayTriangulation,
}

impl PolygonMesh {
    /// Builds a mesh from vertex positions and counter-clockwise faces of at least three corners
    /// (0-based indices).
    ///
    /// Fails on non-finite coordinates, faces with fewer than three corners, out-of-range or
    /// repeated indices, non-manifold edges and inconsistently oriented neighbours. Geometry
    /// (zero vector areas, folded polygons) and vertex manifoldness are checked by the
    /// validation layer ([`crate::SurfaceMesh::validated`]), not here.
    pub fn new(positions: Vec<[f64; 3]>, faces: FaceList) -> Result<Self, MeshError> {
        if let Some(vertex) = positions
            .iter()
            .position(|p| p.iter().any(|x| !x.is_finite()))
        {
            return Err(MeshError::NonFiniteCoordinate { vertex });
        }
        let built = build_topology(positions.len(), &faces)?;
        let display = DisplayTriangulation::of(&positions, &faces)?;
        Ok(Self {
            positions,
            faces,
            corner_edges: built.corner_edges,
            topology: built.topology,
            display,
        })
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

    /// The faces.
    pub fn faces(&self) -> &FaceList {
        &self.faces
    }

    /// The corners of face `f`, counter-clockwise.
    pub fn face(&self, f: usize) -> &[usize] {
        self.faces.corners(f)
    }

    /// The edge joining corner `c` of face `f` to corner `c + 1` (cyclically).
    pub fn face_edge(&self, f: usize, c: usize) -> usize {
        self.corner_edges[self.faces.corner_index(f, c)]
    }

    /// The topology: edges, their faces, components, boundary loops, genus.
    pub fn topology(&self) -> &MeshTopology {
        &self.topology
    }

    /// The positions of the corners of face `f`.
    pub fn corner_positions(&self, f: usize) -> Vec<[f64; 3]> {
        self.face(f).iter().map(|&v| self.positions[v]).collect()
    }

    /// The vector area `a_f = ½ Σ_c p_c × p_{c+1}` of face `f` (units of length²).
    pub fn vector_area(&self, f: usize) -> [f64; 3] {
        polygon_vector_area(&self.corner_positions(f))
    }

    /// The area `|a_f|` of face `f` (units of length²).
    pub fn face_area(&self, f: usize) -> f64 {
        norm(self.vector_area(f))
    }

    /// The unit normal `a_f/|a_f|` of face `f`.
    pub fn face_normal(&self, f: usize) -> [f64; 3] {
        let a = self.vector_area(f);
        scale(a, 1.0 / norm(a))
    }

    /// The average of the corners of face `f`.
    pub fn centroid(&self, f: usize) -> [f64; 3] {
        polygon_centroid(&self.corner_positions(f))
    }

    /// The display triangulation.
    pub fn display(&self) -> &DisplayTriangulation {
        &self.display
    }

    /// The display triangulation as a triangle mesh (its vertices: the mesh's, then one
    /// centroid per face of more than three corners).
    pub fn display_mesh(&self) -> &TriangleMesh {
        self.display.mesh()
    }
}

impl Mesh for PolygonMesh {
    fn positions(&self) -> &[[f64; 3]] {
        &self.positions
    }

    fn face_corners(&self) -> &dyn FaceCorners {
        &self.faces
    }

    fn face_edge(&self, f: usize, c: usize) -> usize {
        self.corner_edges[self.faces.corner_index(f, c)]
    }

    fn topology(&self) -> &MeshTopology {
        &self.topology
    }

    fn as_triangles(&self) -> Option<&TriangleMesh> {
        None
    }

    fn fingerprint(&self) -> u64 {
        PolygonMesh::fingerprint(self)
    }
}
