//! Edge numbering, face↔edge incidence and connected components, built from a list of faces of
//! any size ([`build_topology`]), and what follows from them ([`MeshTopology`]: boundary loops,
//! components, Euler characteristic, genus) for triangle and polygon meshes alike.

use super::error::MeshError;
use super::face_list::FaceCorners;

/// Marker in [`MeshTopology::edge_faces`] for the missing face of a boundary edge.
pub const NO_FACE: usize = usize::MAX;

/// The combinatorial structure of an oriented, edge-manifold mesh: its edges, which faces lie on
/// either side of each, and the connected components.
#[derive(Debug, Clone)]
pub struct MeshTopology {
    vertex_count: usize,
    edges: Vec<[usize; 2]>,
    edge_faces: Vec<[usize; 2]>,
    face_component: Vec<usize>,
    component_count: usize,
}

/// A [`MeshTopology`] and, for every corner of every face (in the order of
/// [`FaceCorners::corner_index`]), the edge from that corner to the next one.
pub(crate) struct BuiltTopology {
    pub topology: MeshTopology,
    pub corner_edges: Vec<usize>,
}

/// Builds the topology of `faces` over `vertex_count` vertices.
///
/// Edges are `(a, b)` with `a < b`, numbered in lexicographic order. Fails on out-of-range or
/// repeated indices within a face, faces with fewer than three corners, edges with more than two
/// faces, and two faces that traverse their common edge in the same direction.
pub(crate) fn build_topology<F: FaceCorners + ?Sized>(
    vertex_count: usize,
    faces: &F,
) -> Result<BuiltTopology, MeshError> {
    if faces.face_count() == 0 {
        return Err(MeshError::NoFaces);
    }
    for f in 0..faces.face_count() {
        check_corners(f, faces.corners(f), vertex_count)?;
    }

    // One record per (face, corner): the undirected edge from the corner to the next one, and
    // the corner's index in the list of all corners.
    let mut half_edges: Vec<(usize, usize, usize, usize)> =
        Vec::with_capacity(faces.total_corners());
    for f in 0..faces.face_count() {
        let corners = faces.corners(f);
        for (c, &from) in corners.iter().enumerate() {
            let to = corners[(c + 1) % corners.len()];
            half_edges.push((from.min(to), from.max(to), f, faces.corner_index(f, c)));
        }
    }
    half_edges.sort_unstable();

    let mut edges = Vec::with_capacity(half_edges.len() / 2 + 1);
    let mut edge_faces: Vec<[usize; 2]> = Vec::with_capacity(half_edges.len() / 2 + 1);
    let mut corner_edges = vec![usize::MAX; faces.total_corners()];
    let flat_vertex = |f: usize, corner: usize| faces.corners(f)[corner - faces.corner_index(f, 0)];
    for group in half_edges.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        let (a, b, _, _) = group[0];
        if group.len() > 2 {
            return Err(MeshError::NonManifoldEdge {
                a,
                b,
                face_count: group.len(),
            });
        }
        let e = edges.len();
        edges.push([a, b]);
        let mut sides = [NO_FACE; 2];
        for &(_, _, f, corner) in group {
            corner_edges[corner] = e;
            let side = if flat_vertex(f, corner) == a { 0 } else { 1 };
            if sides[side] != NO_FACE {
                return Err(MeshError::InconsistentOrientation {
                    face_a: sides[side],
                    face_b: f,
                    a,
                    b,
                });
            }
            sides[side] = f;
        }
        edge_faces.push(sides);
    }

    let (face_component, component_count) = face_components(faces.face_count(), &edge_faces);
    Ok(BuiltTopology {
        topology: MeshTopology {
            vertex_count,
            edges,
            edge_faces,
            face_component,
            component_count,
        },
        corner_edges,
    })
}

