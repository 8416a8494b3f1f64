//! Streamlines of a piecewise-constant tangent field (one 3D vector per face), traced
//! exactly across faces: straight inside a face along the face's own vector (projected to
//! the face plane), and on reaching an edge continued in the neighbouring face along *its*
//! vector. A line stops at a boundary, where the field vanishes, where the neighbour's
//! vector points back across the shared edge (a sink line), at its length budget, or when
//! it comes too close to another line (evenly spaced streamlines after Jobard and Lefer).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::geometry::{add, dot, norm, normalize, scale, sub};
use tvf_core::{TriangleMesh, NO_FACE};

use crate::error::{check_face_count, check_finite_vectors, RenderError};
use crate::spacing::{shuffled, PointGrid};
use crate::surface::{barycentric, barycentric_gradients, mean_edge_length, point_at, tangential};

/// A polyline on the surface: segment `i` runs from `points[i]` to `points[i + 1]` inside
/// face `faces[i]` (so `faces.len() + 1 == points.len()`).
#[derive(Debug, Clone, PartialEq)]
pub struct Streamline {
    /// Points on the surface (mesh length units), in the direction of the field.
    pub points: Vec<[f64; 3]>,
    /// The face containing each segment.
    pub faces: Vec<usize>,
}

impl Streamline {
    /// Arc length.
    pub fn length(&self) -> f64 {
        self.points.windows(2).map(|w| norm(sub(w[1], w[0]))).sum()
    }
}

/// How many streamlines, how far apart and how long.
#[derive(Debug, Clone, PartialEq)]
pub struct StreamlineOptions {
    /// Density of lines: they are spaced `√(total area / count)` apart (the number of lines
    /// is smaller, as each line is many separations long).
    pub count: usize,
    /// Maximal arc length of one line in units of the separation.
    pub max_length: f64,
    /// A line stops when it comes closer than `stop_distance × separation` to another line.
    pub stop_distance: f64,
    /// Seed of the random order in which seed points are tried.
    pub seed: u64,
    /// Line width in output pixels (used by the renderer).
    pub width_px: f64,
    /// Line colour (used by the renderer); the line fades in from its tail to its head.
    pub color: [u8; 3],
}

impl Default for StreamlineOptions {
    fn default() -> Self {
        StreamlineOptions {
            count: 2000,
            max_length: 12.0,
            stop_distance: 0.5,
            seed: 7,
            width_px: 1.3,
            color: [20, 20, 20],
        }
    }
}

/// The walker: per-face unit tangent directions and barycentric gradients.
pub(crate) struct FaceWalker<'a> {
    mesh: &'a TriangleMesh,
    directions: Vec<[f64; 3]>,
    grads: Vec<[[f64; 3]; 3]>,
    /// Steps shorter than this count as zero-length (vertex crossings).
    tiny: f64,
}

impl<'a> FaceWalker<'a> {
    /// Prepares walking along `field` (one vector per face, any length; the tangential
    /// part is used, and faces whose tangential part is below `1e-12 · max` are stagnant).
    pub fn new(mesh: &'a TriangleMesh, field: &[[f64; 3]]) -> Self {
        let tangent: Vec<[f64; 3]> = field
            .iter()
            .enumerate()
            .map(|(t, &v)| tangential(v, mesh.face_normal(t)))
            .collect();
        let largest = tangent.iter().map(|&v| norm(v)).fold(0.0, f64::max);
        let directions = tangent
            .iter()
            .map(|&v| {
                if norm(v) > 1e-12 * largest && largest > 0.0 {
                    normalize(v)
                } else {
                    [0.0; 3]
                }
            })
            .collect();
        FaceWalker {
            mesh,
            directions,
            grads: barycentric_gradients(mesh),
            tiny: 1e-10 * mean_edge_length(mesh).max(1e-300),
        }
    }

