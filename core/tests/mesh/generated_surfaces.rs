//! The genus-g surfaces, bumpy torus, rigid motions and jitter: closed, manifold, outward,
//! of the asked genus, and valid under full validation.

use tvf_core::generate::{bumpy_torus, genus_surface, icosphere, jitter, rigid_motion, torus};
use tvf_core::TriangleMesh;

/// Full validation of an existing mesh; returns its angle range.
fn assert_valid_closed_outward(mesh: &TriangleMesh) -> (f64, f64) {
    let (validated, report) =
        TriangleMesh::validated(mesh.positions().to_vec(), mesh.faces().to_vec())
            .expect("generated meshes pass full validation");
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    assert_eq!(validated.vertex_count(), mesh.vertex_count());
    assert!(mesh.is_closed());
    assert_eq!(mesh.component_count(), 1);
    assert!(mesh.signed_volume() > 0.0, "normals must point outward");
    (report.min_angle_deg, report.max_angle_deg)
}

#[test]
fn genus_surfaces_have_the_asked_genus() {
    for g in 0..=4 {
        for resolution in [4, 8] {
            let mesh = genus_surface(g, resolution);
            let (min, max) = assert_valid_closed_outward(&mesh);
            assert_eq!(mesh.genus(), g, "genus {g} resolution {resolution}");
            assert_eq!(mesh.euler_characteristic(), 2 - 2 * g as i64);
            assert!(min > 20.0 && max < 110.0, "g={g} angles {min}..{max}");
        }
    }
}

#[test]
fn genus_surface_default_sizes_are_small() {
    for g in 0..=4 {
        let f = genus_surface(g, 8).face_count();
        assert!((300..=6000).contains(&f), "genus {g}: {f} faces");
    }
    // Resolution refines: more faces, same genus.
    let coarse = genus_surface(2, 6);
    let fine = genus_surface(2, 12);
    assert!(fine.face_count() > 3 * coarse.face_count());
    assert_eq!(fine.genus(), 2);
    // Odd and tiny resolutions are rounded up, not rejected.
    assert_eq!(genus_surface(1, 0).genus(), 1);
    assert_eq!(
        genus_surface(3, 5).face_count(),
        genus_surface(3, 6).face_count()
    );
}

#[test]
fn genus_surface_has_no_slivers_and_fairly_uniform_areas() {
    let mesh = genus_surface(3, 8);
    let areas = mesh.face_areas();
    let mean = mesh.total_area() / areas.len() as f64;
    let smallest = areas.iter().cloned().fold(f64::INFINITY, f64::min);
    let largest = areas.iter().cloned().fold(0.0, f64::max);
    assert!(
        smallest > 0.1 * mean && largest < 5.0 * mean,
        "{smallest} {mean} {largest}"
    );
}

#[test]
fn bumpy_torus_is_a_bumpy_genus_one_surface() {
    let mesh = bumpy_torus(2.0, 0.5, 64, 32, 12, 0.4).unwrap();
    assert_valid_closed_outward(&mesh);
    assert_eq!(mesh.genus(), 1);
    assert_eq!(mesh.face_count(), 2 * 64 * 32);
    // Bumps make the tube radius vary between 0.5 and 0.5·1.4.
    let tube_radius = |p: [f64; 3]| {
        let r = (p[0] * p[0] + p[1] * p[1]).sqrt() - 2.0;
        (r * r + p[2] * p[2]).sqrt()
    };
    let radii: Vec<f64> = mesh.positions().iter().map(|&p| tube_radius(p)).collect();
    let (lo, hi) = radii
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &r| (a.min(r), b.max(r)));
    assert!(
        (0.5..0.51).contains(&lo) && hi > 0.65 && hi <= 0.7 + 1e-9,
        "{lo} {hi}"
    );
    // Deterministic.
    let again = bumpy_torus(2.0, 0.5, 64, 32, 12, 0.4).unwrap();
    assert_eq!(mesh.positions(), again.positions());
    assert!(bumpy_torus(1.0, 0.8, 16, 8, 3, 0.5).is_none());
    assert!(bumpy_torus(2.0, 0.5, 16, 2, 3, 0.5).is_none());
}

#[test]
fn rigid_motion_preserves_lengths_volume_and_topology() {
    let mesh = torus(2.0, 0.5, 24, 12).unwrap();
    let moved = rigid_motion(&mesh, [1.0, 2.0, -0.5], 0.7, [3.0, -1.0, 2.0]).unwrap();
    assert_eq!(moved.edges(), mesh.edges());
    assert_eq!(moved.faces(), mesh.faces());
    assert!((moved.signed_volume() - mesh.signed_volume()).abs() < 1e-9);
    for (&[a, b], _) in mesh.edges().iter().zip(0..) {
        let length = |m: &TriangleMesh| {
            tvf_core::geometry::norm(tvf_core::geometry::sub(m.positions()[a], m.positions()[b]))
        };
        assert!((length(&mesh) - length(&moved)).abs() < 1e-12);
    }
    // Zero axis: pure translation.
    let shifted = rigid_motion(&mesh, [0.0; 3], 1.0, [1.0, 0.0, 0.0]).unwrap();
    assert!((shifted.positions()[0][0] - mesh.positions()[0][0] - 1.0).abs() < 1e-15);
    assert!(rigid_motion(&mesh, [0.0, 0.0, 1.0], f64::NAN, [0.0; 3]).is_err());
}

#[test]
fn jitter_is_seeded_small_and_keeps_meshes_valid() {
    let meshes = [
        icosphere(2),
        genus_surface(2, 6),
        torus(2.0, 0.5, 24, 12).unwrap(),
    ];
    for mesh in &meshes {
        for seed in 0..5 {
            let jittered = jitter(mesh, 0.2, seed).unwrap();
            assert_valid_closed_outward(&jittered);
            assert_eq!(jittered.genus(), mesh.genus());
            assert_ne!(jittered.positions(), mesh.positions());
            assert_eq!(
                jitter(mesh, 0.2, seed).unwrap().positions(),
                jittered.positions()
            );
        }
    }
    assert_ne!(
        jitter(&meshes[0], 0.1, 1).unwrap().positions(),
        jitter(&meshes[0], 0.1, 2).unwrap().positions()
    );
    assert!(jitter(&meshes[0], f64::INFINITY, 0).is_err());
}
