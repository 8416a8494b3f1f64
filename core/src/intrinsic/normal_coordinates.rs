//! Normal coordinates: how many input edges cross each intrinsic edge, and what they imply about
//! the arcs of input edges inside one intrinsic triangle.
//!
//! The normal coordinate `n_e` of an intrinsic edge `e` counts the transversal crossings of the
//! input edges with `e`; [`ALONG_INPUT_EDGE`] (−1) marks an intrinsic edge that lies along an
//! input edge (all of it, or a part of it between inserted vertices). Input edges never cross
//! each other, so inside an intrinsic triangle their pieces ("arcs") are straight chords of two
//! kinds only:
//!
//! - **corner arcs** around corner `c`, cutting it off: they cross the two sides at `c`;
//! - **emanating arcs** from corner `c` (an input edge leaving the vertex there) to the opposite
//!   side. Two corners cannot both have them (their arcs would cross).
//!
//! With sides numbered by their opposite corner (side `s` joins corners `s+1` and `s+2`) and
//! `n⁺ = max(n, 0)`, side `s` is crossed by the corner arcs of its two ends and the arcs
//! emanating from the opposite corner: `n⁺_s = a_{s+1} + a_{s+2} + e_s`. [`TriangleArcs::new`]
//! solves this for `a` and `e`. Along side `s`, from its first corner `s+1`, the crossings are
//! ordered: `a_{s+1}` corner arcs of `s+1`, then the `e_s` emanating arcs, then the `a_{s+2}`
//! corner arcs of `s+2`.

/// Normal coordinate of an intrinsic edge that lies along an input edge.
pub const ALONG_INPUT_EDGE: i64 = -1;

/// The arcs of input edges inside one intrinsic triangle, implied by its three normal
/// coordinates (`n[s]` for the side opposite corner `s`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct TriangleArcs {
    /// `n⁺` per side: the crossings on side `s`.
    pub crossings: [i64; 3],
    /// Corner arcs around each corner.
    pub corner: [i64; 3],
    /// Arcs emanating from each corner to the opposite side (at most one corner has any).
    pub emanating: [i64; 3],
}

impl TriangleArcs {
    /// Decomposes the crossings of the three sides into corner and emanating arcs.
    pub fn new(n: [i64; 3]) -> Self {
        let p = n.map(|x| x.max(0));
        let emanating: [i64; 3] =
            std::array::from_fn(|c| (p[c] - p[(c + 1) % 3] - p[(c + 2) % 3]).max(0));
        let corner = std::array::from_fn(|c| {
            let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
            (p[c1] + p[c2] - p[c] - emanating[c1] - emanating[c2] + emanating[c]) / 2
        });
        Self {
            crossings: p,
            corner,
            emanating,
        }
    }

    #[cfg(test)]
    /// Whether the normal coordinates describe arcs that can exist: nonnegative whole counts
    /// (the crossings of the three sides have the parity the arcs need) and at most one corner
    /// with emanating arcs.
    pub fn is_valid(&self) -> bool {
        let p = self.crossings;
        let e = self.emanating;
        let parity_ok = (0..3).all(|c| {
            let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
            (p[c1] + p[c2] - p[c] - e[c1] - e[c2] + e[c]).rem_euclid(2) == 0
        });
        parity_ok
            && self.corner.iter().all(|&a| a >= 0)
            && e.iter().filter(|&&x| x > 0).count() <= 1
    }

    /// What crosses side `s` at position `p` (0-based from the side's first corner `s + 1`).
    pub fn arc_at(&self, s: usize, p: i64) -> ArcAt {
        let (s1, s2) = ((s + 1) % 3, (s + 2) % 3);
        if p < self.corner[s1] {
            ArcAt::Corner {
                corner: s1,
                index: p,
            }
        } else if p < self.corner[s1] + self.emanating[s] {
            ArcAt::Emanating {
                corner: s,
                index: p - self.corner[s1],
            }
        } else {
            ArcAt::Corner {
                corner: s2,
                index: self.crossings[s] - 1 - p,
            }
        }
    }
}

/// The arc through one crossing of a side, see [`TriangleArcs::arc_at`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ArcAt {
    /// The `index`-th corner arc around `corner`, counted from the corner outwards.
    Corner { corner: usize, index: i64 },
    /// The `index`-th arc emanating from `corner`, counted counter-clockwise around it.
    Emanating { corner: usize, index: i64 },
}

/// The normal coordinates of a flip of the diagonal `i–j` of the quadrilateral made of the
/// triangles `T1 = (i, j, k)` and `T2 = (j, i, l)` into `k–l`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct FlipUpdate {
    /// Normal coordinate of the new edge `k–l`.
    pub new_edge: i64,
    /// How many input edge ends at `k` lie counter-clockwise from `k→i` (inclusive) to `k→l`
    /// (exclusive): the roundabout of `k→l` is that of `k→i` advanced by this.
    pub advance_at_k: i64,
    /// The same at `l`, from `l→j` to `l→k`.
    pub advance_at_l: i64,
}

