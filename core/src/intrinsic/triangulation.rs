//! [`IntrinsicTriangulation`]: the connectivity and edge lengths of an intrinsic triangulation,
//! with the integer coordinates that tie it to its input mesh.

use super::curve_ends::{CurveEnd, CurveEnds, NO_END};
use super::error::IntrinsicError;
use super::length_geometry::is_triangle;
use super::normal_coordinates::ALONG_INPUT_EDGE;
use super::surface_location::InputLocation;
use crate::geometry::{norm, sub};
use crate::{TriangleMesh, NO_FACE};

/// Marker for the missing twin of a boundary halfedge.
pub(crate) const NO_HALFEDGE: usize = usize::MAX;

/// A triangulation of the same surface as an input [`TriangleMesh`], known by its connectivity
/// and edge lengths only (no positions), with its correspondence to the input.
///
/// **Connectivity.** Face `t` has corners `faces()[t]`, counter-clockwise, and
/// `face_edges(t)[c]` is the edge opposite corner `c` (as in [`TriangleMesh::face_edges`]).
/// Each edge has a reference direction, `edge_vertices(e) = [first, second]`, its faces
/// `edge_faces(e) = [left, right]`, and `face_edge_orientations(t)` tells which sides a face runs
/// along in that direction (DEC's `d0` and `d1`). Unlike a [`TriangleMesh`], an intrinsic
/// triangulation may have several edges between the same two vertices, edges from a vertex to
/// itself, and a face with a repeated corner: edges are known by index, not by their endpoints.
/// Inside, it is a halfedge structure (halfedge `3t + c` is side `c` of face `t`, from corner
/// `c + 1` to `c + 2`, with a twin across the edge), which takes vertices where several sheets of
/// faces meet as they are.
///
/// **Start.** [`IntrinsicTriangulation::new`] copies the input: vertex `v`, edge `e` and face `t`
/// are the input's, with the input's edge numbering (lexicographic, reference direction
/// `a → b`, except on a boundary edge whose face lies on the right of `a → b`: a reference
/// direction is one of the edge's halfedges, and that edge has only the one `b → a`), and edge
/// lengths `|p_b − p_a|`. Flips keep the numbers of the two faces and of the
/// edge they flip; inserted vertices, edges and faces are appended. Methods that need the
/// input's connectivity take the input mesh again and check that its counts match.
///
/// **Correspondence: integer coordinates** (Gillespie, Sharp and Crane, *Integer Coordinates for
/// Intrinsic Geometry Processing*, 2021), not signposts (Sharp, Soliman and Crane 2019). Each
/// intrinsic edge stores its *normal coordinate*, the number of input edges crossing it (−1
/// when it lies along an input edge), and each halfedge its *roundabout*, which input edge
/// leaving its tail vertex comes first counter-clockwise. A flip or an edge split updates them
/// exactly with integer arithmetic on the two faces involved, so the combinatorics of the
/// overlay (which input edges cross which intrinsic edges, in which order) never depends on
/// round-off and cannot drift however many flips are made; positions of crossings are computed
/// from the lengths only when the common subdivision is extracted. Signposts store
/// floating-point angles and recover the overlay by tracing, which round-off can make
/// inconsistent near vertices on long flip sequences; integer coordinates completed on every
/// manifold mesh of Thingi10k in Gillespie et al.'s tests, and their flip update is a few integer
/// operations (cheaper than updating signpost angles).
#[derive(Debug, Clone)]
pub struct IntrinsicTriangulation {
    pub(crate) input_counts: [usize; 3],
    pub(crate) vertex_locations: Vec<InputLocation>,
    pub(crate) faces: Vec<[usize; 3]>,
    pub(crate) twin: Vec<usize>,
    pub(crate) halfedge_edge: Vec<usize>,
    /// One halfedge per edge, the edge's reference direction (the one in the face on its left
    /// for an interior edge at the start).
    pub(crate) edge_halfedge: Vec<usize>,
    pub(crate) lengths: Vec<f64>,
    pub(crate) normal: Vec<i64>,
    /// `Σ max(n_e, 0)`: every crossing of an input edge with an intrinsic edge.
    pub(crate) crossing_total: usize,
    pub(crate) roundabout: Vec<usize>,
    pub(crate) curve_ends: CurveEnds,
    pub(crate) flip_count: usize,
}

