//! Full validation of positions and faces: every check [`TriangleMesh::new`] makes, plus vertex
//! manifoldness, orientability, zero-area faces, unreferenced and duplicate vertices.
//!
//! [`TriangleMesh::new`] stays cheap and only guarantees what the topology tables need.
//! [`TriangleMesh::validated`] is the entry point for data from outside (files, user input);
//! every reader in [`crate::io`] goes through it.

use super::error::MeshError;
use super::triangle_mesh::TriangleMesh;
use super::validation_report::{ValidationReport, ValidationWarning, SMALL_ANGLE_DEG};
use crate::geometry::{cross, dot, norm, sub};
use std::collections::HashMap;

/// A face whose `|(p1−p0)×(p2−p0)|` is at most this times its longest squared edge length is
/// reported as zero-area: collinear or coincident corners up to rounding (a 1e-12° angle).
const ZERO_AREA_RELATIVE: f64 = 64.0 * f64::EPSILON;

impl TriangleMesh {
    /// Validates `positions` and `faces` (0-based, counter-clockwise) and builds the mesh.
    ///
    /// Errors, checked in this order: [`MeshError::NoFaces`], [`MeshError::NonFiniteCoordinate`],
    /// [`MeshError::IndexOutOfRange`], [`MeshError::RepeatedVertexInFace`],
    /// [`MeshError::NonManifoldEdge`], [`MeshError::NonManifoldVertex`],
    /// [`MeshError::NonOrientable`], [`MeshError::InconsistentOrientation`],
    /// [`MeshError::ZeroAreaFace`]. All indices in errors are input indices.
    ///
    /// Unreferenced vertices are dropped (the others keep their order; see
    /// [`ValidationReport::original_vertex`]); they, exact duplicate positions, inward normals
    /// of a closed mesh and sliver faces are reported as warnings.
    pub fn validated(
        positions: Vec<[f64; 3]>,
        faces: Vec<[usize; 3]>,
    ) -> Result<(TriangleMesh, ValidationReport), MeshError> {
        check_faces(&positions, &faces)?;
        let input_vertex_count = positions.len();
        let mut warnings = Vec::new();

        let mut referenced = vec![false; positions.len()];
        for face in &faces {
            for &v in face {
                referenced[v] = true;
            }
        }
        if let Some(first) = referenced.iter().position(|&r| !r) {
            let count = referenced.iter().filter(|&&r| !r).count();
            warnings.push(ValidationWarning::UnreferencedVertices { count, first });
        }
        if let Some(warning) = duplicate_vertices(&positions, &referenced) {
            warnings.push(warning);
        }

        let mut new_index = vec![usize::MAX; positions.len()];
        let mut original_vertex = Vec::with_capacity(positions.len());
        let mut kept_positions = Vec::with_capacity(positions.len());
        for (v, p) in positions.into_iter().enumerate() {
            if referenced[v] {
                new_index[v] = original_vertex.len();
                original_vertex.push(v);
                kept_positions.push(p);
            }
        }
        let faces = faces.into_iter().map(|f| f.map(|v| new_index[v])).collect();
        let mesh = TriangleMesh::new(kept_positions, faces)?;

        if let Some(warning) = inward_components(&mesh) {
            warnings.push(warning);
        }
        let (min_angle_deg, max_angle_deg) = mesh.angle_range_deg();
        let small = (0..mesh.face_count())
            .filter(|&t| {
                mesh.corner_angles(t)
                    .iter()
                    .any(|a| a.to_degrees() < SMALL_ANGLE_DEG)
            })
            .count();
        if small > 0 {
            warnings.push(ValidationWarning::SmallAngles { faces: small });
        }
        let report = ValidationReport {
            warnings,
            original_vertex,
            input_vertex_count,
            min_angle_deg,
            max_angle_deg,
        };
        Ok((mesh, report))
    }
}

/// The closed components of `mesh` whose signed volume is negative (normals inward), if any.
fn inward_components(mesh: &TriangleMesh) -> Option<ValidationWarning> {
    let count = mesh.component_count();
    let mut volume = vec![0.0; count];
    let mut first_face = vec![usize::MAX; count];
    for (t, (face, &c)) in mesh.faces().iter().zip(mesh.face_components()).enumerate() {
        let [p0, p1, p2] = face.map(|v| mesh.positions()[v]);
        volume[c] += dot(p0, cross(p1, p2)) / 6.0;
        first_face[c] = first_face[c].min(t);
    }
    let mut open = vec![false; count];
    let vertex_component = mesh.vertex_components();
    for boundary in mesh.boundary_loops() {
        for v in boundary {
            open[vertex_component[v]] = true;
        }
    }
    let inward: Vec<usize> = (0..count)
        .filter(|&c| !open[c] && volume[c] < 0.0)
        .collect();
    let &first = inward.first()?;
    Some(ValidationWarning::InwardNormals {
        components: inward.len(),
        first_component: first,
        first_face: first_face[first],
        signed_volume: volume[first],
    })
}