/// The flip of the diagonal `i–j` (see [`FlipUpdate`]). `t1` and `t2` are the arcs of the two
/// triangles with their corners named; `n_ij` the diagonal's coordinate; `ki_along` and
/// `lj_along` whether the sides `k–i` and `l–j` lie along input edges.
///
/// Every arc inside the quadrilateral is a straight chord; `k–l` crosses exactly the chords
/// that separate `k` from `l`: the corner arcs of `k` and `l`, the arcs emanating from `i` or
/// `j`, the diagonal itself if it lies along an input edge, and the chords through `i–j` that
/// join a corner arc of `i` on one side to a corner arc of `j` on the other. A chord emanating
/// from `k` that continues as an arc emanating from `l` is an input edge `k–l`: the new edge lies
/// along it.
pub(crate) fn flip_update(
    t1: &QuadTriangle,
    t2: &QuadTriangle,
    n_ij: i64,
    ki_along: bool,
    lj_along: bool,
) -> FlipUpdate {
    let n = n_ij.max(0);
    // Positions along i–j, counted from i: T1 has a_i¹ | e_k¹ | a_j¹, T2 has a_i² | e_l² | a_j².
    let k_from = t1.corner_i;
    let k_to = t1.corner_i + t1.emanating_opposite;
    let l_from = t2.corner_i;
    let l_to = t2.corner_i + t2.emanating_opposite;
    let along_kl = k_from.max(l_from) < k_to.min(l_to);
    let new_edge = if along_kl {
        ALONG_INPUT_EDGE
    } else {
        t1.corner_opposite
            + t1.emanating_i
            + t1.emanating_j
            + t2.corner_opposite
            + t2.emanating_i
            + t2.emanating_j
            + (t1.corner_i + t2.corner_j - n).max(0)
            + (t2.corner_i + t1.corner_j - n).max(0)
            + i64::from(n_ij == ALONG_INPUT_EDGE)
    };
    // Arcs from k that continue into a corner arc of i lie between k→i and k→l; arcs from l
    // that continue into a corner arc of j lie between l→j and l→k.
    let k_side_i = (t2.corner_i - t1.corner_i).clamp(0, t1.emanating_opposite);
    let l_side_j = (l_to - (n - t1.corner_j)).clamp(0, t2.emanating_opposite);
    FlipUpdate {
        new_edge,
        advance_at_k: i64::from(ki_along) + k_side_i,
        advance_at_l: i64::from(lj_along) + l_side_j,
    }
}

/// The arcs of one triangle of a quadrilateral named after the diagonal `i–j` and the opposite
/// corner: see [`flip_update`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct QuadTriangle {
    /// Corner arcs around `i`.
    pub corner_i: i64,
    /// Corner arcs around `j`.
    pub corner_j: i64,
    /// Corner arcs around the opposite corner.
    pub corner_opposite: i64,
    /// Arcs emanating from `i`.
    pub emanating_i: i64,
    /// Arcs emanating from `j`.
    pub emanating_j: i64,
    /// Arcs emanating from the opposite corner (they cross `i–j`).
    pub emanating_opposite: i64,
}

impl QuadTriangle {
    /// Names the arcs of a triangle whose corner `opposite` faces the diagonal, with `i` at
    /// corner `i_corner` and `j` at the remaining one.
    pub fn new(arcs: &TriangleArcs, opposite: usize, i_corner: usize) -> Self {
        let j_corner = 3 - opposite - i_corner;
        Self {
            corner_i: arcs.corner[i_corner],
            corner_j: arcs.corner[j_corner],
            corner_opposite: arcs.corner[opposite],
            emanating_i: arcs.emanating[i_corner],
            emanating_j: arcs.emanating[j_corner],
            emanating_opposite: arcs.emanating[opposite],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arcs_of_a_triangle() {
        // Two corner arcs around each corner.
        let arcs = TriangleArcs::new([4, 4, 4]);
        assert_eq!(arcs.corner, [2, 2, 2]);
        assert_eq!(arcs.emanating, [0, 0, 0]);
        assert!(arcs.is_valid());
        // Side 0 crossed 5 times, sides 1 and 2 once: corner 0 emits 3 arcs.
        let arcs = TriangleArcs::new([5, 1, 1]);
        assert_eq!(arcs.emanating, [3, 0, 0]);
        assert_eq!(arcs.corner, [0, 1, 1]);
        assert_eq!(
            arcs.arc_at(0, 0),
            ArcAt::Corner {
                corner: 1,
                index: 0
            }
        );
        assert_eq!(
            arcs.arc_at(0, 2),
            ArcAt::Emanating {
                corner: 0,
                index: 1
            }
        );
        assert_eq!(
            arcs.arc_at(0, 4),
            ArcAt::Corner {
                corner: 2,
                index: 0
            }
        );
        // Sides along input edges count as 0.
        let arcs = TriangleArcs::new([ALONG_INPUT_EDGE, 1, 1]);
        assert_eq!(arcs.corner, [1, 0, 0]);
        // Odd total without an emanating corner: impossible.
        assert!(!TriangleArcs::new([1, 1, 1]).is_valid());
    }

    #[test]
    fn flipping_an_input_edge_gives_one_crossing() {
        // Two input triangles: every side along an input edge.
        let arcs = TriangleArcs::new([ALONG_INPUT_EDGE; 3]);
        let t = QuadTriangle::new(&arcs, 0, 1);
        let update = flip_update(&t, &t, ALONG_INPUT_EDGE, true, true);
        assert_eq!(update.new_edge, 1);
        assert_eq!(update.advance_at_k, 1);
        assert_eq!(update.advance_at_l, 1);
    }

    #[test]
    fn flipping_back_restores_the_input_edge() {
        // After one flip, the quadrilateral k, i, l, j (sides along input edges) has diagonal
        // k–l crossed once; each triangle has one arc emanating from the corner facing it.
        let arcs = TriangleArcs::new([1, ALONG_INPUT_EDGE, ALONG_INPUT_EDGE]);
        assert_eq!(arcs.emanating, [1, 0, 0]);
        let t = QuadTriangle::new(&arcs, 0, 1);
        let update = flip_update(&t, &t, 1, true, true);
        assert_eq!(update.new_edge, ALONG_INPUT_EDGE);
        assert_eq!(update.advance_at_k, 1);
    }
}
