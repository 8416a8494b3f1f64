//! Line integral convolution in screen space: each face's field direction is projected to
//! the image, and every surface pixel averages a noise texture along the projected
//! streamline through it (a Hann-weighted kernel), stopping at silhouettes, depth jumps
//! and where the field turns back. The result modulates the surface colour.

use rayon::prelude::*;

use crate::raster::{Frame, NO_HIT};

/// Parameters of the line integral convolution.
#[derive(Debug, Clone, PartialEq)]
pub struct LicOptions {
    /// Half-length of the convolution kernel in output pixels.
    pub length_px: f64,
    /// Feature size of the noise in output pixels.
    pub grain_px: f64,
    /// Contrast of the texture: 1 maps ±2 standard deviations to black and white.
    pub contrast: f64,
    /// How strongly the texture darkens the surface colour, in `[0, 1]`.
    pub strength: f64,
    /// Seed of the noise.
    pub seed: u64,
}

impl Default for LicOptions {
    fn default() -> Self {
        LicOptions {
            length_px: 14.0,
            grain_px: 1.4,
            contrast: 1.0,
            strength: 0.65,
            seed: 11,
        }
    }
}

/// Output-resolution view of the supersampled frame: the face and depth of the centre
/// sample of each output pixel.
pub(crate) struct PixelFaces {
    pub width: usize,
    pub height: usize,
    pub face: Vec<u32>,
    pub depth: Vec<f32>,
}

impl PixelFaces {
    pub fn from_frame(frame: &Frame, factor: usize) -> Self {
        let width = frame.width / factor;
        let height = frame.height / factor;
        let mut face = Vec::with_capacity(width * height);
        let mut depth = Vec::with_capacity(width * height);
        for y in 0..height {
            for x in 0..width {
                let i = frame.index(x * factor + factor / 2, y * factor + factor / 2);
                face.push(frame.face[i]);
                depth.push(frame.depth[i]);
            }
        }
        PixelFaces {
            width,
            height,
            face,
            depth,
        }
    }
}

fn hash(x: i64, y: i64, seed: u64) -> f32 {
    let mut z = (x as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (y as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ seed.wrapping_mul(0x1656_67B1_9E37_79F9);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 40) as f32 / (1u64 << 24) as f32
}

/// Value noise on a lattice of spacing `grain` pixels, bilinearly interpolated.
struct Noise {
    columns: usize,
    rows: usize,
    inverse_grain: f64,
    values: Vec<f32>,
}

impl Noise {
    fn new(width: usize, height: usize, grain: f64, seed: u64) -> Self {
        let columns = (width as f64 / grain).ceil() as usize + 2;
        let rows = (height as f64 / grain).ceil() as usize + 2;
        let mut values = Vec::with_capacity(columns * rows);
        for j in 0..rows {
            for i in 0..columns {
                values.push(hash(i as i64, j as i64, seed));
            }
        }
        Noise {
            columns,
            rows,
            inverse_grain: 1.0 / grain,
            values,
        }
    }

    #[inline]
    fn at(&self, x: f64, y: f64) -> f32 {
        let u = (x * self.inverse_grain).max(0.0);
        let v = (y * self.inverse_grain).max(0.0);
        let i = (u as usize).min(self.columns - 2);
        let j = (v as usize).min(self.rows - 2);
        let (fu, fv) = ((u - i as f64) as f32, (v - j as f64) as f32);
        let k = j * self.columns + i;
        let a = self.values[k] * (1.0 - fu) + self.values[k + 1] * fu;
        let b = self.values[k + self.columns] * (1.0 - fu) + self.values[k + self.columns + 1] * fu;
        a * (1.0 - fv) + b * fv
    }
}

/// The LIC texture per output pixel, in `[0, 1]` (background pixels get 1).
/// `directions[t]` is face `t`'s unit field direction in image coordinates (zero where the
/// field vanishes); `depth_jump` is the depth difference treated as a silhouette.
pub(crate) fn lic_texture(
    pixels: &PixelFaces,
    directions: &[[f32; 2]],
    depth_jump: f32,
    options: &LicOptions,
) -> Vec<f32> {
    let (w, h) = (pixels.width, pixels.height);
    let step = 0.8f64;
    let steps = (options.length_px / step).ceil().max(1.0) as usize;
    let noise = Noise::new(w, h, options.grain_px.max(0.5), options.seed);
    // Hann window over the kernel's half-length.
    let kernel: Vec<f32> = (0..=steps)
        .map(|k| {
            let s = k as f32 / (steps as f32 + 1.0);
            0.5 * (1.0 + (std::f32::consts::PI * s).cos())
        })
        .collect();
    let mut raw = vec![f32::NAN; w * h];
    raw.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, out) in row.iter_mut().enumerate() {
            let start_face = pixels.face[y * w + x];
            if start_face == NO_HIT {
                continue;
            }
            let x0 = x as f64 + 0.5;
            let y0 = y as f64 + 0.5;
            let mut sum = noise.at(x0, y0);
            let mut weights = 1.0f32;
            for sign in [1.0f32, -1.0] {
                let (mut px, mut py) = (x0, y0);
                let mut face = start_face;
                let mut depth = pixels.depth[y * w + x];
                let d0 = directions[face as usize];
                let mut prev = [d0[0] * sign, d0[1] * sign];
                for &weight in &kernel[1..=steps] {
                    let d = directions[face as usize];
                    let d = [d[0] * sign, d[1] * sign];
                    if d == [0.0, 0.0] || d[0] * prev[0] + d[1] * prev[1] < 0.0 {
                        break;
                    }
                    prev = d;
                    px += d[0] as f64 * step;
                    py += d[1] as f64 * step;
                    if px < 0.0 || py < 0.0 || px >= w as f64 || py >= h as f64 {
                        break;
                    }
                    let i = py as usize * w + px as usize;
                    let f = pixels.face[i];
                    if f == NO_HIT || (pixels.depth[i] - depth).abs() > depth_jump {
                        break;
                    }
                    face = f;
                    depth = pixels.depth[i];
                    sum += weight * noise.at(px, py);
                    weights += weight;
                }
            }
            *out = sum / weights;
        }
    });
    // Contrast stretch: the averaging shrinks the noise's spread; restore it.
    let values: Vec<f64> = raw
        .iter()
        .filter(|v| !v.is_nan())
        .map(|&v| v as f64)
        .collect();
    let n = values.len().max(1) as f64;
    let mean = values.iter().sum::<f64>() / n;
    let std = (values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n)
        .sqrt()
        .max(1e-6);
    let gain = (0.25 * options.contrast / std) as f32;
    let mean = mean as f32;
    raw.into_iter()
        .map(|v| {
            if v.is_nan() {
                1.0
            } else {
                (0.5 + gain * (v - mean)).clamp(0.0, 1.0)
            }
        })
        .collect()
}
