//! Lawson flips kept up to date edge by edge: [`LawsonFlips`] holds the faces, every edge's two
//! faces and the interior edges ordered by `cot α + cot β`, and a flip updates the five edges it
//! touches. It makes exactly the flips (and so the meshes) of the plain loop that recomputes
//! every cotangent sum and rebuilds the mesh after each flip
//! ([`crate::corpus::try_delaunay_flips`]'s definition; the unit test below keeps that loop as
//! the oracle): the same worst edge, ties broken by the edge order of [`TriangleMesh`] (its
//! vertex pairs ascending), the same vertex order in the new faces, the same sums to the bit.
//! The plain loop rebuilt the topology of the whole mesh per flip, `O(flips · E log E)`: on the
//! generated Delaunay meshes of the property tests it was most of their time.

use crate::corpus::cotangent_sums;
use std::cmp::Ordering;
use std::collections::{BTreeSet, HashMap};
use tvf_core::geometry::{cross, dot, norm, sub};
use tvf_core::{TriangleMesh, NO_FACE};
use tvf_discretizations::DELAUNAY_TOLERANCE;

/// A cotangent sum ordered by [`f64::total_cmp`], as the plain loop compares them.
#[derive(Debug, Clone, Copy)]
struct Sum(f64);

impl PartialEq for Sum {
    fn eq(&self, other: &Self) -> bool {
        self.0.total_cmp(&other.0) == Ordering::Equal
    }
}
impl Eq for Sum {}
impl PartialOrd for Sum {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Sum {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// An edge as its vertex pair `(a, b)`, `a < b`.
type Edge = (usize, usize);

fn edge(u: usize, v: usize) -> Edge {
    (u.min(v), u.max(v))
}

/// The state of a run of Lawson flips on a triangle mesh.
pub struct LawsonFlips<'m> {
    mesh: &'m TriangleMesh,
    faces: Vec<[usize; 3]>,
    /// Every edge's `[left, right]` faces (`left` traverses it from `a` to `b`, [`NO_FACE`] on a
    /// missing side), as [`TriangleMesh::edge_faces`] numbers them.
    sides: HashMap<Edge, [usize; 2]>,
    /// `cot α + cot β` of every interior edge.
    sums: HashMap<Edge, f64>,
    /// The interior edges by sum, then by vertex pair.
    order: BTreeSet<(Sum, usize, usize)>,
    flipped: bool,
}

impl<'m> LawsonFlips<'m> {
    /// The state of `mesh` before any flip.
    pub fn new(mesh: &'m TriangleMesh) -> Self {
        let all = cotangent_sums(mesh);
        let mut sides = HashMap::with_capacity(mesh.edge_count());
        let mut sums = HashMap::new();
        let mut order = BTreeSet::new();
        for (e, &[a, b]) in mesh.edges().iter().enumerate() {
            sides.insert((a, b), mesh.edge_faces()[e]);
            if !mesh.is_boundary_edge(e) {
                sums.insert((a, b), all[e]);
                order.insert((Sum(all[e]), a, b));
            }
        }
        Self {
            mesh,
            faces: mesh.faces().to_vec(),
            sides,
            sums,
            order,
            flipped: false,
        }
    }

    /// The interior edge with the smallest `cot α + cot β` (the first in vertex-pair order among
    /// equal ones) if that is at most [`DELAUNAY_TOLERANCE`].
    pub fn worst(&self) -> Option<Edge> {
        self.order
            .first()
            .filter(|(sum, _, _)| sum.0 <= DELAUNAY_TOLERANCE)
            .map(|&(_, a, b)| (a, b))
    }

    /// Replaces interior edge `(a, b)` by the other diagonal of its two faces: `(p, a, b)` and
    /// `(q, b, a)` become `(p, a, q)` and `(q, b, p)`. An error (the mesh's own, as
    /// [`TriangleMesh::new`] words it) if the flip would break the mesh: the new diagonal is an
    /// edge already, or both faces have the same opposite vertex.
    pub fn flip(&mut self, (a, b): Edge) -> Result<(), String> {
        let [s, t] = self.sides[&(a, b)];
        let cs = self.opposite_corner(s, (a, b));
        let ct = self.opposite_corner(t, (a, b));
        let (p, q) = (self.faces[s][cs], self.faces[t][ct]);
        debug_assert_eq!(
            [self.faces[s][(cs + 1) % 3], self.faces[s][(cs + 2) % 3]],
            [a, b]
        );
        if p == q || self.sides.contains_key(&edge(p, q)) {
            return Err(self.broken_by((a, b), [s, t], [p, q]));
        }
        self.faces[s] = [p, a, q];
        self.faces[t] = [q, b, p];
        self.flipped = true;
        self.sides.remove(&(a, b));
        self.forget_sum((a, b));
        // s = (p, a, q) traverses q → p, t = (q, b, p) traverses p → q.
        let diagonal = if p < q { [t, s] } else { [s, t] };
        self.sides.insert(edge(p, q), diagonal);
        self.replace_side(edge(a, q), t, s);
        self.replace_side(edge(b, p), s, t);
        for e in [edge(p, q), edge(p, a), edge(a, q), edge(q, b), edge(b, p)] {
            self.update_sum(e);
        }
        Ok(())
    }

    /// The mesh after the flips so far (`mesh` itself, cloned, if none was made).
    pub fn into_mesh(self) -> Result<TriangleMesh, String> {
        if !self.flipped {
            return Ok(self.mesh.clone());
        }
        TriangleMesh::new(self.mesh.positions().to_vec(), self.faces)
            .map_err(|e| format!("the flipped faces are not a mesh: {e}"))
    }

