//! Triangle geometry from the three side lengths alone: area, corner angles, cotangents, mixed
//! Voronoi shares and planar layouts. Every intrinsic quantity in this module's parent is built
//! on these functions.
//!
//! Convention throughout: `lengths[c]` is the length of the side **opposite corner `c`** (the
//! side joining corners `c + 1` and `c + 2`, indices mod 3), as in
//! [`crate::TriangleMesh::face_edges`].

/// Area of the triangle with side lengths `lengths` (units of length²), by Kahan's stable form of
/// Heron's formula (accurate to a few ulps even for needle-like triangles).
///
/// Returns 0 when the lengths violate the triangle inequality or meet it with equality (a flat
/// triangle); NaN if a length is NaN.
pub fn triangle_area(lengths: [f64; 3]) -> f64 {
    let mut l = lengths;
    // Sort descending: a ≥ b ≥ c.
    if l[0] < l[1] {
        l.swap(0, 1);
    }
    if l[1] < l[2] {
        l.swap(1, 2);
    }
    if l[0] < l[1] {
        l.swap(0, 1);
    }
    let [a, b, c] = l;
    let product = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
    0.25 * product.max(0.0).sqrt()
}

/// Whether `lengths` are finite, positive and form a triangle of positive area.
pub fn is_triangle(lengths: [f64; 3]) -> bool {
    lengths.iter().all(|&l| l.is_finite() && l > 0.0) && triangle_area(lengths) > 0.0
}

/// Cotangent of the interior angle at every corner (dimensionless):
/// `cot θ_c = (l_{c+1}² + l_{c+2}² − l_c²) / (4 A)`. Negative at an obtuse corner; infinite on a
/// flat triangle.
pub fn corner_cotangents(lengths: [f64; 3]) -> [f64; 3] {
    let four_area = 4.0 * triangle_area(lengths);
    let sq = lengths.map(|l| l * l);
    std::array::from_fn(|c| (sq[(c + 1) % 3] + sq[(c + 2) % 3] - sq[c]) / four_area)
}

/// Interior angle at every corner (radians), `atan2(4 A, l_{c+1}² + l_{c+2}² − l_c²)`: accurate
/// near 0, near π/2 and near π. The three sum to π up to round-off.
pub fn corner_angles(lengths: [f64; 3]) -> [f64; 3] {
    let four_area = 4.0 * triangle_area(lengths);
    let sq = lengths.map(|l| l * l);
    std::array::from_fn(|c| four_area.atan2(sq[(c + 1) % 3] + sq[(c + 2) % 3] - sq[c]))
}

/// The mixed Voronoi share of each corner (units of length², summing to the area): Meyer,
/// Desbrun, Schröder and Barr (2003). In a non-obtuse triangle corner `c` gets its Voronoi cell,
/// `(l_{c+1}² cot θ_{c+1} + l_{c+2}² cot θ_{c+2}) / 8`; in an obtuse triangle the obtuse corner
/// gets `A/2` and the other two `A/4`.
pub fn mixed_voronoi_shares(lengths: [f64; 3]) -> [f64; 3] {
    let area = triangle_area(lengths);
    let cot = corner_cotangents(lengths);
    match (0..3).find(|&c| cot[c] < 0.0) {
        Some(obtuse) => std::array::from_fn(|c| if c == obtuse { area / 2.0 } else { area / 4.0 }),
        None => {
            let sq = lengths.map(|l| l * l);
            std::array::from_fn(|c| {
                let (j, k) = ((c + 1) % 3, (c + 2) % 3);
                (sq[j] * cot[j] + sq[k] * cot[k]) / 8.0
            })
        }
    }
}

/// The third corner of a triangle laid out in the plane on the **left** of the directed segment
/// `a → b`: the point at distance `to_a` from `a` and `to_b` from `b`. `ab` is the length the
/// segment should have (the intrinsic edge length; the laid-out `|b − a|` only gives the
/// direction, so round-off does not accumulate along a strip of unfolded triangles).
pub(crate) fn place_left(a: [f64; 2], b: [f64; 2], ab: f64, to_a: f64, to_b: f64) -> [f64; 2] {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len = d[0].hypot(d[1]);
    let (ux, uy) = (d[0] / len, d[1] / len);
    let along = (ab * ab + to_a * to_a - to_b * to_b) / (2.0 * ab);
    let height = 2.0 * triangle_area([ab, to_b, to_a]) / ab;
    [
        a[0] + along * ux - height * uy,
        a[1] + along * uy + height * ux,
    ]
}

