//! The picture of a convergence study ([`tvf_convergence`]): per surface a log–log
//! plot of each discretization's eigenvalue error against the mean edge length, one colour per
//! discretization, the integrable family as a line with markers and the co-integrable family as
//! markers alone; the surfaces side by side.

use crate::error::FigureError;
use image::RgbaImage;
use tvf_convergence::study::{ConvergenceReport, Surface};
use tvf_render::{grid, Axis, AxisScale, Plot, Series, SeriesStyle, PALETTE};
use tvf_spectral::FieldFamily;

/// The plot of one surface of `report` (`width × height` pixels).
pub fn convergence_plot(
    report: &ConvergenceReport,
    surface: Surface,
    width: u32,
    height: u32,
) -> Plot {
    let names = discretizations(report);
    let mut series = Vec::new();
    let mut errors = Vec::new();
    for (index, name) in names.iter().enumerate() {
        let rows: Vec<_> = report
            .rows
            .iter()
            .filter(|r| &r.discretization == name && r.surface == surface)
            .collect();
        for family in [FieldFamily::Integrable, FieldFamily::Cointegrable] {
            let points: Vec<(f64, f64)> = rows.iter().map(|r| (r.h, r.error(family))).collect();
            errors.extend(points.iter().map(|p| p.1));
            // One legend line per discretization: its integrable series carries the name.
            let (label, style) = match family {
                FieldFamily::Integrable => (name.clone(), SeriesStyle::LineAndMarkers),
                _ => (String::new(), SeriesStyle::Scatter),
            };
            let mut line = Series::new(label, points, style);
            line.color = Some(color(index, names.len()));
            series.push(line);
        }
    }
    let (lo, hi) = errors
        .iter()
        .filter(|e| **e > 0.0 && e.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &e| {
            (lo.min(e), hi.max(e))
        });
    let mut y = Axis::new("max relative eigenvalue error", AxisScale::Log10);
    if lo <= hi {
        // Room above the data for the legend, one line per discretization.
        let decades = 1.0 + 0.45 * names.len() as f64;
        y.range = Some((lo / 2.0, hi * 10f64.powf(decades)));
    }
    Plot {
        title: format!(
            "{} (lines: integrable, dots: co-integrable)",
            surface_title(surface)
        ),
        x: Axis::new("mean edge length h", AxisScale::Log10),
        y,
        series,
        width,
        height,
    }
}

/// Every surface of `report`, side by side (`width × height` pixels each).
pub fn convergence_figure(
    report: &ConvergenceReport,
    width: u32,
    height: u32,
) -> Result<RgbaImage, FigureError> {
    let mut surfaces: Vec<Surface> = Vec::new();
    for row in &report.rows {
        if !surfaces.contains(&row.surface) {
            surfaces.push(row.surface);
        }
    }
    let panels = surfaces
        .iter()
        .map(|&s| Ok(convergence_plot(report, s, width, height).render()?))
        .collect::<Result<Vec<_>, FigureError>>()?;
    Ok(grid(&panels, panels.len().clamp(1, 3)))
}

/// The discretizations of `report`, in the order of its rows.
fn discretizations(report: &ConvergenceReport) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for row in &report.rows {
        if !names.contains(&row.discretization) {
            names.push(row.discretization.clone());
        }
    }
    names
}

/// `Unit sphere`, `Unit hemisphere, tangential`, …
fn surface_title(surface: Surface) -> String {
    match surface.boundary() {
        None => "Unit sphere".to_string(),
        Some(b) => format!("Unit hemisphere, {}", b.name()),
    }
}

/// The colour of discretization `index` of `count`: the plot palette while it lasts, then hues
/// spread around the colour wheel (so that no two discretizations share a colour).
fn color(index: usize, count: usize) -> [u8; 3] {
    if count <= PALETTE.len() {
        return PALETTE[index];
    }
    let hue = index as f64 / count as f64 * 6.0;
    let x = 1.0 - (hue % 2.0 - 1.0).abs();
    let (r, g, b) = match hue as usize {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    // Darkened to 75 % so that yellow and cyan stay readable on white.
    [r, g, b].map(|c| (c * 0.75 * 255.0).round() as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_differ_beyond_the_palette() {
        let colours: Vec<[u8; 3]> = (0..12).map(|i| color(i, 12)).collect();
        for i in 0..12 {
            for j in 0..i {
                assert_ne!(colours[i], colours[j], "{i} and {j}");
            }
        }
        assert_eq!(color(2, 5), PALETTE[2]);
    }
}
