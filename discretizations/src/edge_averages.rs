//! Edge values of a 1-form from per-face contributions: the mean over the faces that share an
//! edge, zero on edges a boundary condition fixes. Used by every sampling that turns face
//! vectors into edge integrals (Whitney, polygonal DEC's sharp, the intrinsic triangulation's),
//! and the de Rham map of face vectors on a mesh's edges written with them ([`edge_integrals`]).

use tvf_core::geometry::{dot, sub};

/// Sums and counts of the contributions to each edge (`E` of each).
pub(crate) struct EdgeAverages {
    sums: Vec<f64>,
    counts: Vec<u32>,
}

impl EdgeAverages {
    /// No contributions yet on `edge_count` edges.
    pub(crate) fn new(edge_count: usize) -> Self {
        Self {
            sums: vec![0.0; edge_count],
            counts: vec![0; edge_count],
        }
    }

    /// One face's contribution `value` to edge `e`.
    pub(crate) fn add(&mut self, e: usize, value: f64) {
        self.sums[e] += value;
        self.counts[e] += 1;
    }

    /// The mean contribution of each edge (`E` values); 0 where an edge had none or is fixed
    /// (`fixed_edges`, `E` flags).
    pub(crate) fn means(self, fixed_edges: &[bool]) -> Vec<f64> {
        self.sums
            .iter()
            .zip(&self.counts)
            .zip(fixed_edges)
            .map(|((&s, &n), &fixed)| {
                if n > 0 && !fixed {
                    s / f64::from(n)
                } else {
                    0.0
                }
            })
            .collect()
    }
}

/// The de Rham map of one tangent vector per face on a mesh's edges (`E` values, units length ×
/// field): `x_e` the mean, over the faces next to edge `e = (a, b)`, of `⟨v_f, p_b − p_a⟩`; 0 on
/// the edges `fixed_edges` flags. `faces` gives each face's edges (in any order) with its vector
/// `v_f`; `edges` are the mesh's edges `(a, b)` and `positions` its vertex positions.
pub(crate) fn edge_integrals<'a>(
    edges: &[[usize; 2]],
    positions: &[[f64; 3]],
    fixed_edges: &[bool],
    faces: impl Iterator<Item = (&'a [usize], [f64; 3])>,
) -> Vec<f64> {
    let mut averages = EdgeAverages::new(edges.len());
    for (face_edges, v) in faces {
        for &e in face_edges {
            let [a, b] = edges[e];
            averages.add(e, dot(v, sub(positions[b], positions[a])));
        }
    }
    averages.means(fixed_edges)
}
