//! Property tests of intrinsic triangulations over generated meshes — closed of genus 0 to 3,
//! with boundary, several components, square grids — jittered and stretched into non-Delaunay
//! shapes; proptest shrinks a failure to the smallest mesh, jitter and stretch that show it.

use super::test_meshes::{square_grid, stretched, union};
use super::{IntrinsicError, IntrinsicTriangulation, RefineOptions, TrianglePoint};
use super::{DELAUNAY_FLIP_TOLERANCE, STRICT_DELAUNAY_MARGIN};
use crate::generate::{
    disk, genus_surface, hemisphere, holed_torus, icosphere, jitter, open_cylinder,
    perforated_plate, torus,
};
use crate::TriangleMesh;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

/// The generated surfaces the strategies start from.
#[derive(Debug, Clone, Copy)]
enum Base {
    Icosphere(u32),
    Torus(usize, usize),
    Genus(usize),
    Disk(usize),
    Hemisphere(usize),
    Cylinder(usize),
    Plate(usize),
    HoledTorus,
    Grid(usize),
    TwoComponents,
}

impl Base {
    fn mesh(self) -> TriangleMesh {
        match self {
            Base::Icosphere(level) => icosphere(level),
            Base::Torus(around, tube) => torus(2.0, 0.7, around, tube).expect("torus"),
            Base::Genus(g) => genus_surface(g, 2),
            Base::Disk(rings) => disk(rings),
            Base::Hemisphere(rings) => hemisphere(rings),
            Base::Cylinder(around) => open_cylinder(around, 3, 1.5),
            Base::Plate(holes) => perforated_plate(holes, 2),
            Base::HoledTorus => holed_torus(2.0, 0.7, 12, 8).expect("holed torus"),
            Base::Grid(n) => square_grid(n),
            Base::TwoComponents => union(&icosphere(1), &disk(2), [3.0, 0.0, 0.0]),
        }
    }
}

fn base() -> impl Strategy<Value = Base> {
    prop_oneof![
        (0u32..=2).prop_map(Base::Icosphere),
        (6usize..=14, 4usize..=8).prop_map(|(a, t)| Base::Torus(a, t)),
        (1usize..=3).prop_map(Base::Genus),
        (1usize..=4).prop_map(Base::Disk),
        (1usize..=4).prop_map(Base::Hemisphere),
        (4usize..=10).prop_map(Base::Cylinder),
        (1usize..=2).prop_map(Base::Plate),
        Just(Base::HoledTorus),
        (1usize..=5).prop_map(Base::Grid),
        Just(Base::TwoComponents),
    ]
}

/// A base surface, jittered (amplitude 0 to 0.4 of the local edge length) and stretched per
/// axis (factors 0.25 to 4).
fn mesh() -> impl Strategy<Value = (Base, TriangleMesh)> {
    (
        base(),
        0.0..0.4f64,
        any::<u64>(),
        (0.25..4.0f64, 0.25..4.0f64, 0.25..4.0f64),
    )
        .prop_map(|(base, amplitude, seed, (x, y, z))| {
            let jittered = jitter(&base.mesh(), amplitude, seed).expect("finite amplitude");
            (base, stretched(&jittered, [x, y, z]))
        })
}

/// The intrinsic triangulation of `mesh`; `None` for a face jitter made degenerate.
fn intrinsic(mesh: &TriangleMesh) -> Option<IntrinsicTriangulation> {
    match IntrinsicTriangulation::new(mesh) {
        Err(IntrinsicError::DegenerateFace { .. }) => None,
        other => Some(other.expect("only degenerate faces are refused")),
    }
}

/// Total area and the angle sum at every input vertex are those of `mesh`.
fn same_surface(tri: &IntrinsicTriangulation, mesh: &TriangleMesh) -> Result<(), TestCaseError> {
    let area = mesh.total_area();
    prop_assert!((tri.total_area() - area).abs() <= 1e-12 * area);
    let before = IntrinsicTriangulation::new(mesh)
        .expect("built once")
        .vertex_angle_sums();
    let after = tri.vertex_angle_sums();
    for v in 0..mesh.vertex_count() {
        prop_assert!(
            (after[v] - before[v]).abs() <= 1e-11,
            "vertex {}: {} vs {}",
            v,
            after[v],
            before[v]
        );
    }
    for &sum in &after[mesh.vertex_count()..] {
        prop_assert!((sum - PI).abs() <= 1e-11 || (sum - 2.0 * PI).abs() <= 1e-11);
    }
    Ok(())
}

