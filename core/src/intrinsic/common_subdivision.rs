//! [`CommonSubdivision`]: the overlay of an input mesh and an intrinsic triangulation of it —
//! polygons that each lie in one input face and one intrinsic face — and what it gives: the
//! area each intrinsic face covers of each input face.

use super::crossings::Crossings;
use super::error::IntrinsicError;
use super::normal_coordinates::TriangleArcs;
use super::surface_location::{location_barycentric, segment_point_barycentric, InputLocation};
use super::triangulation::IntrinsicTriangulation;
use crate::{TriangleMesh, NO_FACE};

/// The common subdivision of an input mesh and an intrinsic triangulation: every connected
/// piece of (input face ∩ intrinsic face) is a **cell**, a convex polygon bounded by pieces of
/// input and intrinsic edges. Each cell has an input face, an intrinsic face and corners given
/// by barycentric coordinates in both; its corners are vertices (input or inserted) and
/// crossings of an input edge with an intrinsic edge. Cells tile every input face and every
/// intrinsic face exactly once.
///
/// Built by [`IntrinsicTriangulation::common_subdivision`]: the integer coordinates say exactly
/// which cells there are and how they meet; the positions of the crossings come from laying out
/// the intrinsic faces along each input edge from the edge lengths (so the two sets of
/// barycentric coordinates of a corner agree to round-off, not bit for bit).
///
/// Areas are in the input's units², measured in the input face (signed: an inverted cell, which
/// only round-off can make, counts negatively, so the cells of a face always add up to its area).
#[derive(Debug, Clone)]
pub struct CommonSubdivision {
    pub(crate) input_faces: Vec<[usize; 3]>,
    pub(crate) input_edges: Vec<[usize; 2]>,
    pub(crate) intrinsic_faces: Vec<[usize; 3]>,
    /// Whether side `s` of an intrinsic face is its edge's reference halfedge.
    pub(crate) reference_sides: Vec<[bool; 3]>,
    pub(crate) vertex_locations: Vec<InputLocation>,
    pub(crate) slot_input_edge: Vec<usize>,
    pub(crate) slot_sigma: Vec<f64>,
    pub(crate) slot_t: Vec<f64>,
    pub(crate) cell_input_face: Vec<usize>,
    pub(crate) cell_intrinsic_face: Vec<usize>,
    pub(crate) cell_offsets: Vec<usize>,
    /// Corner codes: `c < 3` is corner `c` of the cell's intrinsic face; otherwise
    /// `3 + 3 · slot + side`, a crossing on side `side` of the intrinsic face.
    pub(crate) cell_corners: Vec<usize>,
    pub(crate) cell_area: Vec<f64>,
    pub(crate) input_face_cells: (Vec<usize>, Vec<usize>),
    pub(crate) intrinsic_face_cells: (Vec<usize>, Vec<usize>),
    pub(crate) overlaps: (Vec<usize>, Vec<Overlap>),
}

/// The part of an input face covered by one intrinsic face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Overlap {
    /// The intrinsic face.
    pub intrinsic_face: usize,
    /// Area of the overlap (units²), the sum of the cells they share.
    pub area: f64,
}

/// One cell of a [`CommonSubdivision`], with its corners counter-clockwise.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    /// Input face containing the cell.
    pub input_face: usize,
    /// Intrinsic face containing the cell.
    pub intrinsic_face: usize,
    /// Area (units², measured in the input face; see [`CommonSubdivision`]).
    pub area: f64,
    /// Barycentric coordinates of each corner in the input face.
    pub input_corners: Vec<[f64; 3]>,
    /// Barycentric coordinates of each corner in the intrinsic face.
    pub intrinsic_corners: Vec<[f64; 3]>,
}

