//! The property the three mesh-reader targets share: any bytes give a mesh or a typed error,
//! never a panic, and a mesh that loads names only vertices it has.

use tvf_core::io::{parse_mesh_bytes, MeshFormat};

/// Parses `data` as `format` (reported as the file `name`) and checks every face corner of a
/// mesh that loads against its vertex count.
pub fn check_mesh_reader(data: &[u8], format: MeshFormat, name: &str) {
    if let Ok(loaded) = parse_mesh_bytes(data, format, name) {
        let mesh = loaded.mesh;
        let faces = mesh.faces();
        assert!((0..faces.face_count())
            .flat_map(|f| faces.corners(f).iter())
            .all(|&v| v < mesh.vertex_count()));
    }
}
