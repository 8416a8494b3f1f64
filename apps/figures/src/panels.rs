//! Panels of the figures: a field as line integral convolution over a magnitude colour map or
//! a solid tint (`tvf_render::draw_field`), a field with its Hodge parts as a 2×2 grid, and PNG
//! output of the committed pictures.

use crate::error::FigureError;
use crate::finding::Experiment;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::RgbaImage;
use std::io::Write as _;
use std::path::Path;
use tvf_core::discretization::HodgeComplex;
use tvf_core::SurfaceMesh;
use tvf_discretizations::HodgeDecomposer;
use tvf_render::{draw_field, grid, FaceQuantity, Marker, Overlays, Style, Tint, View};

/// Renders `field` (`n1` coefficients of `complex`) on `mesh` as a line integral convolution
/// over `tint`, titled `title`.
pub fn field_panel(
    mesh: &SurfaceMesh,
    complex: &dyn HodgeComplex,
    field: &[f64],
    title: &str,
    tint: Tint,
    view: View,
) -> Result<RgbaImage, FigureError> {
    Ok(draw_field(
        mesh,
        complex,
        Some(field),
        tint,
        Style::Lic,
        Overlays::titled(title),
        view,
    )?)
}

/// `field` (`n1` coefficients of `complex`) and its integrable, co-integrable and harmonic parts
/// (exact Hodge decomposition) as a 2×2 grid of titled panels drawn in `style` over `tint`, each
/// with `markers`; `view` is the size of the whole grid.
pub fn hodge_parts_grid(
    mesh: &SurfaceMesh,
    complex: &dyn HodgeComplex,
    field: &[f64],
    (tint, style): (Tint, Style),
    markers: &[Marker],
    view: View,
) -> Result<RgbaImage, FigureError> {
    let parts = HodgeDecomposer::new(complex)?.decompose(field)?;
    let panels = [
        ("field", field),
        ("integrable (curl-free)", &parts.integrable),
        ("co-integrable (divergence-free)", &parts.cointegrable),
        ("harmonic", &parts.harmonic),
    ];
    let mut images = Vec::new();
    for (name, part) in panels {
        let overlays = Overlays {
            markers: markers.to_vec(),
            title: Some(name.to_string()),
            ..Default::default()
        };
        images.push(draw_field(
            mesh,
            complex,
            Some(part),
            tint,
            style,
            overlays,
            view.panel(2),
        )?);
    }
    Ok(grid(&images, 2))
}

/// Renders `fields` (each `(field, title)`, `n1` coefficients of the experiment's complex) over
/// the magnitude colour map side by side in one row and saves the picture as `file` in the
/// experiment's output folder.
pub fn save_magnitude_row(
    x: &Experiment,
    file: &str,
    fields: &[(&[f64], &str)],
) -> Result<(), FigureError> {
    let panels = fields
        .iter()
        .map(|&(field, title)| {
            let magnitude = Tint::Quantity(FaceQuantity::Magnitude);
            field_panel(x.mesh, x.complex, field, title, magnitude, x.view)
        })
        .collect::<Result<Vec<_>, _>>()?;
    save(&grid(&panels, fields.len()), &x.out.join(file))
}

/// Bits kept per colour channel in saved pictures: 6 of 8 looks the same and halves the size of
/// the noisy line-integral-convolution textures.
const CHANNEL_BITS: u32 = 6;

/// Saves `image` as an RGB PNG at `path` (atomically), alpha dropped (the pictures are opaque),
/// each channel rounded to [`CHANNEL_BITS`] bits, best compression, so that the committed
/// pictures stay small.
pub fn save(image: &RgbaImage, path: &Path) -> Result<(), FigureError> {
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
        .map_err(|e| FigureError::Write {
            path: path.to_path_buf(),
            source: std::io::Error::other(e),
        })?;
    tvf_core::io::write_atomically(path, |w| w.write_all(&bytes)).map_err(|source| {
        FigureError::Write {
            path: path.to_path_buf(),
            source,
        }
    })
}
