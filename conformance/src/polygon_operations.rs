//! Operations that make the polygon meshes of the polygon corpus and strategies out of generated
//! ones: the quad split of any mesh ([`quad_split`]: a genus-`g` quad surface from a genus-`g`
//! triangle surface), holes ([`without_faces`]), seeded vertex jitter that makes polygons
//! non-planar ([`jittered`]), rigid motions ([`moved`]) and disjoint unions ([`beside`]). Every
//! result is re-validated ([`SurfaceMesh::validated`]: no repeated corner, manifold, oriented,
//! no zero vector area, no fold), so a draw that breaks a polygon is an error, not a bad mesh.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::generate::rigidly_moved;
use tvf_core::geometry::{add, norm, scale, sub};
use tvf_core::mesh::{FaceList, Mesh};
use tvf_core::SurfaceMesh;

/// `positions` and `faces` validated into a mesh, the error worded with `what` made it.
fn validated(what: &str, positions: Vec<[f64; 3]>, faces: FaceList) -> Result<SurfaceMesh, String> {
    SurfaceMesh::validated(positions, faces)
        .map(|(mesh, _)| mesh)
        .map_err(|e| format!("{what}: {e}"))
}

/// The quad split of `mesh`: every face of `n` corners becomes `n` quads `(p_c, m_c, o, m_{c−1})`
/// joining corner `c`, the midpoint `m_c` of its side to corner `c + 1`, the face's corner
/// average `o` and the midpoint of the side from corner `c − 1` (`V + E + F` vertices, `Σ n_f`
/// faces; same orientation, genus, components and boundary loops). The quads of a planar face
/// are planar; those of a non-planar polygon are not.
pub fn quad_split<M: Mesh + ?Sized>(mesh: &M) -> Result<SurfaceMesh, String> {
    let (v, e) = (mesh.vertex_count(), mesh.edge_count());
    let p = mesh.positions();
    let mut positions = p.to_vec();
    positions.extend(
        mesh.topology()
            .edges()
            .iter()
            .map(|&[a, b]| scale(add(p[a], p[b]), 0.5)),
    );
    let faces = mesh.face_corners();
    let mut quads = FaceList::new();
    for f in 0..faces.face_count() {
        let corners = faces.corners(f);
        let n = corners.len();
        let centre = corners
            .iter()
            .fold([0.0; 3], |sum, &c| add(sum, scale(p[c], 1.0 / n as f64)));
        positions.push(centre);
        let o = v + e + f;
        for (c, &corner) in corners.iter().enumerate() {
            let next_side = v + mesh.face_edge(f, c);
            let previous_side = v + mesh.face_edge(f, (c + n - 1) % n);
            quads.push(&[corner, next_side, o, previous_side]);
        }
    }
    validated("quad split", positions, quads)
}

/// `mesh` without the faces `removed` (holes; vertices no face uses any more are dropped).
pub fn without_faces(mesh: &SurfaceMesh, removed: &[usize]) -> Result<SurfaceMesh, String> {
    let mut faces = FaceList::new();
    for f in (0..mesh.face_count()).filter(|f| !removed.contains(f)) {
        faces.push(mesh.face(f));
    }
    validated("removing faces", mesh.positions().to_vec(), faces)
}

/// Every vertex moved by a random vector uniform in the ball of radius `amplitude ×` its
/// shortest edge (ChaCha8 seeded by `seed`, the same mesh on every machine): planar polygons
/// become non-planar. Fails when a polygon folds or degenerates (re-validated).
pub fn jittered(mesh: &SurfaceMesh, amplitude: f64, seed: u64) -> Result<SurfaceMesh, String> {
    let p = mesh.positions();
    let mut shortest = vec![f64::INFINITY; p.len()];
    for &[a, b] in mesh.edges() {
        let length = norm(sub(p[a], p[b]));
        shortest[a] = shortest[a].min(length);
        shortest[b] = shortest[b].min(length);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let positions = p
        .iter()
        .zip(&shortest)
        .map(|(&x, &local)| {
            let offset = loop {
                let d: [f64; 3] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
                if norm(d) <= 1.0 {
                    break d;
                }
            };
            add(x, scale(offset, amplitude * local))
        })
        .collect();
    validated("jitter", positions, mesh.to_face_list())
}

/// `mesh` rotated by `angle` radians about `axis` (through the origin; a zero axis is no
/// rotation), then translated by `translation`.
pub fn moved(
    mesh: &SurfaceMesh,
    axis: [f64; 3],
    angle: f64,
    translation: [f64; 3],
) -> Result<SurfaceMesh, String> {
    let positions = rigidly_moved(mesh.positions(), axis, angle, translation);
    validated("rigid motion", positions, mesh.to_face_list())
}

/// The disjoint union of `first` and `second`, `second` translated along x to start 1 beyond
/// the end of `first`.
pub fn beside(first: &SurfaceMesh, second: &SurfaceMesh) -> Result<SurfaceMesh, String> {
    let end = first
        .positions()
        .iter()
        .fold(f64::NEG_INFINITY, |m, p| m.max(p[0]));
    let start = second
        .positions()
        .iter()
        .fold(f64::INFINITY, |m, p| m.min(p[0]));
    let shift = [end + 1.0 - start, 0.0, 0.0];
    let offset = first.vertex_count();
    let mut positions = first.positions().to_vec();
    positions.extend(second.positions().iter().map(|&p| add(p, shift)));
    let mut faces = first.to_face_list();
    for f in 0..second.face_count() {
        let corners: Vec<usize> = second.face(f).iter().map(|&c| c + offset).collect();
        faces.push(&corners);
    }
    validated("disjoint union", positions, faces)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::generate::genus_surface;

    #[test]
    fn the_quad_split_of_a_genus_2_surface_is_a_genus_2_quad_mesh() {
        let triangles = genus_surface(2, 2);
        let quads = quad_split(&triangles).unwrap();
        assert_eq!(quads.face_count(), 3 * triangles.face_count());
        assert_eq!(quads.genus(), 2);
        assert!(quads.is_closed() && !quads.is_triangle_mesh());
        let area = quads.total_area();
        assert!((area - triangles.total_area()).abs() < 1e-12 * area);
        let holed = without_faces(&quads, &[0]).unwrap();
        assert_eq!(holed.boundary_loops().len(), 1);
        let two = beside(&quads, &jittered(&holed, 0.1, 3).unwrap()).unwrap();
        assert_eq!(two.component_count(), 2);
    }
}