/// Every error check of [`TriangleMesh::validated`], without building anything.
pub fn check_faces(positions: &[[f64; 3]], faces: &[[usize; 3]]) -> Result<(), MeshError> {
    if faces.is_empty() {
        return Err(MeshError::NoFaces);
    }
    if let Some(vertex) = positions
        .iter()
        .position(|p| p.iter().any(|x| !x.is_finite()))
    {
        return Err(MeshError::NonFiniteCoordinate { vertex });
    }
    for (face, f) in faces.iter().enumerate() {
        for (c, &index) in f.iter().enumerate() {
            if index >= positions.len() {
                return Err(MeshError::IndexOutOfRange {
                    face,
                    index,
                    vertex_count: positions.len(),
                });
            }
            if f[(c + 1) % 3] == index {
                return Err(MeshError::RepeatedVertexInFace {
                    face,
                    vertex: index,
                });
            }
        }
    }
    let pairs = face_pairs(faces)?;
    check_vertex_fans(positions.len(), faces, &pairs)?;
    check_orientation(faces.len(), &pairs)?;
    check_areas(positions, faces)
}

/// Two faces sharing the undirected edge `(a, b)`, `a < b`.
struct FacePair {
    a: usize,
    b: usize,
    faces: [usize; 2],
    /// Both faces traverse the edge in the same direction.
    same_direction: bool,
}

/// Groups directed half-edges by undirected edge; fails on edges with more than two faces.
fn face_pairs(faces: &[[usize; 3]]) -> Result<Vec<FacePair>, MeshError> {
    let mut half_edges: Vec<(usize, usize, usize, bool)> = Vec::with_capacity(3 * faces.len());
    for (t, f) in faces.iter().enumerate() {
        for c in 0..3 {
            let (from, to) = (f[c], f[(c + 1) % 3]);
            half_edges.push((from.min(to), from.max(to), t, from < to));
        }
    }
    half_edges.sort_unstable();
    let mut pairs = Vec::with_capacity(half_edges.len() / 2);
    for group in half_edges.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        let (a, b, t0, forward0) = group[0];
        match group {
            [_] => {}
            [_, (_, _, t1, forward1)] => pairs.push(FacePair {
                a,
                b,
                faces: [t0, *t1],
                same_direction: forward0 == *forward1,
            }),
            _ => {
                return Err(MeshError::NonManifoldEdge {
                    a,
                    b,
                    face_count: group.len(),
                })
            }
        }
    }
    Ok(pairs)
}

