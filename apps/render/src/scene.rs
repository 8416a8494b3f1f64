//! What to draw ([`Scene`]) and how to draw it ([`RenderOptions`]).

use crate::colormap::{ColorMap, ColorScale};
use crate::lic::LicOptions;
use crate::streamlines::StreamlineOptions;

/// A scalar per face shown through a colour map, with a colour bar.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceScalar {
    /// One value per face (`F` entries), e.g. magnitude, divergence, curl or energy.
    pub values: Vec<f64>,
    /// Colour map and value range.
    pub scale: ColorScale,
    /// Name shown above the colour bar.
    pub label: String,
}

impl FaceScalar {
    /// `values` with `map`, its range fitted by [`ColorScale::fit`] (symmetric about 0 for
    /// a diverging map).
    pub fn new(values: Vec<f64>, map: ColorMap, label: impl Into<String>) -> Self {
        let scale = ColorScale::fit(map, &values);
        FaceScalar {
            values,
            scale,
            label: label.into(),
        }
    }
}

/// Arrow glyphs, one at each of a set of evenly spread faces.
#[derive(Debug, Clone, PartialEq)]
pub struct ArrowOptions {
    /// Largest number of arrows; arrows are spaced `max(mean edge, √(area / max_count))`
    /// apart.
    pub max_count: usize,
    /// Length of the longest arrow in units of that spacing; the others are proportional
    /// to their vector's magnitude.
    pub length_scale: f64,
    /// Shaft width in output pixels.
    pub width_px: f64,
    /// Colour.
    pub color: [u8; 3],
    /// Seed of the random order used to spread the arrows.
    pub seed: u64,
}

impl Default for ArrowOptions {
    fn default() -> Self {
        ArrowOptions {
            max_count: 1500,
            length_scale: 0.9,
            width_px: 1.6,
            color: [15, 15, 15],
            seed: 3,
        }
    }
}

/// How a tangent field is drawn.
#[derive(Debug, Clone, PartialEq)]
pub enum FieldStyle {
    /// Arrow glyphs on evenly spread faces.
    Arrows(ArrowOptions),
    /// Evenly spaced streamlines traced across faces.
    Streamlines(StreamlineOptions),
    /// Line integral convolution texture on the surface.
    Lic(LicOptions),
}

/// A tangent field given as one 3D vector per face (`F` entries; normal components are
/// ignored) and how to draw it.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldLayer {
    /// One vector per face.
    pub vectors: Vec<[f64; 3]>,
    /// Drawing style.
    pub style: FieldStyle,
}

/// A point marker, e.g. a constraint position.
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    /// Position (mesh units), normally on the surface.
    pub position: [f64; 3],
    /// Fill colour; the outline is dark grey.
    pub color: [u8; 3],
    /// Radius in output pixels.
    pub radius_px: f64,
    /// Optional direction (for a vector constraint), drawn as an arrow from the marker with
    /// a length of 8 % of the bounding-sphere diameter (the vector's length is ignored).
    pub direction: Option<[f64; 3]>,
}

impl Marker {
    /// Standard colours for constraint kinds: vector (orange), source (red), sink (blue),
    /// vortex (green); anything else magenta.
    pub fn constraint_color(kind: &str) -> [u8; 3] {
        match kind {
            "vector" => [255, 140, 0],
            "source" => [220, 30, 30],
            "sink" => [30, 80, 230],
            "vortex" => [20, 170, 60],
            _ => [200, 0, 200],
        }
    }
}

/// A 3D polyline drawn with depth test (e.g. a fur strand or an exported streamline),
/// coloured from `color` at its first point to `tip_color` at its last.
#[derive(Debug, Clone, PartialEq)]
pub struct Polyline {
    /// Points (mesh units).
    pub points: Vec<[f64; 3]>,
    /// Colour at the first point.
    pub color: [u8; 3],
    /// Colour at the last point.
    pub tip_color: [u8; 3],
    /// Width in output pixels.
    pub width_px: f64,
}

/// Everything drawn on and around the mesh.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Scene {
    /// Per-face colour map (with colour bar); `None` shades the surface in
    /// [`RenderOptions::surface_color`].
    pub face_scalar: Option<FaceScalar>,
    /// Tangent fields, drawn in order (LIC modulates the surface, the others overlay it).
    pub fields: Vec<FieldLayer>,
    /// Polylines, drawn after the fields.
    pub polylines: Vec<Polyline>,
    /// Markers, drawn last.
    pub markers: Vec<Marker>,
    /// Title printed at the top.
    pub title: Option<String>,
}

/// Flat (one normal per face) or smooth (interpolated vertex normals) shading.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shading {
    /// One normal per face.
    Flat,
    /// Area-weighted vertex normals interpolated across faces.
    Smooth,
}

/// Image size, camera and lighting.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderOptions {
    /// Width in pixels (16..=16384).
    pub width: u32,
    /// Height in pixels (16..=16384).
    pub height: u32,
    /// Turn about the vertical axis in degrees (0: looking along −z).
    pub yaw_degrees: f64,
    /// Elevation in degrees (positive: looking down).
    pub pitch_degrees: f64,
    /// Magnification over the automatic fit (1: the bounding sphere just fits).
    pub zoom: f64,
    /// Samples per pixel along each axis (1..=4; 2 means 2×2 supersampling).
    pub supersample: u32,
    /// Shading mode.
    pub shading: Shading,
    /// Background colour (RGBA).
    pub background: [u8; 4],
    /// Surface colour when no colour map is given.
    pub surface_color: [u8; 3],
    /// Ambient light in `[0, 1]`; the headlight contributes `1 − ambient` at normal incidence.
    pub ambient: f64,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 1024,
            height: 768,
            yaw_degrees: 30.0,
            pitch_degrees: 20.0,
            zoom: 1.0,
            supersample: 2,
            shading: Shading::Smooth,
            background: [255, 255, 255, 255],
            surface_color: [200, 200, 205],
            ambient: 0.3,
        }
    }
}
