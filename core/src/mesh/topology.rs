//! Edge numbering, face↔edge incidence and connected components, built from a face list.

use super::error::MeshError;
use super::triangle_mesh::NO_FACE;

/// The combinatorial structure derived from a face list.
pub(crate) struct Topology {
    /// Edges `(a, b)` with `a < b`, sorted lexicographically.
    pub edges: Vec<[usize; 2]>,
    /// `face_edges[t][c]` is the edge opposite corner `c` of face `t`.
    pub face_edges: Vec<[usize; 3]>,
    /// `edge_faces[e] = [left, right]`: `left` traverses the edge as `a → b`, `right` as `b → a`;
    /// [`NO_FACE`] where the edge is on the boundary.
    pub edge_faces: Vec<[usize; 2]>,
    /// Connected-component id of every face, numbered `0..component_count` in order of first face.
    pub face_component: Vec<usize>,
    /// Number of edge-connected components.
    pub component_count: usize,
}

/// Builds the topology of `faces` over `vertex_count` vertices.
///
/// Fails on out-of-range or repeated indices, on edges with more than two faces, and on two faces
/// that traverse their common edge in the same direction.
pub(crate) fn build_topology(
    vertex_count: usize,
    faces: &[[usize; 3]],
) -> Result<Topology, MeshError> {
    if faces.is_empty() {
        return Err(MeshError::NoFaces);
    }
    for (t, face) in faces.iter().enumerate() {
        for (c, &index) in face.iter().enumerate() {
            if index >= vertex_count {
                return Err(MeshError::IndexOutOfRange {
                    face: t,
                    index,
                    vertex_count,
                });
            }
            if face[(c + 1) % 3] == index {
                return Err(MeshError::RepeatedVertexInFace {
                    face: t,
                    vertex: index,
                });
            }
        }
    }

    // One record per (face, corner): the undirected edge opposite the corner, and whether the
    // face traverses it from the smaller to the larger vertex.
    let mut half_edges: Vec<(usize, usize, usize, usize)> = Vec::with_capacity(3 * faces.len());
    for (t, face) in faces.iter().enumerate() {
        for c in 0..3 {
            let from = face[(c + 1) % 3];
            let to = face[(c + 2) % 3];
            half_edges.push((from.min(to), from.max(to), t, c));
        }
    }
    half_edges.sort_unstable();

    let mut edges = Vec::with_capacity(half_edges.len() / 2 + 1);
    let mut edge_faces: Vec<[usize; 2]> = Vec::with_capacity(half_edges.len() / 2 + 1);
    let mut face_edges = vec![[usize::MAX; 3]; faces.len()];
    let mut start = 0;
    while start < half_edges.len() {
        let (a, b, _, _) = half_edges[start];
        let mut end = start + 1;
        while end < half_edges.len() && half_edges[end].0 == a && half_edges[end].1 == b {
            end += 1;
        }
        if end - start > 2 {
            return Err(MeshError::NonManifoldEdge {
                a,
                b,
                face_count: end - start,
            });
        }
        let e = edges.len();
        edges.push([a, b]);
        let mut sides = [NO_FACE; 2];
        for &(_, _, t, c) in &half_edges[start..end] {
            face_edges[t][c] = e;
            let forward = faces[t][(c + 1) % 3] == a;
            let side = if forward { 0 } else { 1 };
            if sides[side] != NO_FACE {
                return Err(MeshError::InconsistentOrientation {
                    face_a: sides[side],
                    face_b: t,
                    a,
                    b,
                });
            }
            sides[side] = t;
        }
        edge_faces.push(sides);
        start = end;
    }

    let (face_component, component_count) = face_components(faces.len(), &edge_faces);
    Ok(Topology {
        edges,
        face_edges,
        edge_faces,
        face_component,
        component_count,
    })
}

/// Labels faces by edge-connected component (union–find over interior edges).
fn face_components(face_count: usize, edge_faces: &[[usize; 2]]) -> (Vec<usize>, usize) {
    let mut parent: Vec<usize> = (0..face_count).collect();
    fn root(parent: &mut [usize], mut x: usize) -> usize {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    }
    for &[left, right] in edge_faces {
        if left != NO_FACE && right != NO_FACE {
            let (ra, rb) = (root(&mut parent, left), root(&mut parent, right));
            if ra != rb {
                parent[ra.max(rb)] = ra.min(rb);
            }
        }
    }
    let mut label = vec![usize::MAX; face_count];
    let mut count = 0;
    let component = (0..face_count)
        .map(|t| {
            let r = root(&mut parent, t);
            if label[r] == usize::MAX {
                label[r] = count;
                count += 1;
            }
            label[r]
        })
        .collect();
    (component, count)
}
