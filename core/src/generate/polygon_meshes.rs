//! Polygon meshes generated in code: a quad torus, the cube-sphere (quads on the unit sphere,
//! refinable), and the dual of a triangle mesh (non-planar polygons of every valence).

use super::torus::torus_grid;
use crate::geometry::{add, normalize, scale};
use crate::mesh::{FaceList, NO_FACE};
use crate::{PolygonMesh, TriangleMesh};
use std::collections::HashMap;

/// A torus of revolution made of quads: major radius `major`, tube radius `minor`, `around ×
/// tube` quads (genus 1, outward normals; each quad is planar). `None` unless
/// `0 < minor < major` and both resolutions are at least 3.
pub fn quad_torus(major: f64, minor: f64, around: usize, tube: usize) -> Option<PolygonMesh> {
    let valid = minor > 0.0 && minor < major && around >= 3 && tube >= 3 && major.is_finite();
    if !valid {
        return None;
    }
    let (positions, quads) = torus_grid(major, around, tube, |_, _| minor);
    PolygonMesh::new(positions, FaceList::from_polygons(&quads)).ok()
}

/// The cube-sphere: each face of the cube `[−1, 1]³` cut into `n × n` quads, every vertex
/// projected onto the unit sphere (`6n²` quads, genus 0, outward normals, non-planar quads).
/// Refining `n` refines the quads regularly. `None` for `n = 0`.
pub fn cube_sphere(n: usize) -> Option<PolygonMesh> {
    if n == 0 {
        return None;
    }
    // Vertices are keyed by their integer cube coordinates in 0..=n, so the faces share them.
    let mut index: HashMap<[usize; 3], usize> = HashMap::new();
    let mut positions = Vec::new();
    let mut vertex = |key: [usize; 3]| -> usize {
        *index.entry(key).or_insert_with(|| {
            let p = key.map(|k| 2.0 * k as f64 / n as f64 - 1.0);
            positions.push(normalize(p));
            positions.len() - 1
        })
    };
    let mut faces = FaceList::new();
    // For each cube face: the fixed axis, its side (0 or n), and the two running axes ordered so
    // that (u, v, outward normal) is right-handed.
    for axis in 0..3 {
        for side in [0, n] {
            let (mut u, mut v) = ((axis + 1) % 3, (axis + 2) % 3);
            if side == 0 {
                std::mem::swap(&mut u, &mut v);
            }
            for i in 0..n {
                for j in 0..n {
                    let corner = |di: usize, dj: usize| {
                        let mut key = [0; 3];
                        key[axis] = side;
                        key[u] = i + di;
                        key[v] = j + dj;
                        key
                    };
                    let quad =
                        [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)].map(&mut vertex);
                    faces.push(&quad);
                }
            }
        }
    }
    PolygonMesh::new(positions, faces).ok()
}

/// The dual of a triangle mesh: one vertex per triangle (its centroid), one polygon per vertex
/// of `mesh` that is not on the boundary, its corners the centroids of the triangles around it
/// in counter-clockwise order. Vertices of valence `k` give `k`-gons, non-planar on a curved
/// mesh. On a closed mesh the dual has the same genus; on a mesh with boundary the boundary
/// vertices have no polygon, so the dual is smaller and open. `None` if no vertex is interior
/// or the dual is not a valid mesh.
pub fn dual(mesh: &TriangleMesh) -> Option<PolygonMesh> {
    let positions: Vec<[f64; 3]> = (0..mesh.face_count())
        .map(|t| {
            let [a, b, c] = mesh.faces()[t].map(|v| mesh.positions()[v]);
            scale(add(add(a, b), c), 1.0 / 3.0)
        })
        .collect();
    // The face after `t` going counter-clockwise around vertex `v`: across the edge of `t` from
    // `v` to its predecessor in `t`.
    let next_around = |t: usize, v: usize| -> usize {
        let face = mesh.faces()[t];
        let c = face.iter().position(|&w| w == v).unwrap_or(0);
        // The edge {v, face[c + 2]} is opposite corner c + 1.
        let e = mesh.face_edges()[t][(c + 1) % 3];
        let [left, right] = mesh.edge_faces()[e];
        if left == t {
            right
        } else {
            left
        }
    };
    let mut first_face = vec![NO_FACE; mesh.vertex_count()];
    for (t, face) in mesh.faces().iter().enumerate() {
        for &v in face {
            if first_face[v] == NO_FACE {
                first_face[v] = t;
            }
        }
    }
    let mut on_boundary = vec![false; mesh.vertex_count()];
    for e in mesh.boundary_edges() {
        for v in mesh.edges()[e] {
            on_boundary[v] = true;
        }
    }
    let mut faces = FaceList::new();
    for v in 0..mesh.vertex_count() {
        if on_boundary[v] || first_face[v] == NO_FACE {
            continue;
        }
        let mut ring = vec![first_face[v]];
        loop {
            let t = next_around(*ring.last()?, v);
            if t == ring[0] {
                break;
            }
            if t == NO_FACE || ring.len() > mesh.face_count() {
                return None;
            }
            ring.push(t);
        }
        faces.push(&ring);
    }
    if faces.is_empty() {
        return None;
    }
    PolygonMesh::new(positions, faces).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::icosphere;
    use crate::SurfaceMesh;

    #[test]
    fn generated_polygon_meshes_are_valid_closed_and_of_the_right_genus() {
        let torus = quad_torus(1.0, 0.4, 12, 8).unwrap();
        assert_eq!(torus.face_count(), 96);
        let sphere = cube_sphere(3).unwrap();
        assert_eq!((sphere.face_count(), sphere.vertex_count()), (54, 56));
        let dual = dual(&icosphere(2)).unwrap();
        assert_eq!(dual.face_count(), icosphere(2).vertex_count());
        for (mesh, genus) in [(torus, 1), (sphere, 0), (dual, 0)] {
            let faces = mesh.faces().clone();
            let (valid, _) = SurfaceMesh::validated(mesh.positions().to_vec(), faces).unwrap();
            assert!(valid.is_closed());
            assert_eq!(valid.genus(), genus);
            assert!(!valid.is_triangle_mesh());
            // Outward normals: the vector areas point away from the centre on average.
            let outward: f64 = (0..valid.face_count())
                .map(|f| crate::geometry::dot(valid.face_centroid(f), valid.vector_area(f)))
                .sum();
            assert!(outward > 0.0);
        }
    }
}
