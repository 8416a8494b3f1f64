//! Plots: spectrum-like log plots and rate–distortion-like curves.

use crate::common::{keep, rgb};
use tvf_render::{Axis, AxisScale, Plot, RenderError, Series, SeriesStyle};

fn spectrum_plot() -> Plot {
    let integrable: Vec<(f64, f64)> = (1..200)
        .map(|k| (k as f64 * 0.1, (-0.03 * k as f64).exp() + 1e-4))
        .collect();
    let cointegrable: Vec<(f64, f64)> = (1..200)
        .map(|k| (k as f64 * 0.1, 0.3 / (k as f64).powi(2)))
        .collect();
    Plot {
        title: "Fourier coefficients".into(),
        x: Axis::new("frequency sqrt(lambda)", AxisScale::Linear),
        y: Axis::new("|coefficient|", AxisScale::Log10),
        series: vec![
            Series::new("integrable", integrable, SeriesStyle::Scatter),
            Series::new("co-integrable", cointegrable, SeriesStyle::Scatter),
        ],
        width: 800,
        height: 500,
    }
}

#[test]
fn spectrum_plot_has_data_in_the_plot_area() {
    let dir = tempfile::tempdir().unwrap();
    let image = spectrum_plot().render().unwrap();
    assert_eq!(image.dimensions(), (800, 500));
    keep(&image, dir.path(), "plot_spectrum.png");
    // Both palette colours appear inside the central plot area.
    let mut blue = 0;
    let mut red = 0;
    for y in 60..440 {
        for x in 120..780 {
            let c = rgb(&image, x, y);
            blue += (c[2] > 150 && c[0] < 80) as usize;
            red += (c[0] > 180 && c[1] < 80 && c[2] < 80) as usize;
        }
    }
    assert!(blue > 500 && red > 500, "blue {blue} red {red}");
}

#[test]
fn rate_distortion_plot_with_lines_and_legend() {
    let dir = tempfile::tempdir().unwrap();
    let bits: [f64; 6] = [0.5, 1.0, 2.0, 4.0, 8.0, 16.0];
    let curve = |s: f64| {
        bits.iter()
            .map(|&b| (b, s * (-0.4 * b).exp()))
            .collect::<Vec<_>>()
    };
    let plot = Plot {
        title: "rate-distortion".into(),
        x: Axis::new("bits per vertex", AxisScale::Log10),
        y: Axis::new("relative L2 error", AxisScale::Log10),
        series: vec![
            Series::new("64-bit, smooth", curve(0.5), SeriesStyle::LineAndMarkers),
            Series::new("quantised, smooth", curve(0.3), SeriesStyle::LineAndMarkers),
            Series::new("64-bit, noisy", curve(1.0), SeriesStyle::Line),
        ],
        width: 700,
        height: 500,
    };
    let image = plot.render().unwrap();
    keep(&image, dir.path(), "plot_rate_distortion.png");
    let non_white = image
        .pixels()
        .filter(|p| p.0[..3] != [255, 255, 255])
        .count();
    assert!(non_white > 10_000, "{non_white}");
}

#[test]
fn plots_refuse_what_they_cannot_draw() {
    let mut plot = spectrum_plot();
    for s in &mut plot.series {
        for p in &mut s.points {
            p.1 = -p.1;
        }
    }
    assert!(matches!(plot.render(), Err(RenderError::NoPlotData(_))));
    let mut small = spectrum_plot();
    small.width = 20;
    assert!(matches!(
        small.render(),
        Err(RenderError::InvalidSize { .. })
    ));
    let mut bad_range = spectrum_plot();
    bad_range.y.range = Some((0.0, 1.0));
    assert!(bad_range.render().is_err());
}
