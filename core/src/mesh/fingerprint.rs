//! [`TriangleMesh::fingerprint`] and [`PolygonMesh::fingerprint`]: a 64-bit fingerprint of a
//! mesh's numbers, which ties cached bases, compressed fields and constraint files to their mesh.

use crate::hash64::Hash64;
use crate::{PolygonMesh, TriangleMesh};

impl TriangleMesh {
    /// A 64-bit fingerprint of the mesh: the vertex and face counts, the exact `f64` bits of
    /// every vertex position and every face's vertex indices, in order. Equal meshes (same
    /// numbers, same order) have equal fingerprints; any change of a coordinate bit, an index or
    /// the order changes it with overwhelming probability. Not a cryptographic hash.
    pub fn fingerprint(&self) -> u64 {
        let mut h = Hash64::new();
        h.update(b"tvf-mesh");
        h.update_u64(self.vertex_count() as u64);
        h.update_u64(self.face_count() as u64);
        for p in self.positions() {
            for &x in p {
                h.update_f64(x);
            }
        }
        for f in self.faces() {
            for &i in f {
                h.update_u64(i as u64);
            }
        }
        h.finish()
    }
}

impl PolygonMesh {
    /// A 64-bit fingerprint like [`TriangleMesh::fingerprint`], hashing each face's size before
    /// its vertex indices (and under another tag), so a polygon mesh never shares a fingerprint
    /// with a triangle mesh.
    pub fn fingerprint(&self) -> u64 {
        let mut h = Hash64::new();
        h.update(b"tvf-polygon-mesh");
        h.update_u64(self.vertex_count() as u64);
        h.update_u64(self.face_count() as u64);
        for p in self.positions() {
            for &x in p {
                h.update_f64(x);
            }
        }
        for face in self.faces().iter() {
            h.update_u64(face.len() as u64);
            for &i in face {
                h.update_u64(i as u64);
            }
        }
        h.finish()
    }
}

#[cfg(test)]
mod tests {
    use crate::generate::icosphere;
    use crate::TriangleMesh;

    #[test]
    fn the_fingerprint_sees_every_coordinate_and_index() {
        let mesh = icosphere(1);
        let base = mesh.fingerprint();
        assert_eq!(base, icosphere(1).fingerprint());
        let mut positions = mesh.positions().to_vec();
        positions[17][2] = f64::from_bits(positions[17][2].to_bits() ^ 1);
        let moved = TriangleMesh::new(positions, mesh.faces().to_vec()).unwrap();
        assert_ne!(moved.fingerprint(), base);
        let mut faces = mesh.faces().to_vec();
        faces[3] = [faces[3][1], faces[3][2], faces[3][0]];
        let rotated = TriangleMesh::new(mesh.positions().to_vec(), faces).unwrap();
        assert_ne!(rotated.fingerprint(), base);
    }
}
