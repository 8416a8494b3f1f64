//! Anti-aliased 2D drawing on an RGBA image: pixels, rectangles, lines and discs.
//! Used for the plots and for the 2D overlays (colour bar, labels) of a render.

use image::RgbaImage;

/// Blends `color` with coverage `alpha ∈ [0, 1]` over pixel `(x, y)`; pixels outside the
/// image are ignored (straight-alpha "over" compositing).
pub fn blend(image: &mut RgbaImage, x: i64, y: i64, color: [u8; 3], alpha: f32) {
    if x < 0 || y < 0 || x >= image.width() as i64 || y >= image.height() as i64 || alpha <= 0.0 {
        return;
    }
    let a = alpha.min(1.0);
    let p = image.get_pixel_mut(x as u32, y as u32);
    let old = p.0[3] as f32 / 255.0;
    let out = a + old * (1.0 - a);
    for (channel, &c) in p.0.iter_mut().zip(&color) {
        let mixed = (c as f32 * a + *channel as f32 * old * (1.0 - a)) / out;
        *channel = mixed.round().clamp(0.0, 255.0) as u8;
    }
    p.0[3] = (out * 255.0).round() as u8;
}

/// Fills the axis-aligned rectangle `[x0, x1) × [y0, y1)` (pixel coordinates).
pub fn fill_rect(image: &mut RgbaImage, x0: i64, y0: i64, x1: i64, y1: i64, color: [u8; 3]) {
    for y in y0.max(0)..y1.min(image.height() as i64) {
        for x in x0.max(0)..x1.min(image.width() as i64) {
            blend(image, x, y, color, 1.0);
        }
    }
}

/// Draws the outline of the rectangle `[x0, x1] × [y0, y1]` one pixel wide.
pub fn stroke_rect(image: &mut RgbaImage, x0: i64, y0: i64, x1: i64, y1: i64, color: [u8; 3]) {
    fill_rect(image, x0, y0, x1 + 1, y0 + 1, color);
    fill_rect(image, x0, y1, x1 + 1, y1 + 1, color);
    fill_rect(image, x0, y0, x0 + 1, y1 + 1, color);
    fill_rect(image, x1, y0, x1 + 1, y1 + 1, color);
}

/// Draws an anti-aliased line of `width` pixels from `a` to `b` (pixel coordinates, pixel
/// centres at half-integers), with round caps.
pub fn draw_line(image: &mut RgbaImage, a: [f64; 2], b: [f64; 2], width: f64, color: [u8; 3]) {
    let half = 0.5 * width.max(0.5);
    let x0 = (a[0].min(b[0]) - half - 1.0).floor() as i64;
    let x1 = (a[0].max(b[0]) + half + 1.0).ceil() as i64;
    let y0 = (a[1].min(b[1]) - half - 1.0).floor() as i64;
    let y1 = (a[1].max(b[1]) + half + 1.0).ceil() as i64;
    let x0 = x0.max(0);
    let y0 = y0.max(0);
    let x1 = x1.min(image.width() as i64 - 1);
    let y1 = y1.min(image.height() as i64 - 1);
    for y in y0..=y1 {
        for x in x0..=x1 {
            let p = [x as f64 + 0.5, y as f64 + 0.5];
            let d = distance_to_segment(p, a, b);
            let coverage = (half + 0.5 - d).clamp(0.0, 1.0);
            if coverage > 0.0 {
                blend(image, x, y, color, coverage as f32);
            }
        }
    }
}

/// Draws an anti-aliased disc of radius `radius` pixels centred at `c`.
pub fn fill_disc(image: &mut RgbaImage, c: [f64; 2], radius: f64, color: [u8; 3]) {
    draw_line(image, c, c, 2.0 * radius, color);
}

/// Euclidean distance from `p` to the segment `[a, b]` in the plane.
pub fn distance_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1]];
    let ap = [p[0] - a[0], p[1] - a[1]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1];
    let t = if len2 > 0.0 {
        ((ap[0] * ab[0] + ap[1] * ab[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let dx = ap[0] - t * ab[0];
    let dy = ap[1] - t * ab[1];
    (dx * dx + dy * dy).sqrt()
}
