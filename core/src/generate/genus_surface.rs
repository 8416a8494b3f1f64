//! A closed surface of any genus: the boundary of a thickened plate with `g` round holes.

use super::quad_grid::{grid_cell, split_quad, Diagonal};
use crate::TriangleMesh;
use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, PI};

/// Half-thickness of the plate (cells are 2 × 2).
const HALF_THICKNESS: f64 = 0.2;
/// Radius of each hole.
const HOLE_RADIUS: f64 = 0.75;

/// Closed, connected, outward-oriented surface of genus `genus`: a plate of `max(g, 1)` square
/// cells of side 2 in a row along x (centred at the origin), with a round hole of radius 0.75
/// through each cell, thickened to `|z| ≤ 0.2` with rounded (semicircular) rims.
///
/// `resolution` is the number of segments along each cell side (rounded up to an even number,
/// at least 2). Sizes at resolution 8: 448 faces for genus 0, then 544 more per hole
/// (genus 2: 1,184 faces); doubling the resolution roughly quadruples them. For resolutions
/// 4 to 16 all angles lie between 23° and 102° (resolution 2 is coarse: 15.6° to 112.5°).
pub fn genus_surface(genus: usize, resolution: usize) -> TriangleMesh {
    let k = resolution.max(2).div_ceil(2) * 2;
    let mut sheet = if genus == 0 {
        square_sheet(k)
    } else {
        perforated_sheet(genus, k)
    };
    soften_corners(&mut sheet);
    let spacing = 2.0 / k as f64;
    let wall_layers = ((PI * HALF_THICKNESS / spacing).ceil() as usize).max(2);
    thicken(&sheet, wall_layers)
}

/// The flat sheet of [`genus_surface`] with `holes ≥ 1` holes: planar points and
/// counter-clockwise triangles (an annulus-like cell per hole, cells sharing their sides).
pub(crate) fn perforated_plate_sheet(
    holes: usize,
    resolution: usize,
) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    let k = resolution.max(2).div_ceil(2) * 2;
    let sheet = perforated_sheet(holes, k);
    (sheet.points, sheet.triangles)
}

/// A planar triangulation: points and counter-clockwise triangles.
struct Sheet {
    points: Vec<[f64; 2]>,
    triangles: Vec<[usize; 3]>,
}

/// The square `[−1, 1]²` as a `k × k` grid, each square cut along alternating diagonals.
fn square_sheet(k: usize) -> Sheet {
    let coordinate = |a: usize| -1.0 + 2.0 * a as f64 / k as f64;
    let mut points = Vec::with_capacity((k + 1) * (k + 1));
    for b in 0..=k {
        for a in 0..=k {
            points.push([coordinate(a), coordinate(b)]);
        }
    }
    let index = |a: usize, b: usize| b * (k + 1) + a;
    let mut triangles = Vec::with_capacity(2 * k * k);
    for b in 0..k {
        for a in 0..k {
            let diagonal = if (a + b) % 2 == 0 {
                Diagonal::AC
            } else {
                Diagonal::BD
            };
            triangles.extend(split_quad(grid_cell(index, a, b), diagonal));
        }
    }
    Sheet { points, triangles }
}

/// Offset along a cell side at step `t ∈ 0..=k`: points at equal angles seen from the cell
/// centre, exactly `±1` at the corners and antisymmetric, so neighbouring cells compute
/// bit-identical points on their shared side.
fn side_offset(t: usize, k: usize) -> f64 {
    let steps = 2.0 * t as f64 - k as f64;
    if t == 0 {
        -1.0
    } else if t == k {
        1.0
    } else {
        steps.signum() * (steps.abs() * PI / (4.0 * k as f64)).tan()
    }
}

