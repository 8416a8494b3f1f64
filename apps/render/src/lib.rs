//! # tvf-render
//!
//! Pictures and exports for tangent fields on triangle meshes, all in software (no GPU, no
//! system fonts):
//! - [`render`]: a z-buffered, supersampled rasteriser with flat or smooth shading, a
//!   per-face colour map with colour bar ([`FaceScalar`], [`ColorMap`]), the field as arrows,
//!   evenly spaced streamlines traced across faces ([`trace_streamlines`]) or line integral
//!   convolution, point markers and 3D polylines;
//! - [`draw_field`]: a discretization's field over a surface coloured by a [`FaceQuantity`]
//!   (magnitude, divergence, curl, energy density) or one [`Tint`], panels in a [`grid`];
//! - [`Plot`]: line/scatter plots with linear or log axes (spectra, rate–distortion);
//! - [`grow_fur`]: hair strands along a field;
//! - [`write_vtk`], [`write_ply`], [`write_obj`], [`save_png`]: atomic exports.
//!
//! ```
//! use tvf_core::generate::icosphere;
//! use tvf_core::geometry::cross;
//! use tvf_render::{render, ColorMap, FaceScalar, FieldLayer, FieldStyle, RenderOptions, Scene};
//!
//! let mesh = icosphere(2);
//! // The rotation field ω × p about the z axis, sampled at face centroids.
//! let field: Vec<[f64; 3]> = mesh
//!     .faces()
//!     .iter()
//!     .map(|f| {
//!         let p = mesh.positions();
//!         let c = [0, 1, 2].map(|k| (p[f[0]][k] + p[f[1]][k] + p[f[2]][k]) / 3.0);
//!         cross([0.0, 0.0, 1.0], c)
//!     })
//!     .collect();
//! let magnitude = field.iter().map(|v| tvf_core::geometry::norm(*v)).collect();
//! let scene = Scene {
//!     face_scalar: Some(FaceScalar::new(magnitude, ColorMap::Viridis, "|u|")),
//!     fields: vec![FieldLayer { vectors: field, style: FieldStyle::Arrows(Default::default()) }],
//!     ..Default::default()
//! };
//! let options = RenderOptions { width: 320, height: 240, ..Default::default() };
//! let image = render(&mesh, &scene, &options).unwrap();
//! assert_eq!(image.dimensions(), (320, 240));
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod arrows;
mod camera;
mod canvas;
mod colorbar;
mod colormap;
mod error;
mod export;
mod face_quantities;
mod field_picture;
mod fur;
mod lic;
mod overlay3d;
mod plot;
mod polygon_edges;
mod raster;
mod render;
mod scene;
mod spacing;
mod streamlines;
mod surface;
mod text;
mod ticks;

pub use arrows::{arrow_glyphs, ArrowGlyph};
pub use camera::{bounding_box, Camera};
pub use colormap::{ColorMap, ColorScale};
pub use error::RenderError;
pub use export::{
    save_png, streamline_polylines, write_atomically, write_obj, write_ply, write_vtk, FaceData,
};
pub use face_quantities::{energy_density, face_scalar, FaceQuantity};
pub use field_picture::{
    colored, draw_field, field_layer, grid, Overlays, Style, Tint, View, COINTEGRABLE_RED,
    INTEGRABLE_GREEN,
};
pub use fur::{grow_fur, FurOptions};
pub use lic::LicOptions;
pub use plot::{Axis, AxisScale, Plot, Series, SeriesStyle, PALETTE};
pub use polygon_edges::polygon_edges;
pub use render::render;
pub use scene::{
    ArrowOptions, FaceScalar, FieldLayer, FieldStyle, Marker, Polyline, RenderOptions, Scene,
    Shading,
};
pub use streamlines::{trace_streamlines, Streamline, StreamlineOptions};
pub use surface::{mean_edge_length, vertex_normals};
pub use text::{draw_text, format_number, text_width, HAlign, TextSize, TextStyle, VAlign};
