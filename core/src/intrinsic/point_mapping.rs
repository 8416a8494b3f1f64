//! Mapping points between the input surface and the intrinsic triangulation through the cells
//! of a [`CommonSubdivision`].
//!
//! A cell lies flat in both its input face and its intrinsic face, so the map between the two
//! is affine on it. It is fixed by three corners of the cell (the three spanning the largest
//! area in the input face, so that it is well conditioned), and its inverse is used the other
//! way: a point mapped across and back returns to itself up to round-off.

use super::common_subdivision::CommonSubdivision;
use super::error::IntrinsicError;
use super::surface_location::TrianglePoint;

/// Which side of the correspondence a point is given on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Side {
    Input,
    Intrinsic,
}

impl CommonSubdivision {
    /// The point of the intrinsic triangulation at the input point `point` (an input face and
    /// barycentric coordinates in it). Fails on a face out of range or non-finite coordinates.
    pub fn to_intrinsic(&self, point: TrianglePoint) -> Result<TrianglePoint, IntrinsicError> {
        self.map(point, Side::Input).map(|(_, q)| q)
    }

    /// [`CommonSubdivision::to_intrinsic`] with the cell the point was mapped through: the cell
    /// of its input face it lies in (the deepest inside, for a point on a cell's side), whose
    /// isometry [`CommonSubdivision::to_input_displacement`] uses to carry tangent vectors of the
    /// intrinsic face to the input face at that point.
    pub fn locate_on_intrinsic(
        &self,
        point: TrianglePoint,
    ) -> Result<(usize, TrianglePoint), IntrinsicError> {
        self.map(point, Side::Input)
    }

    /// The input point at the point `point` of the intrinsic triangulation (an intrinsic face
    /// and barycentric coordinates in it). Fails on a face out of range or non-finite
    /// coordinates.
    pub fn to_input(&self, point: TrianglePoint) -> Result<TrianglePoint, IntrinsicError> {
        self.map(point, Side::Intrinsic).map(|(_, q)| q)
    }

    /// A tangent vector of the intrinsic face of cell `cell`, given as a displacement of
    /// barycentric coordinates in that face (three components summing to 0), as the same vector
    /// in the cell's input face (its displacement of barycentric coordinates there). The map is
    /// the linear part of the cell's isometry between the two faces, so lengths and angles are
    /// kept: this is how a vector per intrinsic face is drawn on the input. `None` for a cell
    /// index out of range.
    pub fn to_input_displacement(&self, cell: usize, displacement: [f64; 3]) -> Option<[f64; 3]> {
        self.map_displacement(cell, displacement, Side::Intrinsic)
    }

    /// The inverse of [`CommonSubdivision::to_input_displacement`]: a displacement of
    /// barycentric coordinates in the input face of cell `cell` as one in its intrinsic face.
    pub fn to_intrinsic_displacement(
        &self,
        cell: usize,
        displacement: [f64; 3],
    ) -> Option<[f64; 3]> {
        self.map_displacement(cell, displacement, Side::Input)
    }

    fn map_displacement(&self, cell: usize, d: [f64; 3], from: Side) -> Option<[f64; 3]> {
        if cell >= self.cell_count() {
            return None;
        }
        let input = self.corners_2d(cell, Side::Input);
        let intrinsic = self.corners_2d(cell, Side::Intrinsic);
        let frame = largest_triangle(&input);
        let (source, target) = match from {
            Side::Input => (&input, &intrinsic),
            Side::Intrinsic => (&intrinsic, &input),
        };
        let [a, b, c] = frame.map(|k| source[k]);
        let w = triangle_weights(
            [0.0, 0.0],
            [b[0] - a[0], b[1] - a[1]],
            [c[0] - a[0], c[1] - a[1]],
            [d[1], d[2]],
        );
        let [x, y, z] = frame.map(|k| target[k]);
        let q: [f64; 2] = std::array::from_fn(|k| w[1] * (y[k] - x[k]) + w[2] * (z[k] - x[k]));
        Some([-q[0] - q[1], q[0], q[1]])
    }