impl IntrinsicTriangulation {
    /// The common subdivision of `mesh` (the input this triangulation was built from) and this
    /// triangulation. Traces every input edge once: linear in the number of cells.
    ///
    /// Fails with [`IntrinsicError::InputMismatch`] for another mesh, and with
    /// [`IntrinsicError::Inconsistent`] if the traced crossings do not fit together.
    pub fn common_subdivision(
        &self,
        mesh: &TriangleMesh,
    ) -> Result<CommonSubdivision, IntrinsicError> {
        self.check_input(mesh)?;
        let crossings = self.trace_all_crossings(mesh)?;
        let mut sub = CommonSubdivision {
            input_faces: mesh.faces().to_vec(),
            input_edges: mesh.edges().to_vec(),
            intrinsic_faces: self.faces.clone(),
            reference_sides: (0..self.face_count())
                .map(|t| {
                    std::array::from_fn(|s| {
                        self.edge_halfedge[self.halfedge_edge[3 * t + s]] == 3 * t + s
                    })
                })
                .collect(),
            vertex_locations: self.vertex_locations.clone(),
            slot_input_edge: crossings.input_edge.clone(),
            slot_sigma: crossings.sigma.clone(),
            slot_t: crossings.t.clone(),
            cell_input_face: Vec::new(),
            cell_intrinsic_face: Vec::new(),
            cell_offsets: vec![0],
            cell_corners: Vec::new(),
            cell_area: Vec::new(),
            input_face_cells: (Vec::new(), Vec::new()),
            intrinsic_face_cells: (Vec::new(), Vec::new()),
            overlaps: (Vec::new(), Vec::new()),
        };
        for t in 0..self.face_count() {
            self.push_face_cells(t, &crossings, mesh, &mut sub);
        }
        sub.measure_cells(&mesh.face_areas())?;
        sub.input_face_cells = group_by(&sub.cell_input_face, mesh.face_count());
        sub.intrinsic_face_cells = group_by(&sub.cell_intrinsic_face, self.face_count());
        sub.overlaps = sub.collect_overlaps();
        Ok(sub)
    }

    /// Appends the cells of intrinsic face `t`: around each corner, the strips between its
    /// corner arcs; in the middle, one polygon, or a fan of pieces between the arcs emanating
    /// from the one corner that has them.
    fn push_face_cells(
        &self,
        t: usize,
        crossings: &Crossings,
        mesh: &TriangleMesh,
        sub: &mut CommonSubdivision,
    ) {
        let arcs = TriangleArcs::new(self.face_normals(t));
        let n = arcs.crossings;
        let slot = |s: usize, p: i64| 3 + 3 * crossings.slot(self, 3 * t + s, p) + s;
        let face_of = |s: usize, q: i64| crossings.segment_face_of(self, mesh, 3 * t + s, q);
        let mut push = |corners: &[usize], input_face: usize| {
            sub.cell_corners.extend_from_slice(corners);
            sub.cell_offsets.push(sub.cell_corners.len());
            sub.cell_input_face.push(input_face);
            sub.cell_intrinsic_face.push(t);
        };
        // The corner of the middle region at corner c: c itself, or its innermost corner arc.
        let middle_corner = |c: usize, out: &mut Corners| {
            let (s_in, s_out) = ((c + 1) % 3, (c + 2) % 3);
            match arcs.corner[c] {
                0 => out.push(c),
                a => {
                    out.push(slot(s_in, n[s_in] - a));
                    out.push(slot(s_out, a - 1));
                }
            }
        };
        for c in 0..3 {
            let (s_in, s_out) = ((c + 1) % 3, (c + 2) % 3);
            for m in 0..arcs.corner[c] {
                let mut corners = Corners::default();
                if m == 0 {
                    corners.push(c);
                } else {
                    corners.push(slot(s_out, m - 1));
                }
                corners.push(slot(s_out, m));
                corners.push(slot(s_in, n[s_in] - 1 - m));
                if m > 0 {
                    corners.push(slot(s_in, n[s_in] - m));
                }
                push(corners.as_slice(), face_of(s_out, m));
            }
        }
        match (0..3).find(|&c| arcs.emanating[c] > 0) {
            None => {
                let mut corners = Corners::default();
                for c in 0..3 {
                    middle_corner(c, &mut corners);
                }
                push(corners.as_slice(), face_of(2, arcs.corner[0]));
            }
            Some(c) => {
                let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
                let fan = arcs.emanating[c];
                let ray = |m: i64| slot(c, arcs.corner[c1] + m);
                for m in 0..=fan {
                    let mut corners = Corners::default();
                    corners.push(c);
                    if m == 0 {
                        middle_corner(c1, &mut corners);
                    } else {
                        corners.push(ray(m - 1));
                    }
                    if m == fan {
                        middle_corner(c2, &mut corners);
                    } else {
                        corners.push(ray(m));
                    }
                    push(corners.as_slice(), face_of(c, arcs.corner[c1] + m));
                }
            }
        }
    }
}

