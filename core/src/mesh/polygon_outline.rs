//! [`PolygonOutline`]: a polygon seen along its vector area — its corners projected to 2D
//! coordinates in the plane orthogonal to the vector area — and what that view decides: whether
//! the polygon folds over itself (two of its sides cross), whether it is convex, and a
//! triangulation by its own corners (ear clipping) for polygons that are not star-shaped around
//! their corner average.

use crate::geometry::{cross, dot, norm, scale, sub};

/// A polygon's corners in 2D coordinates of the plane orthogonal to its vector area, counter-
/// clockwise seen from the side the vector area points to (units of the input's lengths).
pub(crate) struct PolygonOutline {
    points: Vec<[f64; 2]>,
}

impl PolygonOutline {
    /// The outline of the polygon with corners `corners` and (non-zero) vector area `area`.
    pub(crate) fn new(corners: &[[f64; 3]], area: [f64; 3]) -> Self {
        let normal = scale(area, 1.0 / norm(area));
        // Any unit vector orthogonal to the normal, then the third axis by a cross product.
        let helper = if normal[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let u = cross(helper, normal);
        let u = scale(u, 1.0 / norm(u));
        let v = cross(normal, u);
        let origin = corners[0];
        let points = corners
            .iter()
            .map(|&p| {
                let d = sub(p, origin);
                [dot(d, u), dot(d, v)]
            })
            .collect();
        Self { points }
    }

    /// The first pair of sides `(c, d)`, `c < d`, that are not neighbours and meet (side `c`
    /// joins corner `c` to corner `c + 1`): the polygon folds over itself. `None` for a simple
    /// polygon.
    pub(crate) fn crossing_sides(&self) -> Option<(usize, usize)> {
        let n = self.points.len();
        for c in 0..n {
            for d in c + 2..n {
                if c == 0 && d == n - 1 {
                    continue;
                }
                let (a0, a1) = (self.points[c], self.points[(c + 1) % n]);
                let (b0, b1) = (self.points[d], self.points[(d + 1) % n]);
                if segments_meet(a0, a1, b0, b1) {
                    return Some((c, d));
                }
            }
        }
        None
    }

    /// Whether every corner turns left (a strictly convex polygon; collinear corners count as
    /// not convex).
    pub(crate) fn is_convex(&self) -> bool {
        let n = self.points.len();
        (0..n).all(|c| {
            turn(
                self.points[(c + n - 1) % n],
                self.points[c],
                self.points[(c + 1) % n],
            ) > 0.0
        })
    }

    /// A triangulation of a simple polygon by its own corners (ear clipping: `n − 2` triangles
    /// of corner indices, each counter-clockwise), or `None` if no ear is found (a polygon that
    /// is not simple, or flat up to rounding).
    pub(crate) fn ear_triangles(&self) -> Option<Vec<[usize; 3]>> {
        let mut remaining: Vec<usize> = (0..self.points.len()).collect();
        let mut triangles = Vec::with_capacity(self.points.len() - 2);
        while remaining.len() > 3 {
            let m = remaining.len();
            let ear = (0..m).find(|&i| {
                let [a, b, c] = [
                    remaining[(i + m - 1) % m],
                    remaining[i],
                    remaining[(i + 1) % m],
                ];
                let [pa, pb, pc] = [self.points[a], self.points[b], self.points[c]];
                turn(pa, pb, pc) > 0.0
                    && remaining
                        .iter()
                        .filter(|&&k| k != a && k != b && k != c)
                        .all(|&k| !inside_or_on(self.points[k], pa, pb, pc))
            })?;
            triangles.push([
                remaining[(ear + m - 1) % m],
                remaining[ear],
                remaining[(ear + 1) % m],
            ]);
            remaining.remove(ear);
        }
        triangles.push([remaining[0], remaining[1], remaining[2]]);
        Some(triangles)
    }
}

/// Twice the signed area of the triangle `(a, b, c)`: positive when it turns left at `b`.
fn turn(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether the closed segments `a0a1` and `b0b1` share a point.
fn segments_meet(a0: [f64; 2], a1: [f64; 2], b0: [f64; 2], b1: [f64; 2]) -> bool {
    let (d1, d2) = (turn(b0, b1, a0), turn(b0, b1, a1));
    let (d3, d4) = (turn(a0, a1, b0), turn(a0, a1, b1));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |p: [f64; 2], q0: [f64; 2], q1: [f64; 2], side: f64| {
        side == 0.0
            && p[0] >= q0[0].min(q1[0])
            && p[0] <= q0[0].max(q1[0])
            && p[1] >= q0[1].min(q1[1])
            && p[1] <= q0[1].max(q1[1])
    };
    on(a0, b0, b1, d1) || on(a1, b0, b1, d2) || on(b0, a0, a1, d3) || on(b1, a0, a1, d4)
}

/// Whether `p` lies in the closed counter-clockwise triangle `(a, b, c)`.
fn inside_or_on(p: [f64; 2], a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    turn(a, b, p) >= 0.0 && turn(b, c, p) >= 0.0 && turn(c, a, p) >= 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::polygon_vector_area;

    fn outline(points: &[[f64; 3]]) -> PolygonOutline {
        PolygonOutline::new(points, polygon_vector_area(points))
    }

    #[test]
    fn a_notched_square_is_simple_not_convex_and_ear_clipped_into_three_left_turns() {
        let notch = [
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [4.0, 4.0, 0.0],
            [2.0, 1.0, 0.0],
            [0.0, 4.0, 0.0],
        ];
        let o = outline(&notch);
        assert_eq!(o.crossing_sides(), None);
        assert!(!o.is_convex());
        let triangles = o.ear_triangles().unwrap();
        assert_eq!(triangles.len(), 3);
        let area: f64 = triangles
            .iter()
            .map(|t| turn(o.points[t[0]], o.points[t[1]], o.points[t[2]]) / 2.0)
            .sum();
        // 16 − the notch's triangle (4,4)-(2,1)-(0,4) of area 6.
        assert!((area - 10.0).abs() < 1e-12, "{area}");
        assert!(triangles
            .iter()
            .all(|t| turn(o.points[t[0]], o.points[t[1]], o.points[t[2]]) > 0.0));
    }

    #[test]
    fn a_pentagram_crosses_and_a_bent_square_is_convex() {
        let pentagram: Vec<[f64; 3]> = (0..5)
            .map(|k| {
                let angle = (144.0 * k as f64).to_radians();
                [angle.cos(), angle.sin(), 0.0]
            })
            .collect();
        let o = outline(&pentagram);
        assert_eq!(o.crossing_sides(), Some((0, 2)));
        let square = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.1],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.1],
        ];
        let o = outline(&square);
        assert_eq!(o.crossing_sides(), None);
        assert!(o.is_convex());
    }
}