    /// The cell `point` (on side `from`) lies in and the point on the other side.
    fn map(
        &self,
        point: TrianglePoint,
        from: Side,
    ) -> Result<(usize, TrianglePoint), IntrinsicError> {
        let (face_count, cells) = match from {
            Side::Input => (self.input_face_count(), &self.input_face_cells),
            Side::Intrinsic => (self.intrinsic_face_count(), &self.intrinsic_face_cells),
        };
        if point.face >= face_count {
            return Err(IntrinsicError::NoSuchFace {
                face: point.face,
                face_count,
            });
        }
        if point.barycentric.iter().any(|x| !x.is_finite()) {
            return Err(IntrinsicError::InvalidPoint {
                face: point.face,
                barycentric: point.barycentric,
            });
        }
        let candidates = &cells.1[cells.0[point.face]..cells.0[point.face + 1]];
        let p = [point.barycentric[1], point.barycentric[2]];
        let mut best: Option<(f64, usize)> = None;
        for &i in candidates {
            let depth = inside_depth(&self.corners_2d(i, from), p);
            if best.is_none_or(|(d, _)| depth > d) {
                best = Some((depth, i));
            }
        }
        let Some((_, cell)) = best else {
            return Err(IntrinsicError::Inconsistent(format!(
                "face {} has no cells",
                point.face
            )));
        };
        let input = self.corners_2d(cell, Side::Input);
        let intrinsic = self.corners_2d(cell, Side::Intrinsic);
        let frame = largest_triangle(&input);
        let (source, target, face) = match from {
            Side::Input => (&input, &intrinsic, self.cell_intrinsic_face[cell]),
            Side::Intrinsic => (&intrinsic, &input, self.cell_input_face[cell]),
        };
        let [a, b, c] = frame.map(|k| source[k]);
        let w = triangle_weights(a, b, c, p);
        let [x, y, z] = frame.map(|k| target[k]);
        let q = [
            w[0] * x[0] + w[1] * y[0] + w[2] * z[0],
            w[0] * x[1] + w[1] * y[1] + w[2] * z[1],
        ];
        let barycentric = [1.0 - q[0] - q[1], q[0], q[1]];
        Ok((cell, TrianglePoint { face, barycentric }))
    }

    /// The corners of cell `i` as `(b1, b2)` barycentric coordinates in its face on `side`.
    fn corners_2d(&self, i: usize, side: Side) -> Vec<[f64; 2]> {
        let (f, t) = (self.cell_input_face[i], self.cell_intrinsic_face[i]);
        self.cell_corners[self.cell_offsets[i]..self.cell_offsets[i + 1]]
            .iter()
            .map(|&code| {
                let b = match side {
                    Side::Input => self.input_barycentric(code, t, f).unwrap_or([f64::NAN; 3]),
                    Side::Intrinsic => self.intrinsic_barycentric(code, t),
                };
                [b[1], b[2]]
            })
            .collect()
    }
}

/// How far `p` is inside the convex polygon `corners` (counter-clockwise): the smallest signed
/// distance to the lines of its sides, positive inside.
fn inside_depth(corners: &[[f64; 2]], p: [f64; 2]) -> f64 {
    let n = corners.len();
    let mut depth = f64::INFINITY;
    for i in 0..n {
        let (a, b) = (corners[i], corners[(i + 1) % n]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let length = d[0].hypot(d[1]);
        if length > 0.0 {
            let cross = d[0] * (p[1] - a[1]) - d[1] * (p[0] - a[0]);
            depth = depth.min(cross / length);
        }
    }
    if depth.is_nan() {
        f64::NEG_INFINITY
    } else {
        depth
    }
}

/// Indices of the three corners spanning the largest triangle.
fn largest_triangle(corners: &[[f64; 2]]) -> [usize; 3] {
    let n = corners.len();
    let mut best = ([0, 1.min(n - 1), 2.min(n - 1)], f64::NEG_INFINITY);
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let area = twice_area(corners[i], corners[j], corners[k]).abs();
                if area > best.1 {
                    best = ([i, j, k], area);
                }
            }
        }
    }
    best.0
}

