//! Line and scatter plots with linear or logarithmic axes, tick labels, axis labels and a
//! legend, drawn with the crate's own rasteriser and embedded font (no system fonts).
//! Used for coefficient spectra (paper Figure 8) and rate–distortion curves (Figure 9).

use image::{Rgba, RgbaImage};

use crate::canvas::{blend, draw_line, fill_disc, fill_rect, stroke_rect};
use crate::error::RenderError;
use crate::text::{
    draw_text, draw_text_vertical, format_number, text_width, HAlign, TextSize, TextStyle, VAlign,
};
use crate::ticks::ticks;
pub use crate::ticks::AxisScale;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SeriesStyle {
    /// Connected line.
    Line,
    /// Dots only.
    Scatter,
    /// Connected line with a dot at each point.
    LineAndMarkers,
}

/// One named data series.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Name shown in the legend (empty: not listed).
    pub name: String,
    /// `(x, y)` points in data units, drawn in the given order.
    pub points: Vec<(f64, f64)>,
    /// Drawing style.
    pub style: SeriesStyle,
    /// Colour; `None` picks the next colour of the built-in palette.
    pub color: Option<[u8; 3]>,
}

impl Series {
    /// A series with the palette colour.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>, style: SeriesStyle) -> Self {
        Series {
            name: name.into(),
            points,
            style,
            color: None,
        }
    }
}

/// One axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Axis label.
    pub label: String,
    /// Linear or logarithmic.
    pub scale: AxisScale,
    /// Fixed range in data units; `None` fits the data.
    pub range: Option<(f64, f64)>,
}

impl Axis {
    /// An axis fitted to the data.
    pub fn new(label: impl Into<String>, scale: AxisScale) -> Self {
        Axis {
            label: label.into(),
            scale,
            range: None,
        }
    }
}

/// A plot: axes, series, title and size.
#[derive(Debug, Clone, PartialEq)]
pub struct Plot {
    /// Title at the top.
    pub title: String,
    /// Horizontal axis.
    pub x: Axis,
    /// Vertical axis.
    pub y: Axis,
    /// Data.
    pub series: Vec<Series>,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

/// The colours series get in turn when they name none (sRGB).
pub const PALETTE: [[u8; 3]; 8] = [
    [31, 119, 180],
    [214, 39, 40],
    [44, 160, 44],
    [255, 127, 14],
    [148, 103, 189],
    [140, 86, 75],
    [227, 119, 194],
    [23, 190, 207],
];

/// The range of the axis: fixed, or fitted to the drawable values with a margin.
fn axis_range(axis: &Axis, values: &[f64], name: &str) -> Result<(f64, f64), RenderError> {
    if let Some((a, b)) = axis.range {
        if !(axis.scale.accepts(a) && axis.scale.accepts(b) && a < b) {
            return Err(RenderError::InvalidOption {
                name: "plot axis range",
                value: format!("{a}..{b}"),
                reason: "must be increasing, finite, and positive on a log axis",
            });
        }
        return Ok((a, b));
    }
    let usable: Vec<f64> = values
        .iter()
        .copied()
        .filter(|&v| axis.scale.accepts(v))
        .collect();
    if usable.is_empty() {
        return Err(RenderError::NoPlotData(format!(
            "no {name} value can be drawn on a {:?} axis",
            axis.scale
        )));
    }
    let lo = usable.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = usable.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Ok(match axis.scale {
        AxisScale::Linear => {
            let pad = if hi > lo {
                0.04 * (hi - lo)
            } else {
                0.5 * lo.abs().max(1.0)
            };
            (lo - pad, hi + pad)
        }
        AxisScale::Log10 => {
            let (a, b) = (lo.log10(), hi.log10());
            let pad = if b > a { 0.04 * (b - a) } else { 0.5 };
            (10f64.powf(a - pad), 10f64.powf(b + pad))
        }
    })
}

/// Where the plot area lies in the image and how data map to it.
struct PlotFrame {
    /// Left and top margins (pixels): the plot area starts there.
    left: f64,
    top: f64,
    /// Width and height of the plot area (pixels).
    pw: f64,
    ph: f64,
    x_scale: AxisScale,
    y_scale: AxisScale,
    /// The axis ends through the scales (`forward(x0)`, `forward(x1)`, …).
    fx: (f64, f64),
    fy: (f64, f64),
}

impl PlotFrame {
    /// Horizontal pixel of `x` in the plot area.
    fn to_px(&self, x: f64) -> f64 {
        (self.x_scale.forward(x) - self.fx.0) / (self.fx.1 - self.fx.0) * self.pw
    }