impl IntrinsicTriangulation {
    /// The intrinsic triangulation equal to `mesh`: same vertices, edges (numbering included)
    /// and faces, edge lengths from the positions, every edge along its input edge.
    ///
    /// Fails with [`IntrinsicError::DegenerateFace`] on a face whose edge lengths do not form a
    /// triangle of positive area (collinear or coincident corners), and with
    /// [`IntrinsicError::NonFiniteLength`] on an edge whose length overflows.
    pub fn new(mesh: &TriangleMesh) -> Result<Self, IntrinsicError> {
        let positions = mesh.positions();
        let lengths: Vec<f64> = mesh
            .edges()
            .iter()
            .map(|&[a, b]| norm(sub(positions[b], positions[a])))
            .collect();
        if let Some(edge) = lengths.iter().position(|l| !l.is_finite()) {
            return Err(IntrinsicError::NonFiniteLength { edge });
        }
        for (face, edges) in mesh.face_edges().iter().enumerate() {
            let l = edges.map(|e| lengths[e]);
            if !is_triangle(l) {
                return Err(IntrinsicError::DegenerateFace { face, lengths: l });
            }
        }
        let face_count = mesh.face_count();
        let mut twin = vec![NO_HALFEDGE; 3 * face_count];
        let mut halfedge_edge = vec![0; 3 * face_count];
        let mut edge_halfedge = vec![NO_HALFEDGE; mesh.edge_count()];
        for (t, edges) in mesh.face_edges().iter().enumerate() {
            for (c, &e) in edges.iter().enumerate() {
                let h = 3 * t + c;
                halfedge_edge[h] = e;
                let [left, right] = mesh.edge_faces()[e];
                let other = if left == t { right } else { left };
                if other != NO_FACE {
                    let oc = mesh.face_edges()[other].iter().position(|&x| x == e);
                    twin[h] = 3 * other + oc.unwrap_or(0);
                }
                if t == left || left == NO_FACE {
                    edge_halfedge[e] = h;
                }
            }
        }
        let mut triangulation = Self {
            input_counts: [mesh.vertex_count(), mesh.edge_count(), face_count],
            vertex_locations: (0..mesh.vertex_count())
                .map(InputLocation::Vertex)
                .collect(),
            faces: mesh.faces().to_vec(),
            twin,
            halfedge_edge,
            edge_halfedge,
            lengths,
            normal: vec![ALONG_INPUT_EDGE; mesh.edge_count()],
            crossing_total: 0,
            roundabout: vec![NO_END; 3 * face_count],
            curve_ends: CurveEnds::default(),
            flip_count: 0,
        };
        triangulation.build_input_fans();
        Ok(triangulation)
    }

    /// The ends of the input edges around every input vertex, and the roundabouts of the
    /// halfedges (each is its own input edge's end at the start).
    fn build_input_fans(&mut self) {
        // Input edges are (a, b) with a < b: an edge leaves `from` towards b when its other
        // end is the larger.
        let end_of = |h: usize, from: usize, to: usize| CurveEnd {
            edge: self.halfedge_edge[h],
            toward_b: from < to,
        };
        let mut visited = vec![false; self.twin.len()];
        let mut fan = Vec::new();
        let mut fan_halfedges = Vec::new();
        // Open fans start at the outgoing boundary halfedge; then the closed fans.
        let boundary_starts = (0..self.twin.len()).filter(|&h| self.twin[h] == NO_HALFEDGE);
        let starts: Vec<usize> = boundary_starts.chain(0..self.twin.len()).collect();
        for start in starts {
            if visited[start] {
                continue;
            }
            let v = self.tail(start);
            fan.clear();
            fan_halfedges.clear();
            let mut h = start;
            let closed = loop {
                visited[h] = true;
                fan.push(end_of(h, v, self.head(h)));
                fan_halfedges.push(h);
                let p = self.prev(h);
                if self.twin[p] == NO_HALFEDGE {
                    fan.push(end_of(p, v, self.tail(p)));
                    break false;
                }
                h = self.twin[p];
                if h == start {
                    break true;
                }
            };
            let first = self.curve_ends.push_fan(&fan, closed);
            for (k, &h) in fan_halfedges.iter().enumerate() {
                self.roundabout[h] = first + k;
            }
        }
    }