fn twice_area(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Barycentric weights of `p` with respect to the triangle `(a, b, c)`.
fn triangle_weights(a: [f64; 2], b: [f64; 2], c: [f64; 2], p: [f64; 2]) -> [f64; 3] {
    let total = twice_area(a, b, c);
    let wb = twice_area(a, p, c) / total;
    let wc = twice_area(a, b, p) / total;
    [1.0 - wb - wc, wb, wc]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::intrinsic::test_meshes::non_delaunay_meshes;
    use crate::intrinsic::IntrinsicTriangulation;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn random_barycentric(rng: &mut ChaCha8Rng) -> [f64; 3] {
        let (u, v): (f64, f64) = (rng.random(), rng.random());
        let (u, v) = if u + v > 1.0 {
            (1.0 - u, 1.0 - v)
        } else {
            (u, v)
        };
        [1.0 - u - v, u, v]
    }

    #[test]
    fn points_map_there_and_back() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for (name, mesh) in non_delaunay_meshes() {
            let mut tri = IntrinsicTriangulation::new(&mesh).unwrap();
            tri.flip_to_delaunay().unwrap();
            let sub = tri.common_subdivision(&mesh).unwrap();
            for f in 0..mesh.face_count() {
                for _ in 0..4 {
                    let p = TrianglePoint {
                        face: f,
                        barycentric: random_barycentric(&mut rng),
                    };
                    let q = sub.to_intrinsic(p).unwrap();
                    assert!(
                        q.barycentric.iter().all(|&x| x > -1e-12 && x < 1.0 + 1e-12),
                        "{name}: {q:?}"
                    );
                    let back = sub.to_input(q).unwrap();
                    assert_eq!(back.face, f, "{name}");
                    for k in 0..3 {
                        assert!(
                            (back.barycentric[k] - p.barycentric[k]).abs() < 1e-12,
                            "{name}: {p:?} {back:?}"
                        );
                    }
                }
            }
            for t in 0..tri.face_count() {
                let q = TrianglePoint {
                    face: t,
                    barycentric: random_barycentric(&mut rng),
                };
                let p = sub.to_input(q).unwrap();
                let back = sub.to_intrinsic(p).unwrap();
                assert_eq!(back.face, t, "{name}");
                for k in 0..3 {
                    assert!(
                        (back.barycentric[k] - q.barycentric[k]).abs() < 1e-12,
                        "{name}"
                    );
                }
            }
        }
    }

    /// Vectors between corners of a cell map to the same vectors, with the same length.
    #[test]
    fn displacements_keep_their_length() {
        use crate::intrinsic::length_geometry::layout;
        for (name, mesh) in non_delaunay_meshes() {
            let mut tri = IntrinsicTriangulation::new(&mesh).unwrap();
            tri.flip_to_delaunay().unwrap();
            let overlay = tri.common_subdivision(&mesh).unwrap();
            let scale = mesh.total_area().sqrt();
            for i in 0..overlay.cell_count() {
                let cell = overlay.cell(i);
                let k = cell.input_corners.len() - 1;
                let d: [f64; 3] = std::array::from_fn(|c| {
                    cell.intrinsic_corners[k][c] - cell.intrinsic_corners[0][c]
                });
                let mapped = overlay.to_input_displacement(i, d).unwrap();
                let expected: [f64; 3] =
                    std::array::from_fn(|c| cell.input_corners[k][c] - cell.input_corners[0][c]);
                let p = mesh.faces()[cell.input_face].map(|v| mesh.positions()[v]);
                let in_3d = |b: [f64; 3]| -> f64 {
                    let v: [f64; 3] =
                        std::array::from_fn(|x| b[0] * p[0][x] + b[1] * p[1][x] + b[2] * p[2][x]);
                    crate::geometry::norm(v)
                };
                let q = layout(tri.face_lengths(cell.intrinsic_face));
                let in_2d = |b: [f64; 3]| -> f64 {
                    let v: [f64; 2] =
                        std::array::from_fn(|x| b[0] * q[0][x] + b[1] * q[1][x] + b[2] * q[2][x]);
                    v[0].hypot(v[1])
                };
                let diff: [f64; 3] = std::array::from_fn(|c| mapped[c] - expected[c]);
                assert!(in_3d(diff) < 1e-12 * scale, "{name}: cell {i}");
                assert!(
                    (in_3d(mapped) - in_2d(d)).abs() < 1e-12 * scale,
                    "{name}: cell {i}"
                );
                let back = overlay.to_intrinsic_displacement(i, mapped).unwrap();
                let diff: [f64; 3] = std::array::from_fn(|c| back[c] - d[c]);
                assert!(in_2d(diff) < 1e-13 * scale, "{name}: cell {i}");
            }
            assert_eq!(
                overlay.to_input_displacement(overlay.cell_count(), [0.0; 3]),
                None
            );
        }
    }

    #[test]
    fn bad_points_are_errors() {
        let (_, mesh) = non_delaunay_meshes().remove(0);
        let tri = IntrinsicTriangulation::new(&mesh).unwrap();
        let sub = tri.common_subdivision(&mesh).unwrap();
        let far = TrianglePoint {
            face: mesh.face_count(),
            barycentric: [1.0, 0.0, 0.0],
        };
        assert!(matches!(
            sub.to_intrinsic(far),
            Err(IntrinsicError::NoSuchFace { .. })
        ));
        let nan = TrianglePoint {
            face: 0,
            barycentric: [f64::NAN, 0.0, 1.0],
        };
        assert!(matches!(
            sub.to_input(nan),
            Err(IntrinsicError::InvalidPoint { .. })
        ));
    }
}
