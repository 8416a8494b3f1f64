//! Z-buffered triangle rasterisation into a visibility buffer (face id, depth and
//! perspective-correct barycentric coordinates per sample), parallel over horizontal bands.

use rayon::prelude::*;
use tvf_core::TriangleMesh;

use crate::camera::Camera;

/// Face id of a sample that no triangle covers.
pub(crate) const NO_HIT: u32 = u32::MAX;

/// Number of sample rows handled by one parallel task.
const BAND_ROWS: usize = 16;

/// The supersampled frame: visibility buffer plus colour, filled by the shading pass and
/// the 3D overlays.
pub(crate) struct Frame {
    pub width: usize,
    pub height: usize,
    /// Depth along the viewing direction; `f32::INFINITY` where nothing was drawn.
    pub depth: Vec<f32>,
    /// Face covering the sample, or [`NO_HIT`].
    pub face: Vec<u32>,
    /// Barycentric coordinates `(b1, b2)` of the sample in its face (`b0 = 1 − b1 − b2`).
    pub bary: Vec<[f32; 2]>,
    /// sRGB colour in `[0, 1]`.
    pub color: Vec<[f32; 3]>,
    /// Opacity in `[0, 1]`.
    pub alpha: Vec<f32>,
}

impl Frame {
    pub fn index(&self, x: usize, y: usize) -> usize {
        y * self.width + x
    }
}

/// Rasterises every face of `mesh` seen by `camera` into a `width × height` sample grid.
/// Both sides of a face are drawn (open meshes show their inside).
pub(crate) fn rasterize(
    mesh: &TriangleMesh,
    camera: &Camera,
    width: usize,
    height: usize,
) -> Frame {
    let projected: Vec<[f64; 3]> = mesh
        .positions()
        .par_iter()
        .map(|&p| camera.project(p))
        .collect();
    let near = camera.near();
    let band_count = height.div_ceil(BAND_ROWS);
    // Row range of each drawable triangle, then a counting sort of triangles into bands.
    let spans: Vec<Option<(usize, usize)>> = mesh
        .faces()
        .par_iter()
        .map(|f| {
            let q = [projected[f[0]], projected[f[1]], projected[f[2]]];
            if q.iter().any(|v| v[2] <= near) {
                return None;
            }
            let ymin = q.iter().map(|v| v[1]).fold(f64::INFINITY, f64::min);
            let ymax = q.iter().map(|v| v[1]).fold(f64::NEG_INFINITY, f64::max);
            let xmin = q.iter().map(|v| v[0]).fold(f64::INFINITY, f64::min);
            let xmax = q.iter().map(|v| v[0]).fold(f64::NEG_INFINITY, f64::max);
            if ymax < 0.0 || xmax < 0.0 || ymin >= height as f64 || xmin >= width as f64 {
                return None;
            }
            let r0 = (ymin.max(0.0) as usize) / BAND_ROWS;
            let r1 = ((ymax.min(height as f64 - 1.0)) as usize) / BAND_ROWS;
            Some((r0, r1))
        })
        .collect();
    let mut counts = vec![0usize; band_count + 1];
    for &(r0, r1) in spans.iter().flatten() {
        for c in &mut counts[r0..=r1] {
            *c += 1;
        }
    }
    let mut offsets = vec![0usize; band_count + 1];
    for b in 0..band_count {
        offsets[b + 1] = offsets[b] + counts[b];
    }
    let mut bins = vec![0u32; offsets[band_count]];
    let mut fill = offsets.clone();
    for (t, span) in spans.iter().enumerate() {
        if let Some((r0, r1)) = *span {
            for b in r0..=r1 {
                bins[fill[b]] = t as u32;
                fill[b] += 1;
            }
        }
    }

    let n = width * height;
    let mut depth = vec![f32::INFINITY; n];
    let mut face = vec![NO_HIT; n];
    let mut bary = vec![[0f32; 2]; n];
    let chunk = BAND_ROWS * width;
    depth
        .par_chunks_mut(chunk)
        .zip(face.par_chunks_mut(chunk))
        .zip(bary.par_chunks_mut(chunk))
        .enumerate()
        .for_each(|(band, ((depth, face), bary))| {
            let row0 = band * BAND_ROWS;
            let rows = depth.len() / width;
            for &t in &bins[offsets[band]..offsets[band + 1]] {
                let f = mesh.faces()[t as usize];
                let q = [projected[f[0]], projected[f[1]], projected[f[2]]];
                raster_triangle(t, q, row0, rows, width, depth, face, bary);
            }
        });
    Frame {
        width,
        height,
        depth,
        face,
        bary,
        color: vec![[0.0; 3]; n],
        alpha: vec![0.0; n],
    }
}

#[inline]
fn edge(a: [f64; 3], b: [f64; 3], p: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

#[allow(clippy::too_many_arguments)]
fn raster_triangle(
    t: u32,
    q: [[f64; 3]; 3],
    row0: usize,
    rows: usize,
    width: usize,
    depth: &mut [f32],
    face: &mut [u32],
    bary: &mut [[f32; 2]],
) {
    let area = edge(q[0], q[1], [q[2][0], q[2][1]]);
    if area == 0.0 || !area.is_finite() {
        return;
    }
    let inv_area = 1.0 / area;
    let xmin = q.iter().map(|v| v[0]).fold(f64::INFINITY, f64::min);
    let xmax = q.iter().map(|v| v[0]).fold(f64::NEG_INFINITY, f64::max);
    let ymin = q.iter().map(|v| v[1]).fold(f64::INFINITY, f64::min);
    let ymax = q.iter().map(|v| v[1]).fold(f64::NEG_INFINITY, f64::max);
    let x0 = (xmin - 0.5).ceil().max(0.0) as usize;
    let x1 = ((xmax - 0.5).floor()).min(width as f64 - 1.0);
    let y0 = ((ymin - 0.5).ceil().max(row0 as f64)) as usize;
    let y1 = ((ymax - 0.5).floor()).min((row0 + rows) as f64 - 1.0);
    if x1 < x0 as f64 || y1 < y0 as f64 {
        return;
    }
    let (x1, y1) = (x1 as usize, y1 as usize);
    let iz = [1.0 / q[0][2], 1.0 / q[1][2], 1.0 / q[2][2]];
    for y in y0..=y1 {
        let py = y as f64 + 0.5;
        let base = (y - row0) * width;
        for x in x0..=x1 {
            let p = [x as f64 + 0.5, py];
            let l0 = edge(q[1], q[2], p) * inv_area;
            let l1 = edge(q[2], q[0], p) * inv_area;
            let l2 = 1.0 - l0 - l1;
            if l0 < 0.0 || l1 < 0.0 || l2 < 0.0 {
                continue;
            }
            let w = l0 * iz[0] + l1 * iz[1] + l2 * iz[2];
            let z = (1.0 / w) as f32;
            let i = base + x;
            if z < depth[i] {
                depth[i] = z;
                face[i] = t;
                bary[i] = [(l1 * iz[1] / w) as f32, (l2 * iz[2] / w) as f32];
            }
        }
    }
}