/// Union–find root with path halving.
fn root(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// Fails if the faces around some vertex form more than one edge-connected fan.
///
/// Union–find over corners `3t + c`: two faces sharing edge `(a, b)` join their corners at `a`
/// and at `b`; a manifold vertex ends with all its corners in one set.
fn check_vertex_fans(
    vertex_count: usize,
    faces: &[[usize; 3]],
    pairs: &[FacePair],
) -> Result<(), MeshError> {
    let corner_of = |t: usize, v: usize| 3 * t + faces[t].iter().position(|&w| w == v).unwrap_or(0);
    let mut parent: Vec<usize> = (0..3 * faces.len()).collect();
    for pair in pairs {
        let [t0, t1] = pair.faces;
        for v in [pair.a, pair.b] {
            let (r0, r1) = (
                root(&mut parent, corner_of(t0, v)),
                root(&mut parent, corner_of(t1, v)),
            );
            parent[r0.max(r1)] = r0.min(r1);
        }
    }
    let mut fans: Vec<(usize, usize)> = (0..3 * faces.len())
        .map(|corner| (faces[corner / 3][corner % 3], root(&mut parent, corner)))
        .collect();
    fans.sort_unstable();
    fans.dedup();
    let mut count = vec![0usize; vertex_count];
    for &(v, _) in &fans {
        count[v] += 1;
    }
    match count.iter().position(|&c| c > 1) {
        Some(vertex) => Err(MeshError::NonManifoldVertex {
            vertex,
            fans: count[vertex],
        }),
        None => Ok(()),
    }
}

/// Tries to orient every component consistently by breadth-first search from its first face.
///
/// If some face would need both orientations the surface is non-orientable; otherwise, if any
/// neighbours disagree, it is orientable but inconsistently oriented.
fn check_orientation(face_count: usize, pairs: &[FacePair]) -> Result<(), MeshError> {
    // Compressed adjacency: neighbours of face t are adjacency[offset[t]..offset[t + 1]].
    let mut offset = vec![0usize; face_count + 1];
    for pair in pairs {
        offset[pair.faces[0] + 1] += 1;
        offset[pair.faces[1] + 1] += 1;
    }
    for t in 0..face_count {
        offset[t + 1] += offset[t];
    }
    let mut fill = offset.clone();
    let mut adjacency = vec![(0usize, false); offset[face_count]];
    for pair in pairs {
        let [t0, t1] = pair.faces;
        adjacency[fill[t0]] = (t1, pair.same_direction);
        fill[t0] += 1;
        adjacency[fill[t1]] = (t0, pair.same_direction);
        fill[t1] += 1;
    }
    // flipped[t]: whether face t must be reversed to agree with the first face of its component.
    let mut flipped: Vec<Option<bool>> = vec![None; face_count];
    let mut queue = std::collections::VecDeque::new();
    for start in 0..face_count {
        if flipped[start].is_some() {
            continue;
        }
        flipped[start] = Some(false);
        queue.push_back(start);
        while let Some(t) = queue.pop_front() {
            let flip_t = flipped[t] == Some(true);
            for &(u, same) in &adjacency[offset[t]..offset[t + 1]] {
                let wanted = flip_t ^ same;
                match flipped[u] {
                    None => {
                        flipped[u] = Some(wanted);
                        queue.push_back(u);
                    }
                    Some(actual) if actual != wanted => {
                        return Err(MeshError::NonOrientable {
                            face_a: start,
                            face_b: u,
                        })
                    }
                    Some(_) => {}
                }
            }
        }
    }
    match pairs.iter().find(|p| p.same_direction) {
        Some(pair) => Err(MeshError::InconsistentOrientation {
            face_a: pair.faces[0],
            face_b: pair.faces[1],
            a: pair.a,
            b: pair.b,
        }),
        None => Ok(()),
    }
}

/// Fails on the first face whose area is zero up to rounding (see [`ZERO_AREA_RELATIVE`]).
fn check_areas(positions: &[[f64; 3]], faces: &[[usize; 3]]) -> Result<(), MeshError> {
    for (face, f) in faces.iter().enumerate() {
        let [p0, p1, p2] = f.map(|i| positions[i]);
        let twice_area = norm(cross(sub(p1, p0), sub(p2, p0)));
        let longest_squared = [sub(p1, p0), sub(p2, p1), sub(p0, p2)]
            .iter()
            .map(|e| e[0] * e[0] + e[1] * e[1] + e[2] * e[2])
            .fold(0.0, f64::max);
        if twice_area <= ZERO_AREA_RELATIVE * longest_squared {
            return Err(MeshError::ZeroAreaFace { face });
        }
    }
    Ok(())
}

/// Reports referenced vertices whose position (bit for bit, `-0.0 = 0.0`) repeats an earlier one.
fn duplicate_vertices(positions: &[[f64; 3]], referenced: &[bool]) -> Option<ValidationWarning> {
    let mut seen: HashMap<[u64; 3], usize> = HashMap::with_capacity(positions.len());
    let mut count = 0;
    let mut first = None;
    for (v, p) in positions.iter().enumerate() {
        if !referenced[v] {
            continue;
        }
        let key = p.map(|x| (x + 0.0).to_bits());
        match seen.get(&key) {
            Some(&earlier) => {
                count += 1;
                first.get_or_insert((v, earlier));
            }
            None => {
                seen.insert(key, v);
            }
        }
    }
    first.map(
        |(first, duplicate_of)| ValidationWarning::DuplicateVertices {
            count,
            first,
            duplicate_of,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Vec<[f64; 3]> {
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]
    }

    #[test]
    fn flipped_square_is_inconsistent_not_non_orientable() {
        assert!(TriangleMesh::validated(square(), vec![[0, 1, 2], [0, 2, 3]]).is_ok());
        assert!(matches!(
            check_faces(&square(), &[[0, 1, 2], [0, 3, 2]]),
            Err(MeshError::InconsistentOrientation { a: 0, b: 2, .. })
        ));
    }

    #[test]
    fn bowtie_is_a_non_manifold_vertex() {
        let mut positions = square();
        positions.extend([[-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]);
        let faces = vec![[0, 1, 2], [0, 4, 5]];
        assert_eq!(
            check_faces(&positions, &faces),
            Err(MeshError::NonManifoldVertex { vertex: 0, fans: 2 })
        );
    }

    #[test]
    fn unreferenced_vertices_are_dropped_and_reported() {
        let mut positions = square();
        positions.insert(0, [5.0, 5.0, 5.0]);
        let (mesh, report) =
            TriangleMesh::validated(positions, vec![[1, 2, 3], [1, 3, 4]]).unwrap();
        assert_eq!(mesh.vertex_count(), 4);
        assert_eq!(report.unreferenced_vertices(), 1);
        assert_eq!(report.original_vertex, vec![1, 2, 3, 4]);
        assert_eq!(mesh.faces()[0], [0, 1, 2]);
        assert!((report.max_angle_deg - 90.0).abs() < 1e-12);
        assert!((report.min_angle_deg - 45.0).abs() < 1e-12);
    }

    #[test]
    fn collinear_face_has_zero_area() {
        let positions = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.3, 0.0, 0.0]];
        assert_eq!(
            check_faces(&positions, &[[0, 1, 2]]),
            Err(MeshError::ZeroAreaFace { face: 0 })
        );
    }
}
