//! Deterministic, evenly spread choices of faces (arrow positions, seeds) using a seeded
//! random order and a uniform grid that rejects candidates too close to accepted ones.

use std::collections::HashMap;

use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use tvf_core::geometry::{norm, sub};

/// A uniform 3D hash grid of points with cell size `cell`, answering "is any stored point
/// (of another owner) closer than `r ≤ cell`?".
pub(crate) struct PointGrid {
    cell: f64,
    cells: HashMap<[i64; 3], Vec<(u32, [f64; 3])>>,
}

impl PointGrid {
    pub fn new(cell: f64) -> Self {
        PointGrid {
            cell: cell.max(1e-300),
            cells: HashMap::new(),
        }
    }

    fn key(&self, p: [f64; 3]) -> [i64; 3] {
        p.map(|x| (x / self.cell).floor() as i64)
    }

    pub fn insert(&mut self, owner: u32, p: [f64; 3]) {
        let k = self.key(p);
        self.cells.entry(k).or_default().push((owner, p));
    }

    /// Whether a point of an owner other than `except` lies within `r` of `p`.
    pub fn near(&self, p: [f64; 3], r: f64, except: Option<u32>) -> bool {
        let k = self.key(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(list) = self.cells.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) {
                        if list
                            .iter()
                            .any(|&(o, q)| Some(o) != except && norm(sub(p, q)) < r)
                        {
                            return true;
                        }
                    }
                }
            }
        }
        false
    }
}

/// Indices `0..n` in a random order fixed by `seed`.
pub(crate) fn shuffled(n: usize, seed: u64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..n).collect();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    order.shuffle(&mut rng);
    order
}

/// Picks positions among `points` so that no two picked ones are closer than `spacing`,
/// visiting candidates in a seeded random order: an even spread with about
/// `area / spacing²` picks.
pub(crate) fn spread(points: &[[f64; 3]], spacing: f64, seed: u64) -> Vec<usize> {
    let mut grid = PointGrid::new(spacing);
    let mut picked = Vec::new();
    for i in shuffled(points.len(), seed) {
        if !grid.near(points[i], spacing, None) {
            grid.insert(0, points[i]);
            picked.push(i);
        }
    }
    picked.sort_unstable();
    picked
}
