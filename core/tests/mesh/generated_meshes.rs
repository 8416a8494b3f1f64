//! Generated meshes have the counts, genus and orientation they promise.

use tvf_core::generate::{icosphere, torus};

#[test]
fn icosphere_counts_and_genus() {
    for level in 0..4 {
        let mesh = icosphere(level);
        let f = 20 * 4usize.pow(level);
        assert_eq!(mesh.face_count(), f);
        assert_eq!(mesh.edge_count(), 3 * f / 2);
        assert_eq!(mesh.vertex_count(), f / 2 + 2);
        assert!(mesh.is_closed());
        assert_eq!(mesh.component_count(), 1);
        assert_eq!(mesh.genus(), 0);
        assert_eq!(mesh.euler_characteristic(), 2);
    }
}

#[test]
fn icosphere_normals_point_outward() {
    let mesh = icosphere(2);
    for t in 0..mesh.face_count() {
        let n = mesh.face_normal(t);
        let c = mesh.corner(t, 0);
        assert!(n[0] * c[0] + n[1] * c[1] + n[2] * c[2] > 0.9);
    }
}

#[test]
fn torus_is_closed_genus_one() {
    let mesh = torus(2.0, 0.5, 24, 12).unwrap();
    assert_eq!(mesh.face_count(), 2 * 24 * 12);
    assert!(mesh.is_closed());
    assert_eq!(mesh.genus(), 1);
    assert_eq!(mesh.euler_characteristic(), 0);
    assert!(torus(1.0, 2.0, 24, 12).is_none());
}

#[test]
fn edges_are_lexicographic_and_opposite_their_corner() {
    let mesh = icosphere(1);
    assert!(mesh.edges().windows(2).all(|w| w[0] < w[1]));
    for (t, face) in mesh.faces().iter().enumerate() {
        for c in 0..3 {
            let [a, b] = mesh.edges()[mesh.face_edges()[t][c]];
            let (p, q) = (face[(c + 1) % 3], face[(c + 2) % 3]);
            assert_eq!([a, b], [p.min(q), p.max(q)]);
        }
    }
}