/// The corner codes of one cell while it is built (at most 6: a triangle cut by three corner
/// arcs).
#[derive(Debug, Default)]
struct Corners {
    codes: [usize; 6],
    len: usize,
}

impl Corners {
    fn push(&mut self, code: usize) {
        self.codes[self.len] = code;
        self.len += 1;
    }

    fn as_slice(&self) -> &[usize] {
        &self.codes[..self.len]
    }
}

impl CommonSubdivision {
    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.cell_input_face.len()
    }

    /// Cell `i` with the barycentric coordinates of its corners.
    pub fn cell(&self, i: usize) -> Cell {
        let (input_face, intrinsic_face) = (self.cell_input_face[i], self.cell_intrinsic_face[i]);
        let codes = &self.cell_corners[self.cell_offsets[i]..self.cell_offsets[i + 1]];
        Cell {
            input_face,
            intrinsic_face,
            area: self.cell_area[i],
            input_corners: codes
                .iter()
                .map(|&code| {
                    self.input_barycentric(code, intrinsic_face, input_face)
                        .unwrap_or([f64::NAN; 3])
                })
                .collect(),
            intrinsic_corners: codes
                .iter()
                .map(|&code| self.intrinsic_barycentric(code, intrinsic_face))
                .collect(),
        }
    }

    /// The cells inside input face `f`.
    pub fn input_face_cells(&self, f: usize) -> &[usize] {
        let (offsets, cells) = &self.input_face_cells;
        &cells[offsets[f]..offsets[f + 1]]
    }

    /// The cells inside intrinsic face `t`.
    pub fn intrinsic_face_cells(&self, t: usize) -> &[usize] {
        let (offsets, cells) = &self.intrinsic_face_cells;
        &cells[offsets[t]..offsets[t + 1]]
    }

    /// The intrinsic faces overlapping input face `f`, each once, with the area they cover of it
    /// (sorted by intrinsic face; the areas add up to `f`'s area). The weights for showing a
    /// per-intrinsic-face quantity on the input by area averaging are `area / area(f)`.
    pub fn input_face_overlaps(&self, f: usize) -> &[Overlap] {
        let (offsets, overlaps) = &self.overlaps;
        &overlaps[offsets[f]..offsets[f + 1]]
    }

    /// Number of input faces.
    pub fn input_face_count(&self) -> usize {
        self.input_faces.len()
    }

    /// Number of intrinsic faces.
    pub fn intrinsic_face_count(&self) -> usize {
        self.intrinsic_faces.len()
    }

    /// Barycentric coordinates of a cell corner in the intrinsic face `t`.
    pub(crate) fn intrinsic_barycentric(&self, code: usize, t: usize) -> [f64; 3] {
        let mut bary = [0.0; 3];
        if code < 3 {
            bary[code] = 1.0;
        } else {
            let (slot, side) = ((code - 3) / 3, (code - 3) % 3);
            let sigma = self.slot_sigma[slot];
            let sigma = if self.reference_sides[t][side] {
                sigma
            } else {
                1.0 - sigma
            };
            bary[(side + 1) % 3] = 1.0 - sigma;
            bary[(side + 2) % 3] = sigma;
        }
        bary
    }

    /// Barycentric coordinates of a cell corner in input face `f` (`None` if the corner is not
    /// on `f`, which construction rules out).
    pub(crate) fn input_barycentric(&self, code: usize, t: usize, f: usize) -> Option<[f64; 3]> {
        let face = self.input_faces[f];
        if code >= 3 {
            let slot = (code - 3) / 3;
            let [a, b] = self.input_edges[self.slot_input_edge[slot]];
            return segment_point_barycentric(face, a, b, self.slot_t[slot]);
        }
        location_barycentric(
            self.vertex_locations[self.intrinsic_faces[t][code]],
            f,
            &self.input_faces,
            &self.input_edges,
        )
    }

    /// Areas of all cells (in their input faces); fails if a corner is not on its cell's face.
    fn measure_cells(&mut self, input_areas: &[f64]) -> Result<(), IntrinsicError> {
        self.cell_area = Vec::with_capacity(self.cell_count());
        let mut corners = Vec::with_capacity(6);
        for i in 0..self.cell_count() {
            let (f, t) = (self.cell_input_face[i], self.cell_intrinsic_face[i]);
            if f == NO_FACE {
                return Err(IntrinsicError::Inconsistent(format!(
                    "a cell of intrinsic face {t} lies in no input face"
                )));
            }
            corners.clear();
            for &code in &self.cell_corners[self.cell_offsets[i]..self.cell_offsets[i + 1]] {
                let bary = self.input_barycentric(code, t, f).ok_or_else(|| {
                    IntrinsicError::Inconsistent(format!(
                        "a corner of a cell of intrinsic face {t} is not on input face {f}"
                    ))
                })?;
                corners.push(bary);
            }
            self.cell_area
                .push(2.0 * input_areas[f] * signed_area(&corners));
        }
        Ok(())
    }

    /// For each input face, its cells merged by intrinsic face.
    fn collect_overlaps(&self) -> (Vec<usize>, Vec<Overlap>) {
        let mut offsets = vec![0];
        let mut overlaps: Vec<Overlap> = Vec::with_capacity(self.cell_count());
        let mut scratch: Vec<(usize, f64)> = Vec::new();
        for f in 0..self.input_face_count() {
            scratch.clear();
            scratch.extend(
                self.input_face_cells(f)
                    .iter()
                    .map(|&i| (self.cell_intrinsic_face[i], self.cell_area[i])),
            );
            scratch.sort_by_key(|&(t, _)| t);
            for &(t, area) in &scratch {
                let same = overlaps.len() > offsets[f]
                    && overlaps.last().is_some_and(|last| last.intrinsic_face == t);
                match overlaps.last_mut() {
                    Some(last) if same => last.area += area,
                    _ => overlaps.push(Overlap {
                        intrinsic_face: t,
                        area,
                    }),
                }
            }
            offsets.push(overlaps.len());
        }
        (offsets, overlaps)
    }
}

