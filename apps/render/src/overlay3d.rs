//! Depth-tested 3D overlays drawn into the supersampled frame after shading: line segments
//! (streamlines, arrow shafts, fur), filled triangles (arrow heads) and screen-space discs
//! (markers). Overlays are drawn where they are no deeper than the surface plus an offset.

use crate::camera::Camera;
use crate::canvas::distance_to_segment;
use crate::raster::Frame;

/// How a 3D overlay is depth-tested and coloured.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ink {
    /// sRGB colour in `[0, 1]` at the start and the end of the primitive.
    pub color: [[f32; 3]; 2],
    /// Opacity at the start and the end.
    pub alpha: [f32; 2],
    /// Allowed depth (mesh length units) by which the overlay may lie behind the surface.
    pub depth_offset: f64,
}

fn put(frame: &mut Frame, i: usize, color: [f32; 3], alpha: f32) {
    let c = &mut frame.color[i];
    for k in 0..3 {
        c[k] = c[k] * (1.0 - alpha) + color[k] * alpha;
    }
    frame.alpha[i] = frame.alpha[i] + alpha * (1.0 - frame.alpha[i]);
}

/// Draws the segment `[a, b]` with `width` samples, round caps, perspective-correct depth.
pub(crate) fn segment(
    frame: &mut Frame,
    camera: &Camera,
    a: [f64; 3],
    b: [f64; 3],
    width: f64,
    ink: &Ink,
) {
    let pa = camera.project(a);
    let pb = camera.project(b);
    if pa[2] <= camera.near() || pb[2] <= camera.near() {
        return;
    }
    let half = 0.5 * width;
    let x0 = (pa[0].min(pb[0]) - half - 1.0).floor().max(0.0);
    let y0 = (pa[1].min(pb[1]) - half - 1.0).floor().max(0.0);
    let x1 = (pa[0].max(pb[0]) + half + 1.0)
        .ceil()
        .min(frame.width as f64 - 1.0);
    let y1 = (pa[1].max(pb[1]) + half + 1.0)
        .ceil()
        .min(frame.height as f64 - 1.0);
    if x1 < x0 || y1 < y0 {
        return;
    }
    let a2 = [pa[0], pa[1]];
    let b2 = [pb[0], pb[1]];
    let ab = [b2[0] - a2[0], b2[1] - a2[1]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1];
    for y in y0 as usize..=y1 as usize {
        for x in x0 as usize..=x1 as usize {
            let p = [x as f64 + 0.5, y as f64 + 0.5];
            let d = distance_to_segment(p, a2, b2);
            let coverage = (half + 0.5 - d).clamp(0.0, 1.0) as f32;
            if coverage <= 0.0 {
                continue;
            }
            let s = if len2 > 0.0 {
                (((p[0] - a2[0]) * ab[0] + (p[1] - a2[1]) * ab[1]) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let z = 1.0 / ((1.0 - s) / pa[2] + s / pb[2]);
            let i = frame.index(x, y);
            if z - ink.depth_offset > frame.depth[i] as f64 {
                continue;
            }
            let s = s as f32;
            let mut color = [0f32; 3];
            for (k, c) in color.iter_mut().enumerate() {
                *c = ink.color[0][k] * (1.0 - s) + ink.color[1][k] * s;
            }
            let alpha = (ink.alpha[0] * (1.0 - s) + ink.alpha[1] * s) * coverage;
            put(frame, i, color, alpha);
        }
    }
}

/// Fills the 3D triangle `tri` in the start colour of `ink`.
pub(crate) fn triangle(frame: &mut Frame, camera: &Camera, tri: [[f64; 3]; 3], ink: &Ink) {
    let q = tri.map(|p| camera.project(p));
    if q.iter().any(|v| v[2] <= camera.near()) {
        return;
    }
    let edge = |a: [f64; 3], b: [f64; 3], p: [f64; 2]| {
        (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
    };
    let area = edge(q[0], q[1], [q[2][0], q[2][1]]);
    if area == 0.0 || !area.is_finite() {
        return;
    }
    let x0 = q
        .iter()
        .map(|v| v[0])
        .fold(f64::INFINITY, f64::min)
        .floor()
        .max(0.0);
    let x1 = q
        .iter()
        .map(|v| v[0])
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil()
        .min(frame.width as f64 - 1.0);
    let y0 = q
        .iter()
        .map(|v| v[1])
        .fold(f64::INFINITY, f64::min)
        .floor()
        .max(0.0);
    let y1 = q
        .iter()
        .map(|v| v[1])
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil()
        .min(frame.height as f64 - 1.0);
    if x1 < x0 || y1 < y0 {
        return;
    }
    for y in y0 as usize..=y1 as usize {
        for x in x0 as usize..=x1 as usize {
            let p = [x as f64 + 0.5, y as f64 + 0.5];
            let l0 = edge(q[1], q[2], p) / area;
            let l1 = edge(q[2], q[0], p) / area;
            let l2 = 1.0 - l0 - l1;
            if l0 < 0.0 || l1 < 0.0 || l2 < 0.0 {
                continue;
            }
            let z = 1.0 / (l0 / q[0][2] + l1 / q[1][2] + l2 / q[2][2]);
            let i = frame.index(x, y);
            if z - ink.depth_offset > frame.depth[i] as f64 {
                continue;
            }
            put(frame, i, ink.color[0], ink.alpha[0]);
        }
    }
}

/// Draws a disc of `radius` samples facing the viewer at `center`, with an outline of
/// `outline` samples in the end colour of `ink`; drawn entirely if its centre passes the
/// depth test.
pub(crate) fn disc(
    frame: &mut Frame,
    camera: &Camera,
    center: [f64; 3],
    radius: f64,
    outline: f64,
    ink: &Ink,
) {
    let c = camera.project(center);
    if c[2] <= camera.near() {
        return;
    }
    let cx = c[0].floor();
    let cy = c[1].floor();
    if cx >= 0.0 && cy >= 0.0 && cx < frame.width as f64 && cy < frame.height as f64 {
        let i = frame.index(cx as usize, cy as usize);
        if c[2] - ink.depth_offset > frame.depth[i] as f64 {
            return;
        }
    }
    let r = radius + outline;
    let x0 = (c[0] - r - 1.0).floor().max(0.0);
    let y0 = (c[1] - r - 1.0).floor().max(0.0);
    let x1 = (c[0] + r + 1.0).ceil().min(frame.width as f64 - 1.0);
    let y1 = (c[1] + r + 1.0).ceil().min(frame.height as f64 - 1.0);
    if x1 < x0 || y1 < y0 {
        return;
    }
    for y in y0 as usize..=y1 as usize {
        for x in x0 as usize..=x1 as usize {
            let dx = x as f64 + 0.5 - c[0];
            let dy = y as f64 + 0.5 - c[1];
            let d = (dx * dx + dy * dy).sqrt();
            let i = frame.index(x, y);
            let outer = (r + 0.5 - d).clamp(0.0, 1.0) as f32;
            if outer > 0.0 {
                put(frame, i, ink.color[1], outer * ink.alpha[1]);
            }
            let inner = (radius + 0.5 - d).clamp(0.0, 1.0) as f32;
            if inner > 0.0 {
                put(frame, i, ink.color[0], inner * ink.alpha[0]);
            }
        }
    }
}