    /// Number of vertices: the input's, then the inserted ones.
    pub fn vertex_count(&self) -> usize {
        self.vertex_locations.len()
    }

    /// Number of edges.
    pub fn edge_count(&self) -> usize {
        self.lengths.len()
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }

    /// Number of vertices of the input mesh (intrinsic vertices `0..input_vertex_count()` are
    /// the input's vertices).
    pub fn input_vertex_count(&self) -> usize {
        self.input_counts[0]
    }

    /// Number of vertices inserted by refinement (numbered after the input's).
    pub fn inserted_vertex_count(&self) -> usize {
        self.vertex_count() - self.input_counts[0]
    }

    /// Number of edge flips made since the triangulation was built.
    pub fn flip_count(&self) -> usize {
        self.flip_count
    }

    /// Faces as counter-clockwise vertex triples (a vertex may repeat), `F` entries.
    pub fn faces(&self) -> &[[usize; 3]] {
        &self.faces
    }

    /// Edge lengths (units of the input mesh), `E` entries.
    pub fn lengths(&self) -> &[f64] {
        &self.lengths
    }

    /// `face_edges(t)[c]`: the edge opposite corner `c` of face `t`.
    pub fn face_edges(&self, t: usize) -> [usize; 3] {
        std::array::from_fn(|c| self.halfedge_edge[3 * t + c])
    }

    /// The two endpoints of edge `e` in its reference direction (they may be equal).
    pub fn edge_vertices(&self, e: usize) -> [usize; 2] {
        let h = self.edge_halfedge[e];
        [self.tail(h), self.head(h)]
    }

    /// Whether face `t` runs along each of its sides in the side's edge's reference direction
    /// ([`IntrinsicTriangulation::edge_vertices`]): `true` for side `c` (opposite corner `c`)
    /// when the face's counter-clockwise boundary goes from the edge's first vertex to its
    /// second, the `+1` of DEC's `d1`.
    pub fn face_edge_orientations(&self, t: usize) -> [bool; 3] {
        std::array::from_fn(|c| self.edge_halfedge[self.halfedge_edge[3 * t + c]] == 3 * t + c)
    }

    /// `[left, right]`: the face on the left of edge `e` in its reference direction
    /// ([`IntrinsicTriangulation::edge_vertices`]) and the face on its right ([`NO_FACE`] on the
    /// boundary). Both may be the same face.
    pub fn edge_faces(&self, e: usize) -> [usize; 2] {
        let h = self.edge_halfedge[e];
        let t = self.twin[h];
        [h / 3, if t == NO_HALFEDGE { NO_FACE } else { t / 3 }]
    }

    /// Whether edge `e` has a face on one side only.
    pub fn is_boundary_edge(&self, e: usize) -> bool {
        self.twin[self.edge_halfedge[e]] == NO_HALFEDGE
    }

    /// The edge lengths of face `t`, `[l_0, l_1, l_2]` with `l_c` opposite corner `c`.
    pub fn face_lengths(&self, t: usize) -> [f64; 3] {
        std::array::from_fn(|c| self.lengths[self.halfedge_edge[3 * t + c]])
    }

    /// Where vertex `v` sits on the input surface.
    pub fn vertex_location(&self, v: usize) -> InputLocation {
        self.vertex_locations[v]
    }

    /// The normal coordinate of edge `e`: how many input edges cross it, or −1 if it lies along
    /// an input edge.
    pub fn normal_coordinate(&self, e: usize) -> i64 {
        self.normal[e]
    }

    /// Sets the normal coordinate of edge `e`, keeping the crossing total.
    pub(crate) fn set_normal(&mut self, e: usize, value: i64) {
        self.crossing_total =
            self.crossing_total + value.max(0) as usize - self.normal[e].max(0) as usize;
        self.normal[e] = value;
    }

