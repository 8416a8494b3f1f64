//! The meshes of the accuracy checks ([`crate::accuracy`]): a closed box whose six faces are
//! flat patches (jittered inside each face, so the patches are irregular but planar), and the
//! refinement sequences of the unit sphere and the unit hemisphere, regular and jittered, as
//! triangle meshes and (for entries that accept polygons) as quad meshes.
//!
//! Jittered sequences move every vertex by up to [`JITTER`] of its shortest edge (a new seed per
//! level) and put it back on the surface (hemisphere: equator vertices stay on the equator);
//! triangle meshes are then made Delaunay by edge flips, so that entries that need Delaunay
//! meshes run on them too. The meshes are inscribed: their own geometric error is `O(h²)` and
//! part of what the convergence checks measure.

use crate::corpus::{delaunay_flips, try_delaunay_flips};
use crate::polygon_operations::jittered;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::HashMap;
use tvf_core::generate::{cube_sphere, hemisphere, icosphere};
use tvf_core::geometry::{cross, dot, norm, scale, sub};
use tvf_core::mesh::FaceList;
use tvf_core::{SurfaceMesh, TriangleMesh};

/// Largest vertex move of the jittered sequences, in units of the vertex's shortest edge.
pub const JITTER: f64 = 0.3;

/// Quads along each edge of the cube of [`flat_box`].
pub const BOX_CELLS: usize = 10;

/// Refinement levels of the convergence sequences: icospheres 1–3 (80, 320, 1280 faces), ring
/// hemispheres of 4, 8, 16 rings (96, 384, 1536 faces), cube-spheres of 4, 8, 16 quads per cube
/// edge (96, 384, 1536 quads).
pub const LEVELS: [u32; 3] = [1, 2, 3];

/// A surface of a convergence sequence: its exact Hodge–Laplacian spectrum is known.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sequence {
    /// The unit sphere, triangles (icospheres); jittered if `true`.
    Sphere(bool),
    /// The upper unit hemisphere, triangles (ring meshes); jittered if `true`.
    Hemisphere(bool),
    /// The unit sphere, quads (cube-spheres); jittered (non-planar quads) if `true`.
    QuadSphere(bool),
}

impl Sequence {
    /// The triangle sequences: sphere and hemisphere, regular and jittered.
    pub const TRIANGLES: [Sequence; 4] = [
        Sequence::Sphere(false),
        Sequence::Sphere(true),
        Sequence::Hemisphere(false),
        Sequence::Hemisphere(true),
    ];

    /// The quad sequences: the quad sphere, regular and jittered.
    pub const QUADS: [Sequence; 2] = [Sequence::QuadSphere(false), Sequence::QuadSphere(true)];

    /// `sphere`, `jittered sphere`, `hemisphere`, `jittered hemisphere`, `quad sphere`,
    /// `jittered quad sphere`.
    pub fn name(self) -> &'static str {
        match self {
            Sequence::Sphere(false) => "sphere",
            Sequence::Sphere(true) => "jittered sphere",
            Sequence::Hemisphere(false) => "hemisphere",
            Sequence::Hemisphere(true) => "jittered hemisphere",
            Sequence::QuadSphere(false) => "quad sphere",
            Sequence::QuadSphere(true) => "jittered quad sphere",
        }
    }

    /// Whether the surface has a boundary (the hemisphere).
    pub fn has_boundary(self) -> bool {
        matches!(self, Sequence::Hemisphere(_))
    }

    /// The mesh of refinement `level`, or why it could not be made.
    pub fn mesh(self, level: u32) -> Result<SurfaceMesh, String> {
        let seed = 41 + u64::from(level);
        match self {
            Sequence::Sphere(jitter) => {
                let mesh = icosphere(level);
                if jitter {
                    on_surface(&mesh.into(), seed, false)
                } else {
                    Ok(mesh.into())
                }
            }
            Sequence::Hemisphere(jitter) => {
                let mesh = hemisphere(2 << level);
                if jitter {
                    on_surface(&mesh.into(), seed, true)
                } else {
                    Ok(try_delaunay_flips(&mesh)?.into())
                }
            }
            Sequence::QuadSphere(jitter) => {
                let mesh: SurfaceMesh = cube_sphere(2 << level)
                    .ok_or("cube-sphere of fewer than two quads per edge")?
                    .into();
                if jitter {
                    on_surface(&mesh, seed, false)
                } else {
                    Ok(mesh)
                }
            }
        }
    }
}

/// `mesh` jittered by [`JITTER`] and put back on the unit sphere (on the hemisphere, a vertex
/// of the equator back onto the equator); a triangle mesh made Delaunay by flips.
fn on_surface(mesh: &SurfaceMesh, seed: u64, equator: bool) -> Result<SurfaceMesh, String> {
    let original = mesh.positions();
    let moved = jittered(mesh, JITTER, seed)?;
    let positions: Vec<[f64; 3]> = moved
        .positions()
        .iter()
        .zip(original)
        .map(|(&p, &o)| {
            let p = if equator && o[2].abs() < 1e-12 {
                [p[0], p[1], 0.0]
            } else if equator {
                [p[0], p[1], p[2].abs()]
            } else {
                p
            };
            scale(p, 1.0 / norm(p))
        })
        .collect();
    let projected = SurfaceMesh::new(positions, mesh.to_face_list()).map_err(|e| e.to_string())?;
    match projected.as_triangles() {
        Some(triangles) => Ok(try_delaunay_flips(triangles)?.into()),
        None => Ok(projected),
    }
}