proptest! {
    #[test]
    fn flipping_keeps_the_surface_and_makes_every_edge_delaunay((base, mesh) in mesh()) {
        let Some(mut tri) = intrinsic(&mesh) else { return Ok(()) };
        tri.flip_to_delaunay().unwrap();
        prop_assert_eq!(tri.check_invariants(), Ok(()), "{:?}", base);
        for e in 0..tri.edge_count() {
            if !tri.is_boundary_edge(e) {
                let (sum, scale) = tri.cotan_sum_and_scale(e);
                prop_assert!(sum >= -DELAUNAY_FLIP_TOLERANCE * scale, "{:?}: edge {} has {}", base, e, sum);
            }
        }
        same_surface(&tri, &mesh)?;
    }

    #[test]
    fn the_common_subdivision_tiles_both_and_maps_points_back((base, mesh) in mesh(), seed in any::<u64>()) {
        let Some(mut tri) = intrinsic(&mesh) else { return Ok(()) };
        tri.flip_to_delaunay().unwrap();
        let overlay = tri.common_subdivision(&mesh).unwrap();
        let total = mesh.total_area();
        let mut intrinsic_sums = vec![0.0; tri.face_count()];
        for i in 0..overlay.cell_count() {
            let cell = overlay.cell(i);
            prop_assert!(cell.area >= -1e-14 * total, "{:?}: cell {} has area {}", base, i, cell.area);
            intrinsic_sums[cell.intrinsic_face] += cell.area;
        }
        for f in 0..mesh.face_count() {
            let covered: f64 = overlay.input_face_overlaps(f).iter().map(|o| o.area).sum();
            prop_assert!((covered - mesh.face_area(f)).abs() <= 1e-12 * total, "{:?}: input face {}", base, f);
        }
        for (t, &sum) in intrinsic_sums.iter().enumerate() {
            prop_assert!((sum - tri.face_area(t)).abs() <= 1e-12 * total, "{:?}: intrinsic face {}", base, t);
        }
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        for _ in 0..50 {
            let face = rng.random_range(0..mesh.face_count());
            let (u, v): (f64, f64) = (rng.random(), rng.random());
            let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
            let point = TrianglePoint { face, barycentric: [1.0 - u - v, u, v] };
            let back = overlay.to_input(overlay.to_intrinsic(point).unwrap()).unwrap();
            prop_assert_eq!(back.face, face);
            for k in 0..3 {
                prop_assert!((back.barycentric[k] - point.barycentric[k]).abs() <= 1e-12, "{:?}: {:?} came back as {:?}", base, point, back);
            }
        }
    }

    #[test]
    fn refinement_leaves_every_edge_strictly_delaunay((base, mesh) in mesh()) {
        let Some(mut tri) = intrinsic(&mesh) else { return Ok(()) };
        tri.refine(&mesh, RefineOptions::default()).unwrap();
        prop_assert_eq!(tri.check_invariants(), Ok(()), "{:?}", base);
        for e in 0..tri.edge_count() {
            let (sum, scale) = tri.cotan_sum_and_scale(e);
            prop_assert!(sum > STRICT_DELAUNAY_MARGIN * scale, "{:?}: edge {} has {}", base, e, sum);
        }
        same_surface(&tri, &mesh)?;
        let overlay = tri.common_subdivision(&mesh).unwrap();
        let total = mesh.total_area();
        for f in 0..mesh.face_count() {
            let covered: f64 = overlay.input_face_overlaps(f).iter().map(|o| o.area).sum();
            prop_assert!((covered - mesh.face_area(f)).abs() <= 1e-12 * total, "{:?}: input face {}", base, f);
        }
    }
}

proptest! {
    /// Wild jitter (up to three local edge lengths) makes folded, needle and nearly flat faces:
    /// every step either succeeds with a consistent result or returns an error, never panics.
    #[test]
    fn wild_meshes_give_results_or_errors((base, mesh) in wild_mesh()) {
        let Some(mut tri) = intrinsic(&mesh) else { return Ok(()) };
        if tri.flip_to_delaunay().is_ok() {
            prop_assert_eq!(tri.check_invariants(), Ok(()), "{:?}", base);
            if let Ok(overlay) = tri.common_subdivision(&mesh) {
                let total = mesh.total_area();
                for f in 0..mesh.face_count() {
                    let covered: f64 = overlay.input_face_overlaps(f).iter().map(|o| o.area).sum();
                    prop_assert!((covered - mesh.face_area(f)).abs() <= 1e-9 * total, "{:?}: face {}", base, f);
                }
            }
        }
        let Some(mut tri) = intrinsic(&mesh) else { return Ok(()) };
        if tri.refine(&mesh, RefineOptions::default()).is_ok() {
            prop_assert_eq!(tri.check_invariants(), Ok(()), "{:?}", base);
            prop_assert!(tri.not_strictly_delaunay_edges().is_empty());
        }
    }
}

/// A base surface jittered by 0.5 to 3 local edge lengths.
fn wild_mesh() -> impl Strategy<Value = (Base, TriangleMesh)> {
    (base(), 0.5..3.0f64, any::<u64>()).prop_map(|(base, amplitude, seed)| {
        (
            base,
            jitter(&base.mesh(), amplitude, seed).expect("finite amplitude"),
        )
    })
}