    /// Fails unless `mesh` has the vertex, edge and face counts of the input this triangulation
    /// was built from.
    pub(crate) fn check_input(&self, mesh: &TriangleMesh) -> Result<(), IntrinsicError> {
        let given = [mesh.vertex_count(), mesh.edge_count(), mesh.face_count()];
        if given == self.input_counts {
            Ok(())
        } else {
            Err(IntrinsicError::InputMismatch {
                expected: self.input_counts,
                given,
            })
        }
    }

    /// Tail vertex of halfedge `h`.
    pub(crate) fn tail(&self, h: usize) -> usize {
        self.faces[h / 3][(h % 3 + 1) % 3]
    }

    /// Head vertex of halfedge `h`.
    pub(crate) fn head(&self, h: usize) -> usize {
        self.faces[h / 3][(h % 3 + 2) % 3]
    }

    /// The halfedge after `h` in its face (it starts where `h` ends).
    pub(crate) fn next(&self, h: usize) -> usize {
        3 * (h / 3) + (h % 3 + 1) % 3
    }

    /// The halfedge before `h` in its face (it ends where `h` starts).
    pub(crate) fn prev(&self, h: usize) -> usize {
        3 * (h / 3) + (h % 3 + 2) % 3
    }

    /// Number of input edges crossing the edge of halfedge `h` (0 if it lies along one).
    pub(crate) fn crossings(&self, h: usize) -> i64 {
        self.normal[self.halfedge_edge[h]].max(0)
    }

    /// Whether the edge of halfedge `h` lies along an input edge.
    pub(crate) fn is_along_input(&self, h: usize) -> bool {
        self.normal[self.halfedge_edge[h]] == ALONG_INPUT_EDGE
    }

    /// The normal coordinates of the three sides of face `t`.
    pub(crate) fn face_normals(&self, t: usize) -> [i64; 3] {
        std::array::from_fn(|c| self.normal[self.halfedge_edge[3 * t + c]])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{disk, torus};

    #[test]
    fn starts_as_a_copy_of_the_input() {
        let mesh = torus(2.0, 0.7, 12, 8).unwrap();
        let tri = IntrinsicTriangulation::new(&mesh).unwrap();
        assert_eq!(tri.faces(), mesh.faces());
        for (e, &[a, b]) in mesh.edges().iter().enumerate() {
            assert_eq!(tri.edge_vertices(e), [a, b]);
            let length = norm(sub(mesh.positions()[b], mesh.positions()[a]));
            assert_eq!(tri.lengths()[e].to_bits(), length.to_bits());
            assert_eq!(tri.edge_faces(e), mesh.edge_faces()[e]);
        }
        for t in 0..mesh.face_count() {
            assert_eq!(tri.face_edges(t), mesh.face_edges()[t]);
            // Forward exactly where the face is the edge's left face (it runs a → b).
            let forward = mesh.face_edges()[t].map(|e| mesh.edge_faces()[e][0] == t);
            assert_eq!(tri.face_edge_orientations(t), forward);
        }
        tri.check_invariants().unwrap();
    }

    #[test]
    fn boundary_edges_have_no_twin() {
        let mesh = disk(3);
        let tri = IntrinsicTriangulation::new(&mesh).unwrap();
        for e in 0..mesh.edge_count() {
            assert_eq!(tri.is_boundary_edge(e), mesh.is_boundary_edge(e));
        }
        tri.check_invariants().unwrap();
    }

    #[test]
    fn degenerate_faces_are_errors() {
        let mesh = TriangleMesh::new(
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
            vec![[0, 1, 2]],
        )
        .unwrap();
        let err = IntrinsicTriangulation::new(&mesh).unwrap_err();
        assert!(
            matches!(err, IntrinsicError::DegenerateFace { face: 0, .. }),
            "{err}"
        );
        let huge = TriangleMesh::new(
            vec![[0.0, 0.0, 0.0], [1e308, 0.0, 0.0], [-1e308, 1e308, 0.0]],
            vec![[0, 1, 2]],
        )
        .unwrap();
        let err = IntrinsicTriangulation::new(&huge).unwrap_err();
        assert!(
            matches!(err, IntrinsicError::NonFiniteLength { .. }),
            "{err}"
        );
    }
}