/// Signed area of a polygon given by the barycentric coordinates of its corners, relative to
/// twice its face's area: half the shoelace sum over `(b1, b2)` (the whole face has `1/2`).
pub(crate) fn signed_area(corners: &[[f64; 3]]) -> f64 {
    let n = corners.len();
    let twice: f64 = (0..n)
        .map(|i| {
            let (p, q) = (corners[i], corners[(i + 1) % n]);
            p[1] * q[2] - p[2] * q[1]
        })
        .sum();
    twice / 2.0
}

/// `(offsets, items)`: the indices `i` with `keys[i] = k` at `items[offsets[k]..offsets[k + 1]]`,
/// ascending.
fn group_by(keys: &[usize], key_count: usize) -> (Vec<usize>, Vec<usize>) {
    let mut offsets = vec![0; key_count + 1];
    for &k in keys {
        offsets[k + 1] += 1;
    }
    for k in 0..key_count {
        offsets[k + 1] += offsets[k];
    }
    let mut next = offsets.clone();
    let mut items = vec![0; keys.len()];
    for (i, &k) in keys.iter().enumerate() {
        items[next[k]] = i;
        next[k] += 1;
    }
    (offsets, items)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::icosphere;
    use crate::geometry::{norm, sub};
    use crate::intrinsic::length_geometry::layout;
    use crate::intrinsic::test_meshes::non_delaunay_meshes;

    /// Position of a barycentric point in the input face (3D).
    fn input_position(mesh: &TriangleMesh, f: usize, b: [f64; 3]) -> [f64; 3] {
        let p = mesh.faces()[f].map(|v| mesh.positions()[v]);
        std::array::from_fn(|k| b[0] * p[0][k] + b[1] * p[1][k] + b[2] * p[2][k])
    }

    /// Position of a barycentric point in the intrinsic face laid out flat (2D).
    fn intrinsic_position(tri: &IntrinsicTriangulation, t: usize, b: [f64; 3]) -> [f64; 2] {
        let p = layout(tri.face_lengths(t));
        std::array::from_fn(|k| b[0] * p[0][k] + b[1] * p[1][k] + b[2] * p[2][k])
    }

    #[test]
    fn the_input_is_its_own_subdivision() {
        let mesh = icosphere(1);
        let tri = IntrinsicTriangulation::new(&mesh).unwrap();
        let overlay = tri.common_subdivision(&mesh).unwrap();
        assert_eq!(overlay.cell_count(), mesh.face_count());
        for f in 0..mesh.face_count() {
            let overlaps = overlay.input_face_overlaps(f);
            assert_eq!(overlaps.len(), 1);
            assert_eq!(overlaps[0].intrinsic_face, f);
            assert!((overlaps[0].area - mesh.face_area(f)).abs() < 1e-15);
        }
    }

    /// Cells tile every input face and every intrinsic face, and each cell has the same shape
    /// seen from both (its sides have the same lengths in the input face and the intrinsic one).
    #[test]
    fn cells_tile_both_triangulations() {
        for (name, mesh) in non_delaunay_meshes() {
            let mut tri = IntrinsicTriangulation::new(&mesh).unwrap();
            let flips = tri.flip_to_delaunay().unwrap();
            assert!(flips > 0, "{name}: nothing flipped");
            let overlay = tri.common_subdivision(&mesh).unwrap();
            let scale = mesh.total_area().sqrt();
            let mut input_sums = vec![0.0; mesh.face_count()];
            let mut intrinsic_sums = vec![0.0; tri.face_count()];
            for i in 0..overlay.cell_count() {
                let cell = overlay.cell(i);
                let (f, t) = (cell.input_face, cell.intrinsic_face);
                input_sums[f] += cell.area;
                let intrinsic_area = 2.0 * tri.face_area(t) * signed_area(&cell.intrinsic_corners);
                intrinsic_sums[t] += intrinsic_area;
                assert!(
                    cell.area > -1e-14 * scale * scale,
                    "{name}: cell {i} inverted"
                );
                assert!(
                    (cell.area - intrinsic_area).abs() < 1e-12 * scale * scale,
                    "{name}: cell {i}"
                );
                let k = cell.input_corners.len();
                for m in 0..k {
                    let (a, b) = (cell.input_corners[m], cell.input_corners[(m + 1) % k]);
                    let input = norm(sub(
                        input_position(&mesh, f, a),
                        input_position(&mesh, f, b),
                    ));
                    let (a, b) = (
                        cell.intrinsic_corners[m],
                        cell.intrinsic_corners[(m + 1) % k],
                    );
                    let (p, q) = (
                        intrinsic_position(&tri, t, a),
                        intrinsic_position(&tri, t, b),
                    );
                    let intrinsic = (p[0] - q[0]).hypot(p[1] - q[1]);
                    assert!(
                        (input - intrinsic).abs() < 1e-12 * scale,
                        "{name}: cell {i} side {m}: {input} vs {intrinsic}"
                    );
                }
            }
            for (f, &sum) in input_sums.iter().enumerate() {
                let area = mesh.face_area(f);
                assert!(
                    (sum - area).abs() < 1e-13 * area.max(scale * scale),
                    "{name}: input face {f}"
                );
                let covered: f64 = overlay.input_face_overlaps(f).iter().map(|o| o.area).sum();
                assert!(
                    (covered - area).abs() < 1e-13 * area.max(scale * scale),
                    "{name}: input face {f}"
                );
            }
            for (t, &sum) in intrinsic_sums.iter().enumerate() {
                let area = tri.face_area(t);
                assert!(
                    (sum - area).abs() < 1e-13 * area.max(scale * scale),
                    "{name}: intrinsic face {t}"
                );
            }
        }
    }
}