/// Fails unless face `f` has at least three corners, each a vertex in range and none repeated.
pub(crate) fn check_corners(
    f: usize,
    corners: &[usize],
    vertex_count: usize,
) -> Result<(), MeshError> {
    if corners.len() < 3 {
        return Err(MeshError::TooFewCorners {
            face: f,
            corners: corners.len(),
        });
    }
    // Neighbouring corners first, in corner order (for a triangle every pair is neighbouring).
    for (c, &index) in corners.iter().enumerate() {
        if index >= vertex_count {
            return Err(MeshError::IndexOutOfRange {
                face: f,
                index,
                vertex_count,
            });
        }
        if corners[(c + 1) % corners.len()] == index {
            return Err(MeshError::RepeatedVertexInFace {
                face: f,
                vertex: index,
            });
        }
    }
    match corners
        .iter()
        .enumerate()
        .find(|&(c, v)| corners[c + 1..].contains(v))
    {
        Some((_, &vertex)) => Err(MeshError::RepeatedVertexInFace { face: f, vertex }),
        None => Ok(()),
    }
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

impl MeshTopology {
    /// Number of vertices `V` (referenced or not).
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// Edges `(a, b)`, `a < b`, in lexicographic order, `E` entries.
    pub fn edges(&self) -> &[[usize; 2]] {
        &self.edges
    }

    /// `edge_faces()[e] = [left, right]`: `left` traverses edge `(a, b)` as `a → b`, `right` as
    /// `b → a`; [`NO_FACE`] on the missing side of a boundary edge.
    pub fn edge_faces(&self) -> &[[usize; 2]] {
        &self.edge_faces
    }

    /// Whether edge `e` has only one face.
    pub fn is_boundary_edge(&self, e: usize) -> bool {
        self.edge_faces[e].contains(&NO_FACE)
    }

    /// Indices of the boundary edges, ascending.
    pub fn boundary_edges(&self) -> Vec<usize> {
        (0..self.edges.len())
            .filter(|&e| self.is_boundary_edge(e))
            .collect()
    }

    /// Whether the mesh has no boundary edge.
    pub fn is_closed(&self) -> bool {
        self.edge_faces.iter().all(|f| !f.contains(&NO_FACE))
    }

    /// Boundary loops as closed vertex cycles, each following the boundary orientation
    /// (the surface on the left).
    pub fn boundary_loops(&self) -> Vec<Vec<usize>> {
        // The next boundary vertex after `v` along the orientation of the boundary face.
        let mut next = std::collections::BTreeMap::new();
        for (e, &[a, b]) in self.edges.iter().enumerate() {
            match self.edge_faces[e] {
                [left, NO_FACE] if left != NO_FACE => {
                    next.entry(a).or_insert_with(Vec::new).push(b);
                }
                [NO_FACE, right] if right != NO_FACE => {
                    next.entry(b).or_insert_with(Vec::new).push(a);
                }
                _ => {}
            }
        }
        let mut loops = Vec::new();
        while let Some((&start, _)) = next.iter().find(|(_, v)| !v.is_empty()) {
            let mut cycle = vec![start];
            let mut v = start;
            while let Some(w) = next.get_mut(&v).and_then(|list| list.pop()) {
                if w == start {
                    break;
                }
                cycle.push(w);
                v = w;
            }
            loops.push(cycle);
        }
        loops
    }

    /// Number of edge-connected components.
    pub fn component_count(&self) -> usize {
        self.component_count
    }

    /// Component id of every face, `F` entries, in `0..component_count()`.
    pub fn face_components(&self) -> &[usize] {
        &self.face_component
    }

    /// Component id of every vertex of `faces` (the faces this topology was built from;
    /// `usize::MAX` for a vertex no face uses), `V` entries.
    pub fn vertex_components<F: FaceCorners + ?Sized>(&self, faces: &F) -> Vec<usize> {
        let mut component = vec![usize::MAX; self.vertex_count];
        for f in 0..faces.face_count() {
            for &v in faces.corners(f) {
                component[v] = self.face_component[f];
            }
        }
        component
    }

    /// Component id of every edge, `E` entries.
    pub fn edge_components(&self) -> Vec<usize> {
        self.edge_faces
            .iter()
            .map(|f| {
                let t = if f[0] != NO_FACE { f[0] } else { f[1] };
                self.face_component[t]
            })
            .collect()
    }

    /// Euler characteristic `V − E + F` of every component, over referenced vertices.
    pub fn component_euler_characteristics<F: FaceCorners + ?Sized>(&self, faces: &F) -> Vec<i64> {
        let mut chi = vec![0i64; self.component_count];
        for c in self.vertex_components(faces) {
            if c != usize::MAX {
                chi[c] += 1;
            }
        }
        for c in self.edge_components() {
            chi[c] -= 1;
        }
        for &c in &self.face_component {
            chi[c] += 1;
        }
        chi
    }

    /// Genus of every component, `(2 − b − χ)/2` with `b` its boundary loops.
    pub fn component_genera<F: FaceCorners + ?Sized>(&self, faces: &F) -> Vec<usize> {
        let mut loops = vec![0i64; self.component_count];
        let vertex_component = self.vertex_components(faces);
        for cycle in self.boundary_loops() {
            loops[vertex_component[cycle[0]]] += 1;
        }
        self.component_euler_characteristics(faces)
            .iter()
            .zip(&loops)
            .map(|(&chi, &b)| ((2 - b - chi) / 2).max(0) as usize)
            .collect()
    }
}
