//! The vertex and face order of the generated meshes is pinned: recorded spectra, fixtures and
//! saved fields index their vertices and faces, so a change to a generator must keep both
//! orders (and every coordinate bit) or come with new recordings. Each mesh is summarised by an
//! FNV-1a hash of its coordinate bits and its face indices, in order.

use tvf_core::generate::{
    bumpy_torus, genus_surface, holed_torus, open_cylinder, perforated_plate, torus,
};
use tvf_core::TriangleMesh;

/// FNV-1a (64 bit) over the coordinate bits of every vertex, then the indices of every face.
fn order_hash(mesh: &TriangleMesh) -> u64 {
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    let words = mesh
        .positions()
        .iter()
        .flat_map(|p| p.map(f64::to_bits))
        .chain(mesh.faces().iter().flat_map(|f| f.map(|v| v as u64)));
    for word in words {
        for byte in word.to_le_bytes() {
            hash = (hash ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    hash
}

/// `(name, mesh, hash)`: the hashes were recorded from the generators as they are.
#[test]
fn generated_meshes_keep_their_vertex_and_face_order() {
    let meshes = [
        ("torus", torus(2.0, 0.5, 24, 12), 0x14fc_2ac8_40fd_c04c),
        (
            "holed torus",
            holed_torus(1.0, 0.4, 12, 6),
            0x94e4_6844_bae3_5669,
        ),
        (
            "bumpy torus",
            bumpy_torus(2.0, 0.6, 30, 14, 9, 0.3),
            0xe221_a96f_617c_6186,
        ),
        ("genus 0", Some(genus_surface(0, 6)), 0x3434_f22e_fd48_1a79),
        ("genus 1", Some(genus_surface(1, 4)), 0x3d21_afcf_afe7_3a0d),
        ("genus 2", Some(genus_surface(2, 8)), 0x9c0e_9935_747a_eae5),
        ("pants", Some(perforated_plate(2, 4)), 0x1b40_f2a1_b585_213f),
        (
            "open cylinder",
            Some(open_cylinder(12, 4, 1.0)),
            0xd858_cc9c_9e44_bfab,
        ),
    ];
    for (name, mesh, recorded) in meshes {
        let mesh = mesh.unwrap_or_else(|| panic!("{name}: valid parameters"));
        assert_eq!(
            order_hash(&mesh),
            recorded,
            "{name}: the vertex or face order (or a coordinate) changed"
        );
    }
}
