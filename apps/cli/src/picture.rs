//! Building pictures of fields, shared by `tvf render` and `tvf demo`: field drawing styles,
//! colour scalars, constraint markers, view and size parsing, and panel grids.

use anyhow::{bail, Result};
use clap::ValueEnum;
use image::RgbaImage;
use tvf_core::discretization::HodgeOperators;
use tvf_core::geometry::{add, scale};
use tvf_core::SurfaceMesh;
use tvf_design::{Constraint, Location, Target};
use tvf_render::{
    ArrowOptions, ColorMap, ColorScale, FaceScalar, FieldLayer, FieldStyle, LicOptions, Marker,
    StreamlineOptions,
};

use crate::discretization_flags::Discretization;
use crate::face_quantities::{face_scalar, ColorBy};
use tvf_render::{render, Polyline, RenderOptions, Scene};

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

/// Renders `mesh` with `field` (`2F` face-frame coefficients of `discretization`, if any)
/// coloured by `color` and drawn in `style`, plus `overlays`.
pub fn draw(
    mesh: &SurfaceMesh,
    discretization: &Discretization,
    field: Option<&[f64]>,
    color: ColorBy,
    style: Style,
    overlays: Overlays,
    view: View,
) -> Result<RgbaImage> {
    let mut scene = Scene {
        markers: overlays.markers,
        polylines: overlays.polylines,
        title: overlays.title,
        ..Default::default()
    };
    if let Some(field) = field {
        let vectors = discretization.require_sampling()?.to_face_vectors(field)?;
        let values = face_scalar(discretization.as_ref(), color, field, &vectors)?;
        scene.face_scalar = values.map(|v| colored(color, v));
        scene.fields.extend(field_layer(vectors, style, view.width));
    }
    let options = RenderOptions {
        width: view.width,
        height: view.height,
        yaw_degrees: view.yaw,
        pitch_degrees: view.pitch,
        zoom: view.zoom,
        ..Default::default()
    };
    Ok(render(mesh, &scene, &options)?)
}

/// How a field is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
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
pub fn colored(kind: ColorBy, values: Vec<f64>) -> FaceScalar {
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

/// The point of `mesh` where `constraint` applies: a face's barycentric point (centroid if
/// none), a vertex, or an edge midpoint. `None` if an index is out of range.
pub fn constraint_position(mesh: &SurfaceMesh, constraint: &Constraint) -> Option<[f64; 3]> {
    let p = mesh.positions();
    match constraint.location {
        Location::Face { face, barycentric } => {
            let f = mesh.faces().get(face)?;
            let l = barycentric.unwrap_or([1.0 / 3.0; 3]);
            Some((0..3).fold([0.0; 3], |acc, c| add(acc, scale(p[f[c]], l[c]))))
        }
        Location::Vertex(v) => p.get(v).copied(),
        Location::Edge(e) => {
            let [a, b] = *mesh.edges().get(e)?;
            Some(scale(add(p[a], p[b]), 0.5))
        }
    }
}

/// Markers for constraints, coloured by kind (vector orange with its direction, source red,
/// sink blue, vortex green), `radius_px` in output pixels.
pub fn constraint_markers(
    mesh: &SurfaceMesh,
    constraints: &[Constraint],
    radius_px: f64,
) -> Vec<Marker> {
    constraints
        .iter()
        .filter_map(|c| {
            let position = constraint_position(mesh, c)?;
            let (kind, direction) = match c.target {
                Target::Vector(v) => ("vector", Some(v)),
                Target::Divergence(d) if d >= 0.0 => ("source", None),
                Target::Divergence(_) => ("sink", None),
                Target::Curl(_) => ("vortex", None),
            };
            Some(Marker {
                position,
                color: Marker::constraint_color(kind),
                radius_px,
                direction,
            })
        })
        .collect()
}

/// Parses `YAW,PITCH` in degrees.
pub fn parse_view(text: &str) -> Result<(f64, f64)> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if let [yaw, pitch] = parts[..] {
        if let (Ok(yaw), Ok(pitch)) = (yaw.parse::<f64>(), pitch.parse::<f64>()) {
            if yaw.is_finite() && pitch.is_finite() {
                return Ok((yaw, pitch));
            }
        }
    }
    bail!("'{text}' is not a view: give YAW,PITCH in degrees, e.g. 30,20")
}

/// Parses `WxH` in pixels (each 16..=16384).
pub fn parse_size(text: &str) -> Result<(u32, u32)> {
    let lower = text.to_ascii_lowercase();
    if let Some((w, h)) = lower.split_once('x') {
        if let (Ok(w), Ok(h)) = (w.trim().parse::<u32>(), h.trim().parse::<u32>()) {
            if (16..=16384).contains(&w) && (16..=16384).contains(&h) {
                return Ok((w, h));
            }
        }
    }
    bail!("'{text}' is not an image size: give WxH with each side 16..16384, e.g. 800x600")
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
    fn views_and_sizes_parse_and_reject_garbage() {
        assert_eq!(parse_view("30,-15").unwrap(), (30.0, -15.0));
        assert!(parse_view("30").is_err());
        assert!(parse_view("a,b").is_err());
        assert_eq!(parse_size("800x600").unwrap(), (800, 600));
        assert_eq!(parse_size("64X48").unwrap(), (64, 48));
        assert!(parse_size("8x600").is_err());
        assert!(parse_size("800").is_err());
    }

    #[test]
    fn colour_ranges_ignore_a_few_extreme_faces() {
        let mut values: Vec<f64> = (0..1000).map(|i| (i % 10) as f64 - 4.5).collect();
        values[7] = 1e6;
        let signed = colored(ColorBy::Divergence, values.clone());
        assert_eq!((signed.scale.min, signed.scale.max), (-4.5, 4.5));
        let magnitude: Vec<f64> = values.iter().map(|v| v.abs()).collect();
        let sequential = colored(ColorBy::Magnitude, magnitude);
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
}