    /// Traces from `start` in face `face` along `sign × field` for at most `budget` arc
    /// length; `keep_going(point)` is asked at each point (and every `probe` length along
    /// segments) and ends the line when it returns false.
    pub fn trace(
        &self,
        face: usize,
        start: [f64; 3],
        sign: f64,
        budget: f64,
        probe: f64,
        keep_going: &mut dyn FnMut([f64; 3]) -> bool,
    ) -> Streamline {
        let mesh = self.mesh;
        let mut line = Streamline {
            points: vec![start],
            faces: Vec::new(),
        };
        let mut t = face;
        let mut x = start;
        let mut left = budget;
        let mut idle_steps = 0;
        let max_steps = 4 * mesh.face_count() + 16;
        for _ in 0..max_steps {
            let d = scale(self.directions[t], sign);
            if d == [0.0; 3] || left <= 0.0 {
                break;
            }
            let g = &self.grads[t];
            let l = barycentric(mesh, g, t, x);
            let mut exit = None;
            let mut s_exit = f64::INFINITY;
            for c in 0..3 {
                let rate = dot(g[c], d);
                if rate < 0.0 {
                    let s = l[c].max(0.0) / -rate;
                    if s < s_exit {
                        s_exit = s;
                        exit = Some(c);
                    }
                }
            }
            let Some(c) = exit else { break };
            let (s, ends_inside) = if s_exit > left {
                (left, true)
            } else {
                (s_exit, false)
            };
            // The end point, snapped onto the exit edge when leaving the face.
            let mut y = add(x, scale(d, s));
            if !ends_inside {
                let mut ly = barycentric(mesh, g, t, y);
                ly[c] = 0.0;
                let total: f64 = ly.iter().map(|v| v.max(0.0)).sum();
                if total > 0.0 {
                    ly = ly.map(|v| v.max(0.0) / total);
                }
                y = point_at(mesh, t, ly);
            }
            let step = norm(sub(y, x));
            if !segment_keeps_going(x, y, step, probe, keep_going) {
                break;
            }
            if step > self.tiny {
                line.points.push(y);
                line.faces.push(t);
                idle_steps = 0;
            } else {
                idle_steps += 1;
                if idle_steps > 6 {
                    break;
                }
            }
            left -= step;
            x = y;
            if ends_inside {
                break;
            }
            let e = mesh.face_edges()[t][c];
            let [f0, f1] = mesh.edge_faces()[e];
            let next = if f0 == t { f1 } else { f0 };
            if next == NO_FACE {
                break;
            }
            let d_next = scale(self.directions[next], sign);
            let Some(c_next) = (0..3).find(|&k| mesh.face_edges()[next][k] == e) else {
                break;
            };
            // The neighbour's field must carry the line into the neighbour.
            if dot(self.grads[next][c_next], d_next) <= 1e-9 * norm(self.grads[next][c_next]) {
                break;
            }
            t = next;
        }
        line
    }
}

/// Whether `keep_going` accepts every probe point along the segment from `x` to `y` (of length
/// `step`), taken at most `probe` apart, `y` included: the separation test of a streamline step.
fn segment_keeps_going(
    x: [f64; 3],
    y: [f64; 3],
    step: f64,
    probe: f64,
    keep_going: &mut dyn FnMut([f64; 3]) -> bool,
) -> bool {
    let pieces = (step / probe.max(1e-300)).ceil().max(1.0) as usize;
    (1..=pieces).all(|k| keep_going(add(x, scale(sub(y, x), k as f64 / pieces as f64))))
}

/// Evenly spaced streamlines of `field` (one vector per face, `F` entries) on `mesh`.
///
/// Seeds are tried at random points of faces in a random order fixed by `options.seed`;
/// a seed closer than the separation to an existing line is skipped, and each line is
/// traced backwards and forwards from its seed. Lines shorter than half the separation
/// are dropped. Deterministic for a given mesh, field and options.
pub fn trace_streamlines(
    mesh: &TriangleMesh,
    field: &[[f64; 3]],
    options: &StreamlineOptions,
) -> Result<Vec<Streamline>, RenderError> {
    check_face_count("field", mesh.face_count(), field.len())?;
    check_finite_vectors("field", field)?;
    if options.count == 0 {
        return Err(RenderError::InvalidOption {
            name: "streamline count",
            value: "0".into(),
            reason: "at least one streamline must be asked for",
        });
    }
    if !(options.max_length > 0.0 && options.stop_distance > 0.0 && options.stop_distance <= 1.0) {
        return Err(RenderError::InvalidOption {
            name: "streamline max_length / stop_distance",
            value: format!("{} / {}", options.max_length, options.stop_distance),
            reason: "max_length must be positive and stop_distance in (0, 1]",
        });
    }
    let walker = FaceWalker::new(mesh, field);
    let separation = (mesh.total_area() / options.count as f64).sqrt();
    let stop = options.stop_distance * separation;
    let probe = 0.5 * stop;
    let budget = options.max_length * separation;
    let mut grid = PointGrid::new(separation);
    let mut lines = Vec::new();
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    for t in shuffled(mesh.face_count(), options.seed) {
        let (a, b): (f64, f64) = (rng.random(), rng.random());
        let (a, b) = if a + b > 1.0 {
            (1.0 - a, 1.0 - b)
        } else {
            (a, b)
        };
        let seed_point = point_at(mesh, t, [1.0 - a - b, a, b]);
        if grid.near(seed_point, separation, None) {
            continue;
        }
        let mut ok = |p: [f64; 3]| !grid.near(p, stop, None);
        let backward = walker.trace(t, seed_point, -1.0, 0.5 * budget, probe, &mut ok);
        let forward = walker.trace(t, seed_point, 1.0, 0.5 * budget, probe, &mut ok);
        let mut points: Vec<[f64; 3]> = backward.points.iter().rev().copied().collect();
        let mut faces: Vec<usize> = backward.faces.iter().rev().copied().collect();
        points.extend_from_slice(&forward.points[1..]);
        faces.extend_from_slice(&forward.faces);
        let line = Streamline { points, faces };
        if line.length() < 0.5 * separation {
            continue;
        }
        let owner = lines.len() as u32;
        for w in line.points.windows(2) {
            let pieces = (norm(sub(w[1], w[0])) / probe).ceil().max(1.0) as usize;
            for k in 0..=pieces {
                grid.insert(
                    owner,
                    add(w[0], scale(sub(w[1], w[0]), k as f64 / pieces as f64)),
                );
            }
        }
        lines.push(line);
    }
    Ok(lines)
}