    /// The corner of face `f` opposite edge `e`.
    fn opposite_corner(&self, f: usize, (a, b): Edge) -> usize {
        (0..3)
            .find(|&c| self.faces[f][c] != a && self.faces[f][c] != b)
            .expect("a face of an edge has a third vertex")
    }

    /// Where face `old` was a side of edge `e`, face `new` is.
    fn replace_side(&mut self, e: Edge, old: usize, new: usize) {
        let sides = self.sides.get_mut(&e).expect("an edge of a flipped face");
        for side in sides.iter_mut().filter(|side| **side == old) {
            *side = new;
        }
    }

    fn forget_sum(&mut self, e: Edge) {
        if let Some(sum) = self.sums.remove(&e) {
            self.order.remove(&(Sum(sum), e.0, e.1));
        }
    }

    /// Recomputes the sum of edge `e` from its faces as [`cotangent_sums`] adds them (faces in
    /// ascending order onto zero).
    fn update_sum(&mut self, e: Edge) {
        self.forget_sum(e);
        let [left, right] = self.sides[&e];
        if left == NO_FACE || right == NO_FACE {
            return;
        }
        let sum = [left.min(right), left.max(right)]
            .into_iter()
            .fold(0.0, |sum, f| {
                sum + self.cotangent(f, self.opposite_corner(f, e))
            });
        self.sums.insert(e, sum);
        self.order.insert((Sum(sum), e.0, e.1));
    }

    /// [`crate::corpus::corner_cotangent`] of corner `c` of face `f` as it is now.
    fn cotangent(&self, f: usize, c: usize) -> f64 {
        let p = self.mesh.positions();
        let corner = |k: usize| p[self.faces[f][(c + k) % 3]];
        let o = corner(0);
        let u = sub(corner(1), o);
        let v = sub(corner(2), o);
        dot(u, v) / norm(cross(u, v))
    }

    /// The message of a flip of edge `e` that breaks the mesh, as the plain loop words it: the
    /// edge's index in [`TriangleMesh`]'s order and the error of building the flipped faces.
    fn broken_by(&self, e: Edge, [s, t]: [usize; 2], [p, q]: [usize; 2]) -> String {
        let mut faces = self.faces.clone();
        faces[s] = [p, e.0, q];
        faces[t] = [q, e.1, p];
        let index = self.sides.keys().filter(|&&other| other < e).count();
        match TriangleMesh::new(self.mesh.positions().to_vec(), faces) {
            Err(error) => format!("flipping edge {index} broke the mesh: {error}"),
            Ok(_) => format!("flipping edge {index} would repeat an edge"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::corpus::{open_corpus, sliver_torus, try_delaunay_flips};
    use tvf_core::generate::{hemisphere, icosphere, jitter, perforated_plate, torus};

    /// The plain Lawson loop: every sum recomputed and the mesh rebuilt after each flip.
    fn plain_flips(mesh: &TriangleMesh) -> Result<TriangleMesh, String> {
        let mut current = mesh.clone();
        for _ in 0..10 * mesh.edge_count() {
            let sums = cotangent_sums(&current);
            let worst = (0..sums.len())
                .filter(|&e| !current.is_boundary_edge(e))
                .min_by(|&a, &b| sums[a].total_cmp(&sums[b]))
                .filter(|&e| sums[e] <= DELAUNAY_TOLERANCE);
            let Some(edge) = worst else {
                return Ok(current);
            };
            let mut faces = current.faces().to_vec();
            let [s, t] = current.edge_faces()[edge];
            let corner = |f: usize| {
                current.face_edges()[f]
                    .iter()
                    .position(|&e| e == edge)
                    .expect("an edge's face contains it")
            };
            let (cs, ct) = (corner(s), corner(t));
            let (p, a, b) = (faces[s][cs], faces[s][(cs + 1) % 3], faces[s][(cs + 2) % 3]);
            let q = faces[t][ct];
            faces[s] = [p, a, q];
            faces[t] = [q, b, p];
            current = TriangleMesh::new(current.positions().to_vec(), faces)
                .map_err(|e| format!("flipping edge {edge} broke the mesh: {e}"))?;
        }
        Err("Lawson flips did not converge".to_string())
    }

    #[test]
    fn the_flips_are_those_of_the_plain_loop() {
        // Closed and open, regular (ties between equal sums) and jittered, with slivers.
        let mut meshes: Vec<TriangleMesh> = open_corpus().into_iter().map(|m| m.mesh).collect();
        meshes.push(torus(1.0, 0.4, 12, 6).unwrap());
        meshes.push(sliver_torus(1.0, 0.4, 12, 8, 0.01));
        meshes.push(jitter(&icosphere(2), 0.3, 1).unwrap());
        for seed in 0..3 {
            meshes.push(jitter(&perforated_plate(2, 6), 0.3, seed).unwrap());
            meshes.push(jitter(&hemisphere(4), 0.25, seed).unwrap());
        }
        let mut flipped = 0;
        for mesh in &meshes {
            let plain = plain_flips(mesh);
            let kept = try_delaunay_flips(mesh);
            match (&plain, &kept) {
                (Ok(a), Ok(b)) => {
                    assert_eq!(a.faces(), b.faces());
                    flipped += usize::from(a.faces() != mesh.faces());
                }
                (Err(a), Err(b)) => assert_eq!(a, b),
                _ => panic!("{plain:?} against {kept:?}"),
            }
        }
        assert!(flipped >= 10, "only {flipped} meshes needed flips");
    }
}
