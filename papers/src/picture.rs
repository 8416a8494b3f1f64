//! Pictures of fields for the figures: one panel per field (line integral convolution over a
//! magnitude colour map or a solid tint), panels in a grid, PNG output.

use crate::error::PaperError;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{Rgba, RgbaImage};
use std::path::Path;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::geometry::norm;
use tvf_core::SurfaceMesh;
use tvf_render::{
    render, ColorMap, ColorScale, FaceScalar, FieldLayer, FieldStyle, LicOptions, RenderOptions,
    Scene,
};

/// Panel size and camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Turn about the vertical axis in degrees.
    pub yaw: f64,
    /// Elevation in degrees (positive: looking down).
    pub pitch: f64,
    /// Magnification over the automatic fit.
    pub zoom: f64,
}

/// How the surface under the field's texture is coloured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tint {
    /// The field's magnitude, viridis, range up to the 99th percentile.
    Magnitude,
    /// One colour (the paper's Figure 1: green curl-free, red divergence-free).
    Solid([u8; 3]),
}

/// Green of curl-free (integrable) fields in Figure 1.
pub const INTEGRABLE_GREEN: [u8; 3] = [90, 190, 90];
/// Red of divergence-free (co-integrable) fields in Figure 1.
pub const COINTEGRABLE_RED: [u8; 3] = [225, 95, 85];

/// Renders `field` (`2F` face-frame coefficients of `complex`, pointwise) on `mesh` as a line
/// integral convolution over `tint`, titled `title`.
pub fn field_panel<H: HodgeComplex + ?Sized>(
    mesh: &SurfaceMesh,
    complex: &H,
    field: &[f64],
    title: &str,
    tint: Tint,
    view: View,
) -> Result<RgbaImage, PaperError> {
    let vectors = complex.require_sampling()?.to_face_vectors(field)?;
    let mut options = RenderOptions {
        width: view.width,
        height: view.height,
        yaw_degrees: view.yaw,
        pitch_degrees: view.pitch,
        zoom: view.zoom,
        ..Default::default()
    };
    let face_scalar = match tint {
        Tint::Magnitude => Some(magnitude_scalar(&vectors)),
        Tint::Solid(color) => {
            options.surface_color = color;
            None
        }
    };
    let density = (view.width as f64 / 1024.0).clamp(0.25, 4.0);
    let scene = Scene {
        face_scalar,
        fields: vec![FieldLayer {
            vectors,
            style: FieldStyle::Lic(LicOptions {
                length_px: (14.0 * density).max(6.0),
                ..Default::default()
            }),
        }],
        title: Some(title.to_string()),
        ..Default::default()
    };
    Ok(render(mesh, &scene, &options)?)
}

/// Per-face magnitudes with a viridis scale from 0 to the 99th percentile (so that a few
/// extreme faces do not wash the map out).
fn magnitude_scalar(vectors: &[[f64; 3]]) -> FaceScalar {
    let values: Vec<f64> = vectors.iter().map(|v| norm(*v)).collect();
    let mut sorted: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    sorted.sort_by(f64::total_cmp);
    let top = sorted
        .get(((sorted.len().max(1) - 1) as f64 * 0.99).round() as usize)
        .copied()
        .unwrap_or(1.0);
    let mut scalar = FaceScalar::new(values, ColorMap::Viridis, "|u|");
    if top > 0.0 {
        scalar.scale = ColorScale {
            map: ColorMap::Viridis,
            min: 0.0,
            max: top,
        };
    }
    scalar
}

/// Places `panels` (equal sizes) in a grid `columns` wide on a white background.
pub fn grid(panels: &[RgbaImage], columns: usize) -> RgbaImage {
    let Some(first) = panels.first() else {
        return RgbaImage::new(1, 1);
    };
    let (w, h) = first.dimensions();
    let columns = columns.clamp(1, panels.len());
    let rows = panels.len().div_ceil(columns);
    let mut out = RgbaImage::from_pixel(
        w * columns as u32,
        h * rows as u32,
        Rgba([255, 255, 255, 255]),
    );
    for (i, panel) in panels.iter().enumerate() {
        let x = (i % columns) as i64 * w as i64;
        let y = (i / columns) as i64 * h as i64;
        image::imageops::overlay(&mut out, panel, x, y);
    }
    out
}

/// Bits kept per colour channel in saved pictures: 6 of 8 looks the same and halves the size of
/// the noisy line-integral-convolution textures.
const CHANNEL_BITS: u32 = 6;

/// Saves `image` as an RGB PNG at `path` (atomically), alpha dropped (the pictures are opaque),
/// each channel rounded to [`CHANNEL_BITS`] bits, best compression, so that the committed
/// pictures stay small.
pub fn save(image: &RgbaImage, path: &Path) -> Result<(), PaperError> {
    let step = 1u16 << (8 - CHANNEL_BITS);
    let rgb = image::RgbImage::from_fn(image.width(), image.height(), |x, y| {
        let p = image.get_pixel(x, y).0;
        image::Rgb([0, 1, 2].map(|k| {
            let q = (p[k] as u16 + step / 2) / step * step;
            q.min(255) as u8
        }))
    });
    let mut bytes = Vec::new();
    let encoder =
        PngEncoder::new_with_quality(&mut bytes, CompressionType::Best, FilterType::Adaptive);
    rgb.write_with_encoder(encoder)
        .map_err(|e| PaperError::Write {
            path: path.to_path_buf(),
            source: std::io::Error::other(e),
        })?;
    tvf_spectral::write_atomically(path, &bytes).map_err(|source| PaperError::Write {
        path: path.to_path_buf(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_places_panels_row_by_row() {
        let red = RgbaImage::from_pixel(4, 3, Rgba([255, 0, 0, 255]));
        let blue = RgbaImage::from_pixel(4, 3, Rgba([0, 0, 255, 255]));
        let out = grid(&[red.clone(), blue, red], 2);
        assert_eq!(out.dimensions(), (8, 6));
        assert_eq!(out.get_pixel(5, 1).0, [0, 0, 255, 255]);
        assert_eq!(out.get_pixel(1, 4).0, [255, 0, 0, 255]);
        assert_eq!(out.get_pixel(6, 4).0, [255, 255, 255, 255]);
    }
}
