//! [`Mesh`]: what code written once for triangle, polygon and general meshes reads — vertex
//! positions, faces as corner lists, the edge of each face side, and the topology.

use super::face_list::FaceCorners;
use super::topology::MeshTopology;
use super::TriangleMesh;

/// Read access shared by [`crate::TriangleMesh`], [`crate::PolygonMesh`] and
/// [`crate::SurfaceMesh`], for code that works the same on all of them (writers, the incidences
/// and boundary nodes of primal forms). Each type also has these as inherent methods.
pub trait Mesh {
    /// Vertex positions, `V` entries.
    fn positions(&self) -> &[[f64; 3]];

    /// The faces as corner lists (counter-clockwise).
    fn face_corners(&self) -> &dyn FaceCorners;

    /// The edge joining corner `c` of face `f` to corner `c + 1` (cyclically).
    fn face_edge(&self, f: usize, c: usize) -> usize;

    /// The topology: edges `(a, b)`, `a < b`, in lexicographic order, their faces, components,
    /// boundary loops, genus.
    fn topology(&self) -> &MeshTopology;

    /// The mesh as a triangle mesh, if every face is a triangle.
    fn as_triangles(&self) -> Option<&TriangleMesh>;

    /// A 64-bit hash of the vertex coordinates and the faces (order included); a triangle mesh
    /// hashes the same whichever type holds it, and never like a polygon mesh.
    fn fingerprint(&self) -> u64;

    /// Number of vertices `V`.
    fn vertex_count(&self) -> usize {
        self.positions().len()
    }

    /// Number of edges `E`.
    fn edge_count(&self) -> usize {
        self.topology().edges().len()
    }

    /// Number of faces `F`.
    fn face_count(&self) -> usize {
        self.face_corners().face_count()
    }
}
