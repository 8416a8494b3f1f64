//! Streamlines stay on the surface and follow the field; fur strands grow off it.

use crate::common::{rotation_field, torus_tube_field};
use tvf_core::generate::{icosphere, torus};
use tvf_core::geometry::{cross, dot, norm, sub};
use tvf_core::{SurfaceMesh, TriangleMesh};
use tvf_render::{
    grow_fur, mean_edge_length, trace_streamlines, FurOptions, RenderError, StreamlineOptions,
};

/// Barycentric coordinates of `x` in face `t` and the distance of `x` from the face plane.
fn locate(mesh: &TriangleMesh, t: usize, x: [f64; 3]) -> ([f64; 3], f64) {
    let [a, b, c] = [0, 1, 2].map(|k| mesh.corner(t, k));
    let n = mesh.face_normal(t);
    let area2 = dot(cross(sub(b, a), sub(c, a)), n);
    let l = [
        dot(cross(sub(b, x), sub(c, x)), n) / area2,
        dot(cross(sub(c, x), sub(a, x)), n) / area2,
        dot(cross(sub(a, x), sub(b, x)), n) / area2,
    ];
    (l, dot(sub(x, a), n).abs())
}

fn assert_on_surface(mesh: &TriangleMesh, lines: &[tvf_render::Streamline]) {
    let h = mean_edge_length(mesh);
    for line in lines {
        assert_eq!(line.points.len(), line.faces.len() + 1);
        for (i, &t) in line.faces.iter().enumerate() {
            for x in [line.points[i], line.points[i + 1]] {
                let (l, off_plane) = locate(mesh, t, x);
                assert!(
                    off_plane < 1e-10 * h,
                    "point {x:?} is {off_plane} off face {t}"
                );
                assert!(
                    l.iter().all(|&v| v > -1e-9),
                    "point {x:?} outside face {t}: {l:?}"
                );
            }
        }
    }
}

#[test]
fn sphere_rotation_streamlines_are_latitude_circles_on_the_surface() {
    let mesh = icosphere(4);
    let field = rotation_field(&mesh, [0.0, 0.0, 1.0]);
    let lines = trace_streamlines(
        &mesh,
        &field,
        &StreamlineOptions {
            count: 200,
            ..Default::default()
        },
    )
    .unwrap();
    // Latitude circles a separation √(4π / 200) ≈ 0.25 apart: about 12 rows, each cut
    // into pieces of at most 12 separations.
    assert!(lines.len() > 12, "{} lines", lines.len());
    assert_on_surface(&mesh, &lines);
    // Along a rotation about z, the height z changes only by the discretisation error.
    let h = mean_edge_length(&mesh);
    for line in &lines {
        let zs = line.points.iter().map(|p| p[2]);
        let (lo, hi) = zs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), z| {
            (a.min(z), b.max(z))
        });
        assert!(hi - lo < 1.5 * h, "height drifts by {} (edge {h})", hi - lo);
    }
    // Deterministic.
    let again = trace_streamlines(
        &mesh,
        &field,
        &StreamlineOptions {
            count: 200,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(lines, again);
}

#[test]
fn torus_streamlines_cover_the_surface_evenly() {
    let mesh = torus(1.0, 0.4, 120, 48).unwrap();
    let field = torus_tube_field(&mesh, 1.0);
    let count = 500;
    let lines = trace_streamlines(
        &mesh,
        &field,
        &StreamlineOptions {
            count,
            ..Default::default()
        },
    )
    .unwrap();
    assert_on_surface(&mesh, &lines);
    // Total length ≈ area / separation when the lines are evenly spaced.
    let separation = (mesh.total_area() / count as f64).sqrt();
    let total: f64 = lines.iter().map(|l| l.length()).sum();
    let ideal = mesh.total_area() / separation;
    assert!(
        total > 0.5 * ideal && total < 2.0 * ideal,
        "total {total}, ideal {ideal}"
    );
    // Each line follows the field: segment directions agree with the face's vector.
    for line in &lines {
        for (i, &t) in line.faces.iter().enumerate() {
            let d = sub(line.points[i + 1], line.points[i]);
            if norm(d) > 1e-9 {
                assert!(dot(d, field[t]) / norm(d) / norm(field[t]) > 0.999);
            }
        }
    }
}

#[test]
fn streamlines_stop_at_boundaries() {
    // Half of a torus cut open along u: the field ∂/∂u runs into the cut.
    let full = torus(1.0, 0.4, 48, 16).unwrap();
    let keep: Vec<[usize; 3]> = full
        .faces()
        .iter()
        .copied()
        .filter(|f| f.iter().all(|&v| full.positions()[v][1] >= -1e-12))
        .collect();
    let mesh = TriangleMesh::new(full.positions().to_vec(), keep).unwrap();
    assert!(!mesh.is_closed());
    let field = rotation_field(&mesh, [0.0, 0.0, 1.0]);
    let lines = trace_streamlines(
        &mesh,
        &field,
        &StreamlineOptions {
            count: 100,
            max_length: 100.0,
            ..Default::default()
        },
    )
    .unwrap();
    assert_on_surface(&mesh, &lines);
    assert!(!lines.is_empty());
}

#[test]
fn fur_roots_on_the_surface_tips_above_it() {
    let mesh = SurfaceMesh::from(icosphere(4));
    let field = rotation_field(mesh.as_triangles().unwrap(), [0.0, 0.0, 1.0]);
    let options = FurOptions {
        strand_count: 2000,
        ..Default::default()
    };
    let strands = grow_fur(&mesh, &field, &options).unwrap();
    // Strands only vanish near the poles where |ω × p| is tiny.
    assert!(strands.len() > 1900, "{} strands", strands.len());
    let h = mean_edge_length(mesh.as_triangles().unwrap());
    for s in &strands {
        assert_eq!(s.len(), options.points_per_strand);
        let root = norm(s[0]);
        // The root lies on a flat face inside the unit sphere, at most the sagitta below it.
        assert!(
            root <= 1.0 + 1e-12 && root > 1.0 - h * h,
            "root radius {root}"
        );
        assert!(norm(s[s.len() - 1]) > root, "tip not lifted");
        let length: f64 = s.windows(2).map(|w| norm(sub(w[1], w[0]))).sum();
        // Surface length at most `length × diagonal` (2√3 for the unit sphere's box); the lift
        // adds at most a factor √(1 + (2·lift)²) ≈ 1.22.
        let longest = options.length * 2.0 * 3f64.sqrt();
        assert!(length < 1.25 * longest, "strand length {length}");
    }
    // Same seed, same fur.
    assert_eq!(strands, grow_fur(&mesh, &field, &options).unwrap());
    assert!(matches!(
        grow_fur(&mesh, &field[..10], &options),
        Err(RenderError::FaceCountMismatch { .. })
    ));
}