/// `g` cells in a row, each an annulus between its hole circle and its square, meshed as a
/// polar grid: `4k` rays at equal angles, and layers graded towards the circle.
fn perforated_sheet(genus: usize, k: usize) -> Sheet {
    let layers = ((0.2 * k as f64).round() as usize).max(1);
    let mut points: Vec<[f64; 2]> = Vec::new();
    let mut shared: HashMap<[u64; 2], usize> = HashMap::new();
    let mut triangles = Vec::new();
    for cell in 0..genus {
        let centre = (2 * cell + 1) as f64 - genus as f64;
        // The 4k square points, counter-clockwise from the corner (1, −1).
        let mut square = Vec::with_capacity(4 * k);
        square.extend((0..k).map(|t| [1.0, side_offset(t, k)]));
        square.extend((1..=k).rev().map(|t| [side_offset(t, k), 1.0]));
        square.extend((1..=k).rev().map(|t| [-1.0, side_offset(t, k)]));
        square.extend((0..k).map(|t| [side_offset(t, k), -1.0]));
        // rings[l][j]: point j of layer l (0 = hole circle, `layers` = square).
        let mut rings = vec![Vec::with_capacity(4 * k); layers + 1];
        for &[x, y] in &square {
            let length = (x * x + y * y).sqrt();
            let circle = [HOLE_RADIUS * x / length, HOLE_RADIUS * y / length];
            for (l, ring) in rings.iter_mut().enumerate() {
                let s = (l as f64 / layers as f64).powf(1.3);
                let p = [
                    centre + circle[0] + s * (x - circle[0]),
                    circle[1] + s * (y - circle[1]),
                ];
                let index = if l == layers {
                    let p = [centre + x, y];
                    *shared.entry(p.map(f64::to_bits)).or_insert_with(|| {
                        points.push(p);
                        points.len() - 1
                    })
                } else {
                    points.push(p);
                    points.len() - 1
                };
                ring.push(index);
            }
        }
        let vertex = |l: usize, j: usize| rings[l][j % (4 * k)];
        for l in 0..layers {
            for j in 0..4 * k {
                let quad = grid_cell(vertex, l, j);
                triangles.extend(split_quad(quad, shorter_diagonal(&points, quad)));
            }
        }
    }
    Sheet { points, triangles }
}

/// The shorter diagonal of the quad `quad` of planar `points`.
fn shorter_diagonal(points: &[[f64; 2]], quad: [usize; 4]) -> Diagonal {
    Diagonal::shorter(quad, |p, q| {
        let (dx, dy) = (points[p][0] - points[q][0], points[p][1] - points[q][1]);
        dx * dx + dy * dy
    })
}

/// Boundary loops of a sheet, each with the sheet on its left (outer loop counter-clockwise,
/// hole loops clockwise).
fn boundary_loops(sheet: &Sheet) -> Vec<Vec<usize>> {
    let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
    for t in &sheet.triangles {
        for c in 0..3 {
            *directed.entry((t[c], t[(c + 1) % 3])).or_default() += 1;
        }
    }
    let mut next: HashMap<usize, usize> = directed
        .keys()
        .filter(|&&(a, b)| !directed.contains_key(&(b, a)))
        .map(|&(a, b)| (a, b))
        .collect();
    let mut starts: Vec<usize> = next.keys().copied().collect();
    starts.sort_unstable();
    let mut loops = Vec::new();
    for start in starts {
        let mut cycle = Vec::new();
        let mut v = start;
        while let Some(w) = next.remove(&v) {
            cycle.push(v);
            v = w;
        }
        if !cycle.is_empty() {
            loops.push(cycle);
        }
    }
    loops
}

