//! [`folded_polygons`]: polygons (faces with more than three corners) whose fan triangulation
//! folds over itself, which happens when the polygon is not convex (seen from its first
//! corner): some fan triangles then face the other way and cover area twice, so the mesh's
//! area and everything computed on it are wrong without any error.

/// How many fan-triangulated polygons fold, and the file line of the first; `None` if none
/// does. A polygon is the run of consecutive triangles with the same `face_lines` entry (one
/// polygon per line in text files; without lines nothing can be checked). A fan folds when one
/// of its triangles' normals points against the polygon's area vector (their sum).
pub(crate) fn folded_polygons(
    positions: &[[f64; 3]],
    faces: &[[usize; 3]],
    face_lines: &[usize],
) -> Option<(usize, usize)> {
    if face_lines.len() != faces.len() {
        return None;
    }
    let normal = |f: &[usize; 3]| -> Option<[f64; 3]> {
        let p = |k: usize| positions.get(f[k]).copied();
        let (a, b, c) = (p(0)?, p(1)?, p(2)?);
        let (u, v) = (sub(b, a), sub(c, a));
        Some([
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ])
    };
    let (mut count, mut first) = (0, None);
    let mut start = 0;
    while start < faces.len() {
        let line = face_lines[start];
        let end = start
            + face_lines[start..]
                .iter()
                .take_while(|&&l| l == line)
                .count();
        if end - start >= 2 {
            let normals: Option<Vec<[f64; 3]>> = faces[start..end].iter().map(normal).collect();
            if let Some(normals) = normals {
                let total = normals.iter().fold([0.0; 3], |s, n| add(s, *n));
                if normals.iter().any(|n| dot(*n, total) < 0.0) {
                    count += 1;
                    first.get_or_insert(line);
                }
            }
        }
        start = end;
    }
    first.map(|line| (count, line))
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_concave_polygon_folds_and_a_convex_one_does_not() {
        // A square with a notch: reflex corner 3, fanned from corner 0.
        let positions = [
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [4.0, 4.0, 0.0],
            [2.0, 1.0, 0.0],
            [0.0, 4.0, 0.0],
        ];
        let fan = [[0, 1, 2], [0, 2, 3], [0, 3, 4]];
        assert_eq!(folded_polygons(&positions, &fan, &[7, 7, 7]), Some((1, 7)));
        let convex = [[0, 1, 2], [0, 2, 4]];
        assert_eq!(folded_polygons(&positions, &convex, &[3, 3]), None);
        // Separate triangles (different lines) are never a polygon.
        assert_eq!(folded_polygons(&positions, &fan, &[1, 2, 3]), None);
        assert_eq!(folded_polygons(&positions, &fan, &[]), None);
    }
}