/// The three corners of a triangle laid out counter-clockwise in the plane: corner 1 at the
/// origin, corner 2 on the positive x axis, corner 0 above it.
pub(crate) fn layout(lengths: [f64; 3]) -> [[f64; 2]; 3] {
    let p1 = [0.0, 0.0];
    let p2 = [lengths[0], 0.0];
    let p0 = place_left(p1, p2, lengths[0], lengths[2], lengths[1]);
    [p0, p1, p2]
}

/// Length of the diagonal `k–l` of the quadrilateral made of the triangles `(i, j, k)` and
/// `(j, i, l)` glued along `i–j` (both counter-clockwise): the length of the edge that replaces
/// `i–j` when it is flipped. Arguments: `ij`, then the sides `jk`, `ki` of the first triangle and
/// `il`, `lj` of the second.
pub(crate) fn flipped_length(ij: f64, jk: f64, ki: f64, il: f64, lj: f64) -> f64 {
    let i = [0.0, 0.0];
    let j = [ij, 0.0];
    let k = place_left(i, j, ij, ki, jk);
    let l = place_left(j, i, ij, lj, il);
    (k[0] - l[0]).hypot(k[1] - l[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn right_triangle() {
        // Legs 3 and 4 at corner 0, hypotenuse 5 opposite it.
        let l = [5.0, 4.0, 3.0];
        assert_eq!(triangle_area(l), 6.0);
        let angles = corner_angles(l);
        assert!((angles[0] - PI / 2.0).abs() < 1e-15);
        assert!((angles.iter().sum::<f64>() - PI).abs() < 1e-15);
        let cot = corner_cotangents(l);
        assert!(cot[0].abs() < 1e-15);
        assert!((cot[1] - 3.0 / 4.0).abs() < 1e-15 && (cot[2] - 4.0 / 3.0).abs() < 1e-15);
        let shares = mixed_voronoi_shares(l);
        assert!((shares.iter().sum::<f64>() - 6.0).abs() < 1e-14);
        assert!((shares[0] - 3.0).abs() < 1e-14, "{shares:?}");
    }

    #[test]
    fn needle_triangle_keeps_its_area() {
        // Kahan's example a = 100000, b = 99999.99979, c = 0.00029. With the lengths as rounded
        // to f64 the exact area is 10.000000077021038 (computed with 80 digits); the textbook
        // Heron formula in f64 gives 9.99999981 (eight digits right), Kahan's form all of them.
        let area = triangle_area([100000.0, 99999.99979, 0.00029]);
        assert!(
            (area - 10.000000077021038).abs() < 4.0 * f64::EPSILON * area,
            "{area}"
        );
        assert!(is_triangle([1.0, 1.0, 1.0]));
        assert!(!is_triangle([1.0, 1.0, 2.0]));
        assert!(!is_triangle([1.0, 1.0, 3.0]));
        assert!(!is_triangle([1.0, f64::NAN, 1.0]));
    }

    #[test]
    fn layout_has_the_lengths() {
        let l = [1.3, 0.7, 0.9];
        let p = layout(l);
        for c in 0..3 {
            let (a, b) = (p[(c + 1) % 3], p[(c + 2) % 3]);
            assert!(((b[0] - a[0]).hypot(b[1] - a[1]) - l[c]).abs() < 1e-15);
        }
        // Counter-clockwise: positive signed area.
        let cross =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
        assert!((cross / 2.0 - triangle_area(l)).abs() < 1e-15);
    }

    #[test]
    fn flipped_diagonal_of_a_unit_square() {
        let d = flipped_length(2f64.sqrt(), 1.0, 1.0, 1.0, 1.0);
        assert!((d - 2f64.sqrt()).abs() < 1e-15);
        // A rhombus with a 60° angle: diagonals 1 and √3.
        let d = flipped_length(1.0, 1.0, 1.0, 1.0, 1.0);
        assert!((d - 3f64.sqrt()).abs() < 1e-15);
    }
}