/// Moves every sharp convex boundary corner (turning by more than 60°, i.e. the four corners of
/// the plate) 60% of the way towards the midpoint of its two boundary neighbours. The rounded
/// wall then turns in three steps of at most ~45° instead of one of 90°, which keeps the wall
/// triangles at the corners from becoming obtuse slivers.
fn soften_corners(sheet: &mut Sheet) {
    for cycle in boundary_loops(sheet) {
        let len = cycle.len();
        let moves: Vec<(usize, [f64; 2])> = (0..len)
            .filter_map(|i| {
                let [a, p, b] = [cycle[(i + len - 1) % len], cycle[i], cycle[(i + 1) % len]]
                    .map(|v| sheet.points[v]);
                let (u, w) = ([p[0] - a[0], p[1] - a[1]], [b[0] - p[0], b[1] - p[1]]);
                let turn = (u[0] * w[1] - u[1] * w[0]).atan2(u[0] * w[0] + u[1] * w[1]);
                (turn > PI / 3.0).then(|| {
                    let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
                    (
                        cycle[i],
                        [p[0] + 0.6 * (mid[0] - p[0]), p[1] + 0.6 * (mid[1] - p[1])],
                    )
                })
            })
            .collect();
        for (v, p) in moves {
            sheet.points[v] = p;
        }
    }
}

/// The closed surface around the sheet: top copy at `z = +h`, reversed bottom copy at `z = −h`,
/// and along every boundary loop a wall whose profile is a half circle of radius `h` bulging
/// away from the sheet, with `wall_layers` segments.
fn thicken(sheet: &Sheet, wall_layers: usize) -> TriangleMesh {
    let h = HALF_THICKNESS;
    let n = sheet.points.len();
    let mut positions: Vec<[f64; 3]> = sheet.points.iter().map(|p| [p[0], p[1], h]).collect();
    positions.extend(sheet.points.iter().map(|p| [p[0], p[1], -h]));
    let mut faces: Vec<[usize; 3]> = sheet.triangles.clone();
    faces.extend(
        sheet
            .triangles
            .iter()
            .map(|&[a, b, c]| [a + n, c + n, b + n]),
    );

    for cycle in boundary_loops(sheet) {
        let len = cycle.len();
        // Outward (right-hand) normal of the segment from cycle[i] to cycle[i + 1].
        let segment_normal = |i: usize| {
            let (p, q) = (
                sheet.points[cycle[i % len]],
                sheet.points[cycle[(i + 1) % len]],
            );
            let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
            let length = (dx * dx + dy * dy).sqrt();
            [dy / length, -dx / length]
        };
        // ring[r][i]: vertex of loop point i on profile ring r (0 = top, wall_layers = bottom).
        let mut ring = vec![vec![0usize; len]; wall_layers + 1];
        for (i, &v) in cycle.iter().enumerate() {
            let (a, b) = (segment_normal(i + len - 1), segment_normal(i));
            let (nx, ny) = (a[0] + b[0], a[1] + b[1]);
            let norm = (nx * nx + ny * ny).sqrt();
            let normal = [nx / norm, ny / norm];
            ring[0][i] = v;
            ring[wall_layers][i] = v + n;
            for (r, row) in ring.iter_mut().enumerate().take(wall_layers).skip(1) {
                let phi = PI * r as f64 / wall_layers as f64;
                let bulge = h * (phi - FRAC_PI_2).cos();
                let p = sheet.points[v];
                positions.push([
                    p[0] + bulge * normal[0],
                    p[1] + bulge * normal[1],
                    h * phi.cos(),
                ]);
                row[i] = positions.len() - 1;
            }
        }
        for r in 0..wall_layers {
            for i in 0..len {
                let j = (i + 1) % len;
                // The top sheet traverses cycle[i] → cycle[j]; the wall goes the other way.
                let quad = [ring[r][j], ring[r][i], ring[r + 1][i], ring[r + 1][j]];
                let diagonal = Diagonal::shorter(quad, |p, q| {
                    let d = crate::geometry::sub(positions[p], positions[q]);
                    crate::geometry::dot(d, d)
                });
                faces.extend(split_quad(quad, diagonal));
            }
        }
    }
    TriangleMesh::new(positions, faces).expect("the thickened plate is a closed oriented manifold")
}