    /// Vertical pixel of `y` in the plot area (down from its top).
    fn to_py(&self, y: f64) -> f64 {
        self.ph - (self.y_scale.forward(y) - self.fy.0) / (self.fy.1 - self.fy.0) * self.ph
    }
}

/// Major and minor ticks of both axes (data units).
struct PlotTicks {
    x_major: Vec<f64>,
    x_minor: Vec<f64>,
    y_major: Vec<f64>,
    y_minor: Vec<f64>,
}

impl Plot {
    /// Draws the plot. Points that cannot be drawn (non-finite, or non-positive on a log
    /// axis) are skipped, and a line is broken there. Fails when no point at all can be
    /// drawn, on a size below 200×150 or above 16384, or on an invalid fixed range.
    pub fn render(&self) -> Result<RgbaImage, RenderError> {
        if !(200..=16384).contains(&self.width) || !(150..=16384).contains(&self.height) {
            return Err(RenderError::InvalidSize {
                width: self.width,
                height: self.height,
            });
        }
        let xs: Vec<f64> = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.0))
            .collect();
        let ys: Vec<f64> = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .collect();
        let (x0, x1) = axis_range(&self.x, &xs, "x")?;
        let (y0, y1) = axis_range(&self.y, &ys, "y")?;
        let (w, h) = (self.width as f64, self.height as f64);
        let size = TextSize::for_height((h / 32.0).clamp(16.0, 32.0));
        let small = TextSize::for_height(size.height() as f64 * 0.8);
        let th = size.height() as f64;
        let tick_style = TextStyle::new(small);
        let (y_major, y_minor) = ticks(self.y.scale, y0, y1);
        let (x_major, x_minor) = ticks(self.x.scale, x0, x1);
        let ticks = PlotTicks {
            x_major,
            x_minor,
            y_major,
            y_minor,
        };
        let y_label_width = ticks
            .y_major
            .iter()
            .map(|&v| text_width(&format_number(v, 3), &tick_style))
            .max()
            .unwrap_or(0) as f64;
        let left = (th + 14.0 + y_label_width + 10.0).round();
        let right = 24.0;
        let top = (th * 2.0).round();
        let bottom = (small.height() as f64 + th + 24.0).round();
        let (pw, ph) = (w - left - right, h - top - bottom);
        if pw < 40.0 || ph < 40.0 {
            return Err(RenderError::InvalidSize {
                width: self.width,
                height: self.height,
            });
        }
        let frame = PlotFrame {
            left,
            top,
            pw,
            ph,
            x_scale: self.x.scale,
            y_scale: self.y.scale,
            fx: (self.x.scale.forward(x0), self.x.scale.forward(x1)),
            fy: (self.y.scale.forward(y0), self.y.scale.forward(y1)),
        };

        let mut image = RgbaImage::from_pixel(self.width, self.height, Rgba([255, 255, 255, 255]));
        // Grid and data on the plot layer (clipped to the plot area).
        let mut layer = RgbaImage::new(pw as u32, ph as u32);
        draw_grid(&mut layer, &frame, &ticks);
        let line_width = (h / 300.0).clamp(1.5, 4.0);
        let legend = self.draw_series(&mut layer, &frame, line_width);
        overlay(&mut image, &layer, left as i64, top as i64);
        stroke_rect(
            &mut image,
            left as i64 - 1,
            top as i64 - 1,
            (left + pw) as i64,
            (top + ph) as i64,
            [60, 60, 60],
        );
        draw_tick_labels(&mut image, &frame, &ticks, &tick_style);
        self.draw_labels(&mut image, &frame, size);
        draw_legend(
            &mut image,
            &legend,
            left + pw - 10.0,
            top + 10.0,
            small,
            line_width,
        );
        Ok(image)
    }

    /// Draws every series on the plot `layer` (lines `line_width` pixels wide, dots 1.6 times
    /// that) and returns the legend entries of the named ones.
    fn draw_series(
        &self,
        layer: &mut RgbaImage,
        frame: &PlotFrame,
        line_width: f64,
    ) -> Vec<(&str, [u8; 3], SeriesStyle)> {
        let mut legend = Vec::new();
        for (k, s) in self.series.iter().enumerate() {
            let color = s.color.unwrap_or(PALETTE[k % PALETTE.len()]);
            let mut previous: Option<[f64; 2]> = None;
            for &(x, y) in &s.points {
                if !(self.x.scale.accepts(x) && self.y.scale.accepts(y)) {
                    previous = None;
                    continue;
                }
                let p = [frame.to_px(x), frame.to_py(y)];
                if let (Some(q), SeriesStyle::Line | SeriesStyle::LineAndMarkers) =
                    (previous, s.style)
                {
                    draw_line(layer, q, p, line_width, color);
                }
                if matches!(s.style, SeriesStyle::Scatter | SeriesStyle::LineAndMarkers) {
                    fill_disc(layer, p, 1.6 * line_width, color);
                }
                previous = Some(p);
            }
            if !s.name.is_empty() {
                legend.push((s.name.as_str(), color, s.style));
            }
        }
        legend
    }

    /// The axis labels (the y label vertical, left) and the title (bold, top centre), in text
    /// of `size`.
    fn draw_labels(&self, image: &mut RgbaImage, frame: &PlotFrame, size: TextSize) {
        let (w, h) = (self.width as f64, self.height as f64);
        let th = size.height() as f64;
        let label_style = TextStyle::new(size);
        draw_text(
            image,
            frame.left + 0.5 * frame.pw,
            h - 6.0,
            &self.x.label,
            &label_style.aligned(HAlign::Center, VAlign::Bottom),
        );
        draw_text_vertical(
            image,
            6.0 + 0.5 * th,
            frame.top + 0.5 * frame.ph,
            &self.y.label,
            &label_style,
        );
        draw_text(
            image,
            0.5 * w,
            0.5 * frame.top,
            &self.title,
            &label_style.bold().aligned(HAlign::Center, VAlign::Middle),
        );
    }
}

