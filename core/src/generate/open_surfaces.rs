//! Meshes with boundary: disk, hemisphere, open cylinder, perforated plate (annulus, pair of
//! pants), torus with a hole.

use super::genus_surface::perforated_plate_sheet;
use super::staggered_ring_faces;
use crate::TriangleMesh;
use std::f64::consts::{FRAC_PI_2, TAU};

/// The ring triangulation of the unit disk in polar coordinates: a centre vertex and `rings`
/// rings, ring `i` (radius `i / rings`) with `6i` vertices at equal angles; consecutive rings are
/// stitched by angle. Returns `(radius, angle)` per vertex and counter-clockwise triangles
/// (`6·rings²` of them).
fn polar_rings(rings: usize) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    let rings = rings.max(1);
    let mut points = vec![[0.0, 0.0]];
    let mut starts = vec![0usize];
    for i in 1..=rings {
        starts.push(points.len());
        let count = 6 * i;
        points.extend((0..count).map(|j| [i as f64 / rings as f64, TAU * j as f64 / count as f64]));
    }
    let mut triangles = Vec::with_capacity(6 * rings * rings);
    for i in 1..=rings {
        let (inner_count, outer_count) = (if i == 1 { 1 } else { 6 * (i - 1) }, 6 * i);
        let inner = |j: usize| starts[i - 1] + j % inner_count;
        let outer = |j: usize| starts[i] + j % outer_count;
        // Walk both rings by angle (fractions of a turn), adding one triangle per step.
        let (mut a, mut b) = (0usize, 0usize);
        while a < inner_count || b < outer_count {
            let next_inner = if i == 1 {
                f64::INFINITY
            } else {
                (a + 1) as f64 / inner_count as f64
            };
            let next_outer = (b + 1) as f64 / outer_count as f64;
            if b < outer_count && (next_outer <= next_inner || a >= inner_count) {
                triangles.push([inner(a), outer(b), outer(b + 1)]);
                b += 1;
            } else {
                triangles.push([inner(a), outer(b), inner(a + 1)]);
                a += 1;
            }
            if i == 1 && b == outer_count {
                break;
            }
        }
    }
    (points, triangles)
}

/// The unit disk in the plane `z = 0` (normal +z): a centre vertex and `rings` rings of `6i`
/// vertices, `6·rings²` faces, one boundary loop (the unit circle, `6·rings` edges).
pub fn disk(rings: usize) -> TriangleMesh {
    let (points, faces) = polar_rings(rings);
    let positions = points
        .iter()
        .map(|&[r, a]| [r * a.cos(), r * a.sin(), 0.0])
        .collect();
    TriangleMesh::new(positions, faces).expect("the ring disk is a valid mesh")
}

/// The upper unit hemisphere `z ≥ 0` (outward normals): the ring disk of [`disk`] with radius `r`
/// mapped to the polar angle `θ = r·π/2`; one boundary loop (the equator), `6·rings²` faces.
pub fn hemisphere(rings: usize) -> TriangleMesh {
    let (points, faces) = polar_rings(rings);
    let positions = points
        .iter()
        .map(|&[r, a]| {
            let theta = r * FRAC_PI_2;
            [theta.sin() * a.cos(), theta.sin() * a.sin(), theta.cos()]
        })
        .collect();
    TriangleMesh::new(positions, faces).expect("the ring hemisphere is a valid mesh")
}

/// An open cylinder (annulus) `x² + y² = 1`, `0 ≤ z ≤ height`, outward normals: `around ≥ 3`
/// vertices per ring, `layers ≥ 1` layers of quads, every other ring shifted by half a cell so
/// the triangles are near-isosceles. Two boundary loops; `2·around·layers` faces.
pub fn open_cylinder(around: usize, layers: usize, height: f64) -> TriangleMesh {
    let (around, layers) = (around.max(3), layers.max(1));
    let positions = (0..=layers)
        .flat_map(|ring| {
            let shift = 0.5 * (ring % 2) as f64;
            (0..around).map(move |i| {
                let u = TAU * (i as f64 + shift) / around as f64;
                [u.cos(), u.sin(), height * ring as f64 / layers as f64]
            })
        })
        .collect();
    let faces = staggered_ring_faces(around, layers, layers + 1);
    TriangleMesh::new(positions, faces).expect("the open cylinder is a valid mesh")
}

/// A flat plate in `z = 0` (normal +z) of `holes ≥ 1` square cells of side 2 in a row, each
/// with a round hole of radius 0.75 (the sheet of [`super::genus_surface`]): genus 0 with
/// `holes + 1` boundary loops — an annulus for one hole, a pair of pants for two. `resolution`
/// is the number of segments along each cell side (rounded up to even, at least 2).
pub fn perforated_plate(holes: usize, resolution: usize) -> TriangleMesh {
    let (points, faces) = perforated_plate_sheet(holes.max(1), resolution);
    let positions = points.iter().map(|p| [p[0], p[1], 0.0]).collect();
    TriangleMesh::new(positions, faces).expect("the perforated plate is a valid mesh")
}

/// A torus of revolution (as [`super::torus`]) with the two faces of one grid cell removed: genus
/// 1, one boundary loop of four edges. `None` for invalid torus parameters.
pub fn holed_torus(major: f64, minor: f64, around: usize, tube: usize) -> Option<TriangleMesh> {
    let closed = super::torus(major, minor, around, tube)?;
    let faces = closed.faces()[2..].to_vec();
    TriangleMesh::new(closed.positions().to_vec(), faces).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn loops(mesh: &TriangleMesh) -> usize {
        mesh.boundary_loops().len()
    }

    #[test]
    fn open_surfaces_have_their_boundary_loops_and_genus() {
        let d = disk(4);
        assert_eq!(
            (d.face_count(), loops(&d), d.euler_characteristic()),
            (96, 1, 1)
        );
        let h = hemisphere(4);
        assert_eq!((loops(&h), h.genus()), (1, 0));
        assert!(h.positions().iter().all(|p| p[2] >= -1e-15));
        let c = open_cylinder(12, 4, 1.0);
        assert_eq!((loops(&c), c.euler_characteristic()), (2, 0));
        let pants = perforated_plate(2, 4);
        assert_eq!((loops(&pants), pants.genus()), (3, 0));
        let t = holed_torus(1.0, 0.4, 12, 6).unwrap();
        assert_eq!((loops(&t), t.genus()), (1, 1));
        // Outward orientation: the hemisphere's normals point away from the origin.
        for t in 0..h.face_count() {
            let n = h.face_normal(t);
            let p = h.corner(t, 0);
            assert!(n[0] * p[0] + n[1] * p[1] + n[2] * p[2] > 0.0);
        }
        assert!((0..d.face_count()).all(|t| d.face_normal(t)[2] > 0.0));
    }
}
