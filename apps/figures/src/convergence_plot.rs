//! The picture of a convergence study ([`tvf_convergence`]): per surface a log–log
//! plot of each discretization's eigenvalue error against the number of faces, one colour per
//! discretization, the integrable family as a line with markers and the co-integrable family as
//! a plain line, with a grey reference line of second order (`error ∝ h² ∝ 1/faces`); the
//! surfaces side by side.
//!
//! The error falls to the lower right (more faces, smaller `h`), which leaves the upper right
//! corner to the legend: the y axis spans the data (a factor 2 below and 3 above), not decades
//! of empty room.

use crate::error::FigureError;
use image::RgbaImage;
use tvf_convergence::study::{ConvergenceReport, Surface};
use tvf_render::{grid, Axis, AxisScale, Plot, Series, SeriesStyle, PALETTE};
use tvf_spectral::FieldFamily;

/// Colour of the second-order reference line.
const REFERENCE_GREY: [u8; 3] = [150, 150, 150];

/// The plot of one surface of `report` (`width × height` pixels).
pub fn convergence_plot(
    report: &ConvergenceReport,
    surface: Surface,
    width: u32,
    height: u32,
) -> Plot {
    let names = discretizations(report);
    let mut series = Vec::new();
    let mut points_all = Vec::new();
    for (index, name) in names.iter().enumerate() {
        let rows: Vec<_> = report
            .rows
            .iter()
            .filter(|r| &r.discretization == name && r.surface == surface)
            .collect();
        for family in [FieldFamily::Integrable, FieldFamily::Cointegrable] {
            let points: Vec<(f64, f64)> = rows
                .iter()
                .map(|r| (r.faces as f64, r.error(family)))
                .collect();
            points_all.extend(points.iter().copied());
            // One legend line per discretization: its integrable series carries the name.
            let (label, style) = match family {
                FieldFamily::Integrable => (name.clone(), SeriesStyle::LineAndMarkers),
                _ => (String::new(), SeriesStyle::Line),
            };
            let mut line = Series::new(label, points, style);
            line.color = Some(color(index, names.len()));
            series.push(line);
        }
    }
    let usable: Vec<(f64, f64)> = points_all
        .into_iter()
        .filter(|(f, e)| *f > 0.0 && *e > 0.0 && e.is_finite())
        .collect();
    let mut y = Axis::new("max relative eigenvalue error", AxisScale::Log10);
    if let Some(reference) = second_order_reference(&usable) {
        series.push(reference);
    }
    let (lo, hi) = usable
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &(_, e)| {
            (lo.min(e), hi.max(e))
        });
    if lo <= hi {
        y.range = Some((lo / 2.0, hi * 3.0));
    }
    Plot {
        title: format!(
            "{} (dots: integrable, plain: co-integrable, grey: order 2)",
            surface_title(surface)
        ),
        x: Axis::new("faces (h ∝ faces^-1/2)", AxisScale::Log10),
        y,
        series,
        width,
        height,
    }
}

/// A grey line of slope −1 against the number of faces (second order in `h`) through the
/// geometric mean of the data, spanning its faces; `None` without two distinct face counts.
fn second_order_reference(points: &[(f64, f64)]) -> Option<Series> {
    let (min, max) = points.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
        (lo.min(p.0), hi.max(p.0))
    });
    if points.is_empty() || min >= max {
        return None;
    }
    let n = points.len() as f64;
    let mean_log_f = points.iter().map(|p| p.0.ln()).sum::<f64>() / n;
    let mean_log_e = points.iter().map(|p| p.1.ln()).sum::<f64>() / n;
    let at = |f: f64| (mean_log_e - (f.ln() - mean_log_f)).exp();
    let mut line = Series::new(
        String::new(),
        vec![(min, at(min)), (max, at(max))],
        SeriesStyle::Line,
    );
    line.color = Some(REFERENCE_GREY);
    Some(line)
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

/// `Unit sphere`, `Unit hemisphere, tangential`, `Jittered unit sphere`, …
fn surface_title(surface: Surface) -> String {
    let jittered = if surface.is_jittered() {
        "Jittered u"
    } else {
        "U"
    };
    let quads = if surface.has_quads() { " (quads)" } else { "" };
    match surface.boundary() {
        None => format!("{jittered}nit sphere{quads}"),
        Some(b) => format!("{jittered}nit hemisphere{quads}, {}", b.name()),
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
    use tvf_convergence::study::LevelRow;

    /// Co-integrable series are lines, a grey order-2 reference spans the faces, and the y axis
    /// stays within a factor of the data (it once ran to 100+ for the legend's room).
    #[test]
    fn the_plot_has_lines_a_reference_and_a_tight_y_axis() {
        let row = |name: &str, level: u32, faces: usize, e: f64| LevelRow {
            discretization: name.to_string(),
            surface: Surface::Sphere,
            level,
            faces,
            h: 1.0 / (faces as f64).sqrt(),
            integrable_error: e,
            cointegrable_error: 2.0 * e,
            seconds: 0.0,
        };
        let report = ConvergenceReport {
            rows: vec![
                row("a", 1, 80, 1e-2),
                row("a", 2, 320, 2.5e-3),
                row("b", 1, 80, 2e-2),
                row("b", 2, 320, 5e-3),
            ],
            orders: Vec::new(),
        };
        let plot = convergence_plot(&report, Surface::Sphere, 320, 240);
        let styles: Vec<SeriesStyle> = plot.series.iter().map(|s| s.style).collect();
        assert_eq!(styles[1], SeriesStyle::Line, "co-integrable: a line");
        let reference = plot.series.last().unwrap();
        assert_eq!(reference.color, Some(REFERENCE_GREY));
        let [(f0, e0), (f1, e1)] = [reference.points[0], reference.points[1]];
        assert_eq!((f0, f1), (80.0, 320.0));
        assert!(
            ((e1 / e0).ln() / (f1 / f0).ln() + 1.0).abs() < 1e-12,
            "slope −1"
        );
        let (lo, hi) = plot.y.range.unwrap();
        assert!(lo >= 1e-3 && hi <= 0.2, "{lo} – {hi}");
        plot.render().unwrap();
    }

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
