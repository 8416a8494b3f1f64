//! The plots of `tvf analyze` and `tvf rate-distortion`: a field's coefficient magnitudes
//! against frequency (the paper's Figure 8) and rate–distortion curves (Figure 9).

use tvf_render::{Axis, AxisScale, Plot, Series, SeriesStyle};
use tvf_spectral::{CoefficientCoding, FieldFamily, RatePoint, SpectralAnalysis};

/// |coefficient| against frequency `√λ` for both families and the harmonic fields (log scale,
/// 1000 × 600 pixels); coefficients below `1e-12` times the largest are left out. `None` when
/// no coefficient is left to plot.
pub fn spectrum_plot(analysis: &SpectralAnalysis) -> Option<Plot> {
    // Coefficients below round-off of the largest (e.g. harmonic ones of a field without a
    // harmonic part) would only stretch the log axis.
    let largest = analysis
        .entries
        .iter()
        .fold(0.0f64, |m, e| m.max(e.coefficient.abs()));
    let points = |family| -> Vec<(f64, f64)> {
        analysis
            .family(family)
            .map(|e| (e.frequency, e.coefficient.abs()))
            .filter(|&(_, c)| c > 1e-12 * largest)
            .collect()
    };
    let mut series = vec![
        Series::new(
            "integrable |alpha|",
            points(FieldFamily::Integrable),
            SeriesStyle::Line,
        ),
        Series::new(
            "co-integrable |beta|",
            points(FieldFamily::Cointegrable),
            SeriesStyle::Line,
        ),
    ];
    let harmonic = points(FieldFamily::Harmonic);
    if !harmonic.is_empty() {
        series.push(Series::new(
            "harmonic |gamma|",
            harmonic,
            SeriesStyle::Scatter,
        ));
    }
    series.retain(|s| !s.points.is_empty());
    (!series.is_empty()).then(|| Plot {
        title: "Spectral analysis: coefficient magnitudes".to_string(),
        x: Axis::new("frequency sqrt(lambda)", AxisScale::Linear),
        y: Axis::new("|coefficient|", AxisScale::Log10),
        series,
        width: 1000,
        height: 600,
    })
}

/// Relative error against bits per vertex, one line per coding (log–log), `size` in pixels.
pub fn rate_distortion_plot(
    points: &[RatePoint],
    codings: &[CoefficientCoding],
    title: String,
    (width, height): (u32, u32),
) -> Plot {
    let series = codings
        .iter()
        .map(|&coding| {
            let mut line: Vec<(f64, f64)> = points
                .iter()
                .filter(|p| p.coding == coding)
                .map(|p| (p.bits_per_vertex, p.relative_error))
                .collect();
            line.sort_by(|a, b| a.0.total_cmp(&b.0));
            Series::new(coding.label(), line, SeriesStyle::LineAndMarkers)
        })
        .collect();
    Plot {
        title,
        x: Axis::new("bits per vertex", AxisScale::Log10),
        y: Axis::new("relative L2 error", AxisScale::Log10),
        series,
        width,
        height,
    }
}
