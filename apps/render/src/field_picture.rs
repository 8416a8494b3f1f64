//! Pictures of a discretization's fields, shared by `tvf render`, `tvf demo` and papers/: a
//! field drawn in a [`FieldStyle`]-like [`Style`] over a surface coloured by a
//! [`FaceQuantity`] or one solid [`Tint`], seen from a [`View`], and panels in a [`grid`].

use crate::face_quantities::{face_scalar, FaceQuantity};
use crate::{
    render, ArrowOptions, ColorMap, ColorScale, FaceScalar, FieldLayer, FieldStyle, LicOptions,
    Marker, Polyline, RenderError, RenderOptions, Scene, StreamlineOptions,
};
use image::RgbaImage;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::SurfaceMesh;

/// Image size and camera.
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

impl View {
    /// Unit vector from the centre of the picture towards the camera (as in
    /// [`crate::Camera::fit`]).
    pub fn to_eye(&self) -> [f64; 3] {
        let (yaw, pitch) = (self.yaw.to_radians(), self.pitch.to_radians());
        [
            yaw.sin() * pitch.cos(),
            pitch.sin(),
            yaw.cos() * pitch.cos(),
        ]
    }

    /// The same camera at `1/divisor` of the size each way (at least 16 pixels): one panel of
    /// a grid `divisor` panels wide.
    pub fn panel(&self, divisor: u32) -> View {
        View {
            width: (self.width / divisor.max(1)).max(16),
            height: (self.height / divisor.max(1)).max(16),
            ..*self
        }
    }
}

/// How a field is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// Arrow glyphs on evenly spread faces.
    Arrows,
    /// Evenly spaced streamlines traced across faces.
    Streamlines,
    /// Line integral convolution.
    Lic,
    /// The field is not drawn (colour map only).
    None,
}

impl Style {
    /// Every style, in the order of [`Style::NAMES`].
    pub const ALL: [Style; 4] = [Style::Arrows, Style::Streamlines, Style::Lic, Style::None];

    /// The names command lines use.
    pub const NAMES: [&'static str; 4] = ["arrows", "streamlines", "lic", "none"];

    /// The style called `name` (one of [`Style::NAMES`]).
    pub fn from_name(name: &str) -> Option<Style> {
        Self::NAMES
            .iter()
            .position(|&n| n == name)
            .map(|i| Self::ALL[i])
    }
}

/// How the surface under the field is coloured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tint {
    /// A per-face quantity of the field, colour-mapped (see [`colored`]).
    Quantity(FaceQuantity),
    /// One colour (the paper's Figure 1: green curl-free, red divergence-free fields).
    Solid([u8; 3]),
}

/// Green of curl-free (integrable) fields, as in the paper's Figure 1.
pub const INTEGRABLE_GREEN: [u8; 3] = [90, 190, 90];
/// Red of divergence-free (co-integrable) fields, as in the paper's Figure 1.
pub const COINTEGRABLE_RED: [u8; 3] = [225, 95, 85];

/// What to draw besides the surface.
#[derive(Debug, Clone, Default)]
pub struct Overlays {
    /// Point markers (constraints).
    pub markers: Vec<Marker>,
    /// 3D polylines (fur strands).
    pub polylines: Vec<Polyline>,
    /// Title at the top.
    pub title: Option<String>,
}

impl Overlays {
    /// Only a title.
    pub fn titled(title: impl Into<String>) -> Self {
        Overlays {
            title: Some(title.into()),
            ..Default::default()
        }
    }
}

/// Renders `mesh` with `field` (`n1` coefficients of `complex`, if any) over a surface
/// coloured by `tint`, the field drawn in `style`, plus `overlays`. Needs the complex's
/// sampling (and its point evaluation for divergence, curl and energy). A polygon mesh is drawn
/// through its display triangulation, each triangle with its polygon's colour and vector.
pub fn draw_field(
    mesh: &SurfaceMesh,
    complex: &dyn HodgeComplex,
    field: Option<&[f64]>,
    tint: Tint,
    style: Style,
    overlays: Overlays,
    view: View,
) -> Result<RgbaImage, RenderError> {
    let mut scene = Scene {
        markers: overlays.markers,
        polylines: overlays.polylines,
        title: overlays.title,
        ..Default::default()
    };
    let mut options = RenderOptions {
        width: view.width,
        height: view.height,
        yaw_degrees: view.yaw,
        pitch_degrees: view.pitch,
        zoom: view.zoom,
        ..Default::default()
    };
    if let Tint::Solid(color) = tint {
        options.surface_color = color;
    }
    if let Some(field) = field {
        let vectors = complex.require_sampling()?.to_face_vectors(field)?;
        if let Tint::Quantity(quantity) = tint {
            let values = face_scalar(complex, mesh, quantity, field, &vectors)?;
            scene.face_scalar = values.map(|v| colored(quantity, mesh.on_display(&v)));
        }
        scene
            .fields
            .extend(field_layer(mesh.on_display(&vectors), style, view.width));
    }
    render(mesh.display(), &scene, &options)
}

