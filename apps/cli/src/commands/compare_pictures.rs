//! The pictures of `tvf compare -o DIR`: for the lowest fields of each family of the
//! reference, one PNG with a panel per entry side by side (`eigenfield-FAMILY-N.png`). The
//! reference's panel is its own field; another entry's panel is the field of its matching
//! eigenspace nearest to the reference's — the projection, in the area-weighted inner product,
//! of the reference's field onto the span of the entry's fields at the positions of the
//! reference's cluster — so that a degenerate eigenspace, whose single fields each entry may
//! rotate freely, and the arbitrary sign of a field do not make equal spaces look different.
//! Each panel's title gives the entry's eigenvalue at that position and the angle between the
//! reference's field and that span (radians). Panels are coloured by the magnitude of the
//! drawn field (each panel scaled to its own field), with streamlines.

use crate::progress::Progress;
use anyhow::{Context, Result};
use tvf_core::io::StagedFolder;
use tvf_core::SurfaceMesh;
use tvf_render::{
    colored, field_layer, grid, polygon_edges, render, save_png, FaceQuantity, RenderOptions,
    Scene, Style,
};
use tvf_spectral::eigenspace_angles::{family_columns, weighted_projection};
use tvf_spectral::{area_weights, ComparisonReport, FieldFamily};

/// Which pictures, how large, from where.
pub struct PictureRequest {
    /// The lowest N fields of each family (harmonic ones only where the mesh has them).
    pub per_family: usize,
    /// Width and height of one panel in pixels.
    pub panel: (u32, u32),
    /// Yaw and pitch of the camera in degrees.
    pub view: (f64, f64),
}

/// Writes the pictures of `request` into `folder`.
pub fn write_pictures(
    folder: &StagedFolder,
    report: &ComparisonReport,
    mesh: &SurfaceMesh,
    request: &PictureRequest,
) -> Result<()> {
    let reference = &report.entries[report.reference].sampled;
    let pictures: Vec<(FieldFamily, usize, usize)> = [
        FieldFamily::Harmonic,
        FieldFamily::Integrable,
        FieldFamily::Cointegrable,
    ]
    .into_iter()
    .flat_map(|family| {
        (0..request.per_family).filter_map(move |position| {
            family_columns(&reference.families, family, position, 1)
                .map(|column| (family, position, column[0]))
        })
    })
    .collect();
    let progress = Progress::new("compare pictures");
    for (done, &(family, position, column)) in pictures.iter().enumerate() {
        progress.update("pictures", done, pictures.len());
        let panels = (0..report.entries.len())
            .map(|entry| panel(report, mesh, request, entry, column))
            .collect::<Result<Vec<_>>>()?;
        let name = format!("eigenfield-{}-{position}.png", family.name());
        let image = grid(&panels, panels.len());
        save_png(&image, &folder.path().join(&name))
            .with_context(|| format!("cannot write {}", folder.target().join(&name).display()))?;
    }
    progress.finish(format!("{} pictures", pictures.len()));
    Ok(())
}

/// The panel of entry `entry` for the reference's field `column`.
fn panel(
    report: &ComparisonReport,
    mesh: &SurfaceMesh,
    request: &PictureRequest,
    entry: usize,
    column: usize,
) -> Result<image::RgbaImage> {
    let reference = &report.entries[report.reference].sampled;
    let sampled = &report.entries[entry].sampled;
    let weights = area_weights(mesh);
    let target: Vec<f64> = reference.vectors.col(column).iter().copied().collect();
    let comparison = &report.comparisons[entry];
    let cluster = comparison
        .clusters
        .iter()
        .find(|c| c.cluster.columns.contains(&column))
        .context("every field of the reference lies in one of its clusters")?;
    let family = cluster.cluster.family;
    let position = cluster.cluster.first
        + cluster
            .cluster
            .columns
            .iter()
            .position(|&c| c == column)
            .unwrap_or(0);
    let label = &report.entries[entry].measurements.label;
    let (vectors, title) = match &cluster.other_columns {
        Some(columns) => {
            let span = sampled.columns(columns);
            let projection = weighted_projection(span.as_ref(), &weights, &target)
                .context("the sampled fields of an entry are linearly dependent")?;
            let angle = angle_to(&target, &projection, &weights);
            let eigenvalue = family_columns(&sampled.families, family, position, 1)
                .map_or(f64::NAN, |c| sampled.eigenvalues[c[0]]);
            let role = if entry == report.reference {
                " (ref.)"
            } else {
                ""
            };
            let title = format!("{label}{role}  lambda {eigenvalue:.4}  angle {angle:.3}");
            (projection, title)
        }
        None => (
            vec![0.0; target.len()],
            format!("{label}: no {} field {position}", family.name()),
        ),
    };
    draw(mesh, &vectors, title, request)
}

/// The angle (radians) between `v` and its projection `p` onto a subspace, in the weighted
/// norm: `acos(|p| / |v|)`, through the sine for accuracy at small angles.
fn angle_to(v: &[f64], p: &[f64], weights: &[f64]) -> f64 {
    let norm2 = |x: &dyn Fn(usize) -> f64| -> f64 {
        (0..v.len()).map(|r| weights[r] * x(r) * x(r)).sum::<f64>()
    };
    let whole = norm2(&|r| v[r]);
    let outside = norm2(&|r| v[r] - p[r]);
    if whole > 0.0 {
        (outside / whole).sqrt().min(1.0).asin()
    } else {
        0.0
    }
}

/// One panel: the per-face `vectors` (`3F`) as streamlines over their magnitude.
fn draw(
    mesh: &SurfaceMesh,
    vectors: &[f64],
    title: String,
    request: &PictureRequest,
) -> Result<image::RgbaImage> {
    let per_face: Vec<[f64; 3]> = vectors
        .chunks_exact(3)
        .map(|v| [v[0], v[1], v[2]])
        .collect();
    let magnitude: Vec<f64> = per_face
        .iter()
        .map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
        .collect();
    let (width, height) = request.panel;
    let scene = Scene {
        face_scalar: Some(colored(
            FaceQuantity::Magnitude,
            mesh.on_display(&magnitude),
        )),
        fields: field_layer(mesh.on_display(&per_face), Style::Streamlines, width)
            .into_iter()
            .collect(),
        polylines: polygon_edges(mesh, (width as f64 / 1024.0).clamp(0.5, 2.0)),
        title: Some(title),
        ..Default::default()
    };
    let options = RenderOptions {
        width,
        height,
        yaw_degrees: request.view.0,
        pitch_degrees: request.view.1,
        ..Default::default()
    };
    Ok(render(mesh.display(), &scene, &options)?)
}
