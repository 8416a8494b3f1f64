//! The colour bar with its min/max labels, and the title.

use image::RgbaImage;

use crate::canvas::{fill_rect, stroke_rect};
use crate::colormap::ColorScale;
use crate::text::{draw_text, format_number, text_width, HAlign, TextSize, TextStyle, VAlign};

/// Horizontal space (pixels) a colour bar with these labels needs at the right edge.
pub(crate) fn colorbar_margin(scale: &ColorScale, label: &str, size: TextSize) -> u32 {
    let style = TextStyle::new(size);
    let labels = [format_number(scale.min, 3), format_number(scale.max, 3)];
    let widest = labels
        .iter()
        .map(|s| text_width(s, &style))
        .max()
        .unwrap_or(0);
    let bar = bar_width(size);
    let label_width = text_width(label, &style);
    (bar + 12 + widest).max(label_width) + 24
}

fn bar_width(size: TextSize) -> u32 {
    size.height()
}

/// Draws the vertical colour bar at the right edge: `max` at the top, `min` at the bottom
/// (and `0` in the middle for a diverging map), with `label` above it.
pub(crate) fn draw_colorbar(
    image: &mut RgbaImage,
    scale: &ColorScale,
    label: &str,
    size: TextSize,
) {
    let (w, h) = (image.width() as i64, image.height() as i64);
    let margin = colorbar_margin(scale, label, size) as i64;
    let bar = bar_width(size) as i64;
    let x0 = w - margin + 12;
    let text_h = size.height() as i64;
    let y0 = (h / 5).max(2 * text_h + 8);
    let y1 = (h - h / 5).max(y0 + 20);
    for y in y0..=y1 {
        let t = (y1 - y) as f64 / (y1 - y0) as f64;
        let value = scale.min + t * (scale.max - scale.min);
        fill_rect(image, x0, y, x0 + bar, y + 1, scale.color(value));
    }
    stroke_rect(image, x0 - 1, y0 - 1, x0 + bar, y1 + 1, [40, 40, 40]);
    let style = TextStyle::new(size);
    let lx = (x0 + bar + 6) as f64;
    let label_style = style.aligned(HAlign::Left, VAlign::Middle);
    for (y, value) in [(y0, scale.max), (y1, scale.min)] {
        draw_text(image, lx, y as f64, &format_number(value, 3), &label_style);
    }
    if scale.map.is_diverging() {
        draw_text(
            image,
            lx,
            0.5 * (y0 + y1) as f64,
            "0",
            &style.aligned(HAlign::Left, VAlign::Middle),
        );
    }
    draw_text(
        image,
        (x0 + bar / 2) as f64,
        (y0 - text_h / 2 - 4) as f64,
        label,
        &style.bold().aligned(HAlign::Center, VAlign::Bottom),
    );
}

/// Draws `title` centred at the top.
pub(crate) fn draw_title(image: &mut RgbaImage, title: &str, size: TextSize) {
    let style = TextStyle::new(size)
        .bold()
        .aligned(HAlign::Center, VAlign::Top);
    draw_text(image, 0.5 * image.width() as f64, 6.0, title, &style);
}