/// The layer drawing `vectors` (one per face) in `style`, sized for an image `width` pixels
/// wide; `None` for [`Style::None`].
pub fn field_layer(vectors: Vec<[f64; 3]>, style: Style, width: u32) -> Option<FieldLayer> {
    let density = (width as f64 / 1024.0).clamp(0.25, 4.0);
    let style = match style {
        Style::Arrows => FieldStyle::Arrows(ArrowOptions {
            max_count: (1200.0 * density * density) as usize,
            ..Default::default()
        }),
        Style::Streamlines => FieldStyle::Streamlines(StreamlineOptions {
            count: (3000.0 * density).max(300.0) as usize,
            ..Default::default()
        }),
        Style::Lic => FieldStyle::Lic(LicOptions {
            length_px: (14.0 * density).max(6.0),
            ..Default::default()
        }),
        Style::None => return None,
    };
    Some(FieldLayer { vectors, style })
}

/// A colour-mapped per-face scalar: viridis for magnitude and energy, blue–white–red
/// (symmetric about 0) for divergence and curl. The range is robust: the 1st to 99th percentile
/// (of `|value|` for signed quantities), so that a few extreme faces (slivers, sharp creases) do
/// not wash the map out; values beyond it get the end colours.
pub fn colored(kind: FaceQuantity, values: Vec<f64>) -> FaceScalar {
    let map = if kind.is_signed() {
        ColorMap::BlueWhiteRed
    } else {
        ColorMap::Viridis
    };
    let mut scalar = FaceScalar::new(values, map, kind.label());
    let mut sorted: Vec<f64> = scalar
        .values
        .iter()
        .map(|&v| if kind.is_signed() { v.abs() } else { v })
        .filter(|v| v.is_finite())
        .collect();
    sorted.sort_by(f64::total_cmp);
    if sorted.len() >= 100 {
        let at = |q: f64| sorted[((sorted.len() - 1) as f64 * q).round() as usize];
        let (lo, hi) = (at(0.01), at(0.99));
        if kind.is_signed() && hi > 0.0 {
            scalar.scale = ColorScale {
                map,
                min: -hi,
                max: hi,
            };
        } else if !kind.is_signed() && hi > lo {
            scalar.scale = ColorScale {
                map,
                min: lo,
                max: hi,
            };
        }
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
        image::Rgba([255, 255, 255, 255]),
    );
    for (i, panel) in panels.iter().enumerate() {
        let x = (i % columns) as i64 * w as i64;
        let y = (i / columns) as i64 * h as i64;
        image::imageops::overlay(&mut out, panel, x, y);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_ranges_ignore_a_few_extreme_faces() {
        let mut values: Vec<f64> = (0..1000).map(|i| (i % 10) as f64 - 4.5).collect();
        values[7] = 1e6;
        let signed = colored(FaceQuantity::Divergence, values.clone());
        assert_eq!((signed.scale.min, signed.scale.max), (-4.5, 4.5));
        let magnitude: Vec<f64> = values.iter().map(|v| v.abs()).collect();
        let sequential = colored(FaceQuantity::Magnitude, magnitude);
        assert_eq!((sequential.scale.min, sequential.scale.max), (0.5, 4.5));
        assert_eq!(signed.values.len(), 1000);
    }

    #[test]
    fn grid_places_panels_row_by_row() {
        let red = RgbaImage::from_pixel(4, 3, image::Rgba([255, 0, 0, 255]));
        let blue = RgbaImage::from_pixel(4, 3, image::Rgba([0, 0, 255, 255]));
        let out = grid(&[red.clone(), blue, red], 2);
        assert_eq!(out.dimensions(), (8, 6));
        assert_eq!(out.get_pixel(5, 1).0, [0, 0, 255, 255]);
        assert_eq!(out.get_pixel(1, 4).0, [255, 0, 0, 255]);
        assert_eq!(out.get_pixel(6, 4).0, [255, 255, 255, 255]);
    }

    #[test]
    fn names_round_trip() {
        for (style, name) in Style::ALL.iter().zip(Style::NAMES) {
            assert_eq!(Style::from_name(name), Some(*style));
        }
        for quantity in FaceQuantity::ALL {
            assert_eq!(FaceQuantity::from_name(quantity.label()), Some(quantity));
        }
        assert_eq!(Style::from_name("glyphs"), None);
        assert_eq!(FaceQuantity::from_name("speed"), None);
    }
}
