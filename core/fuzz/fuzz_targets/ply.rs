//! Fuzzes the PLY reader: any bytes must give a mesh or a typed error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tvf_core::io::{parse_mesh_bytes, MeshFormat};

fuzz_target!(|data: &[u8]| {
    if let Ok(loaded) = parse_mesh_bytes(data, MeshFormat::Ply, "fuzz.ply") {
        let mesh = loaded.mesh;
        assert!(mesh
            .faces()
            .iter()
            .flatten()
            .all(|&v| v < mesh.vertex_count()));
    }
});