/// Grid lines on the plot `layer`: minor ones light, major ones darker, above the minor ones.
fn draw_grid(layer: &mut RgbaImage, frame: &PlotFrame, ticks: &PlotTicks) {
    const MINOR: [u8; 3] = [238, 238, 238];
    const MAJOR: [u8; 3] = [215, 215, 215];
    let (pw, ph) = (frame.pw, frame.ph);
    for (x_values, y_values, colour) in [
        (&ticks.x_minor, &ticks.y_minor, MINOR),
        (&ticks.x_major, &ticks.y_major, MAJOR),
    ] {
        for &v in x_values {
            let x = frame.to_px(v);
            draw_line(layer, [x, 0.0], [x, ph], 1.0, colour);
        }
        for &v in y_values {
            let y = frame.to_py(v);
            draw_line(layer, [0.0, y], [pw, y], 1.0, colour);
        }
    }
}

/// Tick marks and the labels of the major ticks, outside the plot area (below it and left of
/// it).
fn draw_tick_labels(
    image: &mut RgbaImage,
    frame: &PlotFrame,
    ticks: &PlotTicks,
    tick_style: &TextStyle,
) {
    let (left, top, ph) = (frame.left, frame.top, frame.ph);
    for &v in &ticks.x_major {
        let x = left + frame.to_px(v);
        draw_line(image, [x, top + ph], [x, top + ph + 5.0], 1.0, [60, 60, 60]);
        let style = tick_style.aligned(HAlign::Center, VAlign::Top);
        draw_text(image, x, top + ph + 7.0, &format_number(v, 3), &style);
    }
    for &v in &ticks.y_major {
        let y = top + frame.to_py(v);
        draw_line(image, [left - 5.0, y], [left, y], 1.0, [60, 60, 60]);
        let style = tick_style.aligned(HAlign::Right, VAlign::Middle);
        draw_text(image, left - 8.0, y, &format_number(v, 3), &style);
    }
}

fn overlay(image: &mut RgbaImage, layer: &RgbaImage, left: i64, top: i64) {
    for (x, y, p) in layer.enumerate_pixels() {
        if p.0[3] > 0 {
            let c = [p.0[0], p.0[1], p.0[2]];
            blend(
                image,
                left + x as i64,
                top + y as i64,
                c,
                p.0[3] as f32 / 255.0,
            );
        }
    }
}

/// Legend box anchored at its top-right corner `(right, top)`.
fn draw_legend(
    image: &mut RgbaImage,
    entries: &[(&str, [u8; 3], SeriesStyle)],
    right: f64,
    top: f64,
    size: TextSize,
    line_width: f64,
) {
    if entries.is_empty() {
        return;
    }
    let style = TextStyle::new(size).aligned(HAlign::Left, VAlign::Middle);
    let row = size.height() as f64 + 6.0;
    let sample = 28.0;
    let widest = entries
        .iter()
        .map(|e| text_width(e.0, &style))
        .max()
        .unwrap_or(0) as f64;
    let bw = widest + sample + 26.0;
    let bh = row * entries.len() as f64 + 10.0;
    let x0 = right - bw;
    // The legend box in pixels: left, top, right, bottom.
    let (l, t, r, b) = (x0 as i64, top as i64, right as i64, (top + bh) as i64);
    fill_rect(image, l, t, r, b, [255, 255, 255]);
    stroke_rect(image, l, t, r, b, [150, 150, 150]);
    for (i, (name, color, s)) in entries.iter().enumerate() {
        let y = top + 5.0 + row * (i as f64 + 0.5);
        let a = [x0 + 8.0, y];
        let b = [x0 + 8.0 + sample, y];
        if matches!(s, SeriesStyle::Line | SeriesStyle::LineAndMarkers) {
            draw_line(image, a, b, line_width, *color);
        }
        if matches!(s, SeriesStyle::Scatter | SeriesStyle::LineAndMarkers) {
            fill_disc(image, [0.5 * (a[0] + b[0]), y], 1.6 * line_width, *color);
        }
        draw_text(image, b[0] + 8.0, y, name, &style);
    }
}
