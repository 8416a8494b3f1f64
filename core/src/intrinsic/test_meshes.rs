//! Meshes for the intrinsic triangulation tests: generated ones made non-Delaunay by jitter,
//! stretching and slivers, with boundary, several components and a pinched vertex.

use crate::generate::{disk, genus_surface, hemisphere, icosphere, jitter, open_cylinder, torus};
use crate::TriangleMesh;

/// `mesh` with every position scaled by `factors` per axis (stretching makes thin, obtuse,
/// non-Delaunay triangles).
pub(crate) fn stretched(mesh: &TriangleMesh, factors: [f64; 3]) -> TriangleMesh {
    let positions = mesh
        .positions()
        .iter()
        .map(|p| std::array::from_fn(|k| p[k] * factors[k]))
        .collect();
    TriangleMesh::new(positions, mesh.faces().to_vec()).expect("stretching keeps a mesh valid")
}

/// The disjoint union of two meshes (the second's vertices renumbered after the first's).
pub(crate) fn union(a: &TriangleMesh, b: &TriangleMesh, offset: [f64; 3]) -> TriangleMesh {
    let mut positions = a.positions().to_vec();
    positions.extend(
        b.positions()
            .iter()
            .map(|p| std::array::from_fn(|k| p[k] + offset[k])),
    );
    let n = a.vertex_count();
    let mut faces = a.faces().to_vec();
    faces.extend(b.faces().iter().map(|f| f.map(|v| v + n)));
    TriangleMesh::new(positions, faces).expect("a union of meshes is a mesh")
}

/// Two jittered icospheres touching at one vertex (a vertex with two fans of faces): the
/// second is the first turned by 180° about the vertical line through its vertex of largest x.
pub(crate) fn pinched_spheres() -> TriangleMesh {
    let a = jitter(&icosphere(1), 0.35, 9).expect("finite amplitude");
    let pinch = (0..a.vertex_count())
        .max_by(|&u, &v| a.positions()[u][0].total_cmp(&a.positions()[v][0]))
        .unwrap_or(0);
    let [px, py, _] = a.positions()[pinch];
    let n = a.vertex_count();
    let mut positions = a.positions().to_vec();
    positions.extend(
        a.positions()
            .iter()
            .map(|p| [2.0 * px - p[0], 2.0 * py - p[1], p[2]]),
    );
    let renumber = |v: usize| if v == pinch { pinch } else { v + n };
    let mut faces = a.faces().to_vec();
    faces.extend(a.faces().iter().map(|f| f.map(renumber)));
    TriangleMesh::new(positions, faces).expect("two spheres sharing a vertex")
}

/// A set of non-Delaunay meshes covering the cases: closed genus 0, 1 and 2, open, several
/// components, slivers, a pinched vertex. `(name, mesh)`.
pub(crate) fn non_delaunay_meshes() -> Vec<(&'static str, TriangleMesh)> {
    let j = |m: &TriangleMesh, a: f64, seed: u64| jitter(m, a, seed).expect("finite amplitude");
    vec![
        ("jittered icosphere", j(&icosphere(2), 0.35, 1)),
        (
            "stretched icosphere",
            stretched(&icosphere(2), [4.0, 1.0, 0.5]),
        ),
        (
            "jittered torus",
            j(&torus(2.0, 0.6, 16, 9).expect("torus"), 0.3, 2),
        ),
        (
            "stretched genus 2",
            stretched(&genus_surface(2, 3), [1.0, 3.0, 1.0]),
        ),
        ("jittered disk", j(&disk(4), 0.3, 3)),
        (
            "stretched hemisphere",
            stretched(&hemisphere(4), [3.0, 1.0, 1.0]),
        ),
        (
            "thin open cylinder",
            stretched(&open_cylinder(12, 3, 1.0), [1.0, 1.0, 0.1]),
        ),
        (
            "two components",
            union(
                &j(&icosphere(1), 0.3, 4),
                &stretched(&disk(3), [2.0, 0.5, 1.0]),
                [3.0, 0.0, 0.0],
            ),
        ),
        ("pinched spheres", pinched_spheres()),
    ]
}

/// The unit square as an `n × n` grid of squares, each split by its diagonal from lower left to
/// upper right: every diagonal is cocircular (`⋆1 = 0`) and every boundary triangle has a right
/// angle.
pub(crate) fn square_grid(n: usize) -> TriangleMesh {
    let index = |i: usize, j: usize| i * (n + 1) + j;
    let positions = (0..=n)
        .flat_map(|i| (0..=n).map(move |j| [j as f64 / n as f64, i as f64 / n as f64, 0.0]))
        .collect();
    let mut faces = Vec::new();
    for i in 0..n {
        for j in 0..n {
            faces.push([index(i, j), index(i, j + 1), index(i + 1, j + 1)]);
            faces.push([index(i, j), index(i + 1, j + 1), index(i + 1, j)]);
        }
    }
    TriangleMesh::new(positions, faces).expect("a grid is a mesh")
}

/// One obtuse triangle (120° at corner 2): its longest side is a boundary edge no flip can fix.
pub(crate) fn obtuse_triangle() -> TriangleMesh {
    let h = 0.5 / 3f64.sqrt();
    TriangleMesh::new(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, h, 0.0]],
        vec![[0, 1, 2]],
    )
    .expect("a triangle is a mesh")
}