/// The closed box `[−1, 1]³` with every cube face an `n × n` grid (`n` = [`BOX_CELLS`]) of
/// planar quads (`quads`) or of triangles (each quad split along alternating diagonals), the
/// grid vertices strictly inside a cube face moved within that face by up to [`JITTER`] of the
/// grid spacing, triangles made Delaunay by flips: six flat, irregular patches joined along the
/// cube's edges.
pub fn flat_box(quads: bool, seed: u64) -> SurfaceMesh {
    let n = BOX_CELLS;
    let spacing = 2.0 / n as f64;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut index: HashMap<[usize; 3], usize> = HashMap::new();
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut faces = FaceList::new();
    for axis in 0..3 {
        for side in [0, n] {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let mut vertex = |i: usize, j: usize| {
                let mut key = [0; 3];
                key[axis] = side;
                key[u] = i;
                key[v] = j;
                *index.entry(key).or_insert_with(|| {
                    let mut p = key.map(|k| -1.0 + spacing * k as f64);
                    if (1..n).contains(&i) && (1..n).contains(&j) {
                        p[u] += JITTER * spacing * rng.random_range(-1.0..1.0);
                        p[v] += JITTER * spacing * rng.random_range(-1.0..1.0);
                    }
                    positions.push(p);
                    positions.len() - 1
                })
            };
            let mut cells = Vec::new();
            for i in 0..n {
                for j in 0..n {
                    cells.push([
                        vertex(i, j),
                        vertex(i + 1, j),
                        vertex(i + 1, j + 1),
                        vertex(i, j + 1),
                    ]);
                }
            }
            let outward = if side == n { 1.0 } else { -1.0 };
            for (k, mut cell) in cells.into_iter().enumerate() {
                let [a, b, _, d] = cell.map(|c| positions[c]);
                if dot(cross(sub(b, a), sub(d, a)), unit(axis)) * outward < 0.0 {
                    cell.reverse();
                }
                if quads {
                    faces.push(&cell);
                } else if k % 2 == 0 {
                    faces.push(&[cell[0], cell[1], cell[2]]);
                    faces.push(&[cell[0], cell[2], cell[3]]);
                } else {
                    faces.push(&[cell[0], cell[1], cell[3]]);
                    faces.push(&[cell[1], cell[2], cell[3]]);
                }
            }
        }
    }
    let mesh = SurfaceMesh::new(positions, faces).expect("the jittered box is a valid closed mesh");
    // Delaunay by flips, so that entries needing Delaunay meshes build on it; a flip changes
    // the surface only at the cube's edges (a diagonal inside a planar face stays in the face).
    match mesh.as_triangles() {
        Some(triangles) => delaunay_flips(triangles).into(),
        None => mesh,
    }
}

/// The unit vector along coordinate `axis`.
fn unit(axis: usize) -> [f64; 3] {
    let mut e = [0.0; 3];
    e[axis] = 1.0;
    e
}

/// Whether `point` lies inside one face of the box of [`flat_box`], at least `margin` from the
/// cube's edges: on a flat patch, with every node within `margin` of it on that patch too.
pub fn deep_inside_a_box_face(point: [f64; 3], margin: f64) -> bool {
    let on_face = point
        .iter()
        .filter(|x| (x.abs() - 1.0).abs() < 1e-12)
        .count();
    let inner = point.iter().filter(|x| x.abs() <= 1.0 - margin).count();
    on_face == 1 && inner == 2
}

/// The unit icosphere of level 2 (320 faces) jittered by [`JITTER`] and put back on the sphere,
/// made Delaunay by flips: a curved patch without boundary.
pub fn curved_sphere() -> TriangleMesh {
    let mesh = on_surface(&icosphere(2).into(), 7, false).expect("the jittered icosphere is valid");
    mesh.into_triangles()
        .unwrap_or_else(|_| unreachable!("an icosphere has triangles"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_box_is_closed_and_flat_inside_its_faces() {
        for quads in [false, true] {
            let mesh = flat_box(quads, 3);
            assert!(mesh.is_closed());
            let area = mesh.total_area();
            assert!((area - 24.0).abs() < 1e-10, "area {area}");
            let deep = mesh
                .positions()
                .iter()
                .filter(|&&p| deep_inside_a_box_face(p, 0.5))
                .count();
            assert!(deep >= 6 * 16, "{deep} deep vertices");
        }
    }

    #[test]
    fn sequences_refine_and_stay_on_the_surface() {
        for sequence in Sequence::TRIANGLES.into_iter().chain(Sequence::QUADS) {
            let counts: Vec<usize> = LEVELS
                .iter()
                .map(|&l| sequence.mesh(l).unwrap().face_count())
                .collect();
            assert!(counts[0] < counts[1] && counts[1] < counts[2], "{counts:?}");
            let mesh = sequence.mesh(2).unwrap();
            for p in mesh.positions() {
                assert!((norm(*p) - 1.0).abs() < 1e-12);
            }
            assert_eq!(mesh.is_closed(), !sequence.has_boundary());
        }
    }
}
