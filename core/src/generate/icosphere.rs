//! The unit icosphere: a subdivided icosahedron projected onto the unit sphere.

use crate::geometry::normalize;
use crate::TriangleMesh;
use std::collections::HashMap;

/// Unit icosphere after `level` 1-to-4 subdivisions: `20·4^level` faces, genus 0, outward normals.
///
/// Level 0 has 12 vertices; level 2 has 320 faces (the mesh of the spectrum facts in `docs/conventions.md`).
pub fn icosphere(level: u32) -> TriangleMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut positions: Vec<[f64; 3]> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .into_iter()
    .map(normalize)
    .collect();
    let mut faces: Vec<[usize; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..level {
        let mut midpoint: HashMap<(usize, usize), usize> = HashMap::new();
        let mut split = |a: usize, b: usize, positions: &mut Vec<[f64; 3]>| -> usize {
            *midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (positions[a], positions[b]);
                positions.push(normalize([p[0] + q[0], p[1] + q[1], p[2] + q[2]]));
                positions.len() - 1
            })
        };
        let mut refined = Vec::with_capacity(4 * faces.len());
        for [a, b, c] in faces {
            let ab = split(a, b, &mut positions);
            let bc = split(b, c, &mut positions);
            let ca = split(c, a, &mut positions);
            refined.extend_from_slice(&[[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = refined;
    }
    TriangleMesh::new(positions, faces).expect("the icosphere construction is a valid closed mesh")
}
