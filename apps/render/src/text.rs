//! Text drawn from an embedded, pre-rasterised font (Noto Sans Mono, anti-aliased bitmaps
//! from the `noto-sans-mono-bitmap` crate): no system fonts are read at run time.

use image::RgbaImage;
use noto_sans_mono_bitmap::{get_raster, get_raster_width, FontWeight, RasterHeight};

use crate::canvas::blend;

/// Text height in pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextSize {
    /// 16 pixels.
    Small,
    /// 20 pixels.
    Medium,
    /// 24 pixels.
    Large,
    /// 32 pixels.
    Huge,
}

impl TextSize {
    fn raster(self) -> RasterHeight {
        match self {
            TextSize::Small => RasterHeight::Size16,
            TextSize::Medium => RasterHeight::Size20,
            TextSize::Large => RasterHeight::Size24,
            TextSize::Huge => RasterHeight::Size32,
        }
    }

    /// Line height in pixels.
    pub fn height(self) -> u32 {
        self.raster().val() as u32
    }

    /// The size whose height is closest to `pixels`.
    pub fn for_height(pixels: f64) -> TextSize {
        [
            TextSize::Small,
            TextSize::Medium,
            TextSize::Large,
            TextSize::Huge,
        ]
        .into_iter()
        .min_by(|a, b| {
            let da = (a.height() as f64 - pixels).abs();
            let db = (b.height() as f64 - pixels).abs();
            da.total_cmp(&db)
        })
        .unwrap_or(TextSize::Small)
    }
}

/// Horizontal placement of a text relative to its anchor point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HAlign {
    /// Anchor at the left end.
    Left,
    /// Anchor at the middle.
    Center,
    /// Anchor at the right end.
    Right,
}

/// Vertical placement of a text relative to its anchor point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VAlign {
    /// Anchor at the top.
    Top,
    /// Anchor at the middle.
    Middle,
    /// Anchor at the bottom.
    Bottom,
}

/// Style of a text.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextStyle {
    /// Height.
    pub size: TextSize,
    /// Bold or regular.
    pub bold: bool,
    /// sRGB colour.
    pub color: [u8; 3],
    /// Horizontal alignment.
    pub halign: HAlign,
    /// Vertical alignment.
    pub valign: VAlign,
}

impl TextStyle {
    /// Regular black text, anchored at its top-left corner.
    pub fn new(size: TextSize) -> Self {
        TextStyle {
            size,
            bold: false,
            color: [20, 20, 20],
            halign: HAlign::Left,
            valign: VAlign::Top,
        }
    }

    /// The same style with another alignment.
    pub fn aligned(mut self, halign: HAlign, valign: VAlign) -> Self {
        self.halign = halign;
        self.valign = valign;
        self
    }

    /// The same style in bold.
    pub fn bold(mut self) -> Self {
        self.bold = true;
        self
    }

    /// The same style in another colour.
    pub fn colored(mut self, color: [u8; 3]) -> Self {
        self.color = color;
        self
    }

    fn weight(&self) -> FontWeight {
        if self.bold {
            FontWeight::Bold
        } else {
            FontWeight::Regular
        }
    }
}

/// Width in pixels of `text` (monospaced).
pub fn text_width(text: &str, style: &TextStyle) -> u32 {
    (text.chars().count() * get_raster_width(style.weight(), style.size.raster())) as u32
}

/// Draws `text` horizontally at the anchor `(x, y)`; characters the font lacks print as `?`.
pub fn draw_text(image: &mut RgbaImage, x: f64, y: f64, text: &str, style: &TextStyle) {
    let (left, top) = origin(x, y, text, style);
    let advance = get_raster_width(style.weight(), style.size.raster()) as i64;
    for (i, c) in text.chars().enumerate() {
        let glyph = get_raster(c, style.weight(), style.size.raster())
            .or_else(|| get_raster('?', style.weight(), style.size.raster()));
        let Some(glyph) = glyph else { continue };
        let gx = left + i as i64 * advance;
        for (row, line) in glyph.rows().enumerate() {
            for (col, &a) in line.iter().enumerate() {
                if a > 0 {
                    let px = gx + col as i64;
                    let py = top + row as i64;
                    blend(image, px, py, style.color, a as f32 / 255.0);
                }
            }
        }
    }
}

/// Draws `text` turned a quarter turn counter-clockwise (reading bottom to top), centred
/// on `(x, y)`: used for vertical axis labels.
pub fn draw_text_vertical(image: &mut RgbaImage, x: f64, y: f64, text: &str, style: &TextStyle) {
    let width = text_width(text, style) as i64;
    let height = style.size.height() as i64;
    let advance = get_raster_width(style.weight(), style.size.raster()) as i64;
    // Unrotated coordinates (u along the text, v down) map to image (x0 + v, y0 - u).
    let x0 = x.round() as i64 - height / 2;
    let y0 = y.round() as i64 + width / 2;
    for (i, c) in text.chars().enumerate() {
        let glyph = get_raster(c, style.weight(), style.size.raster())
            .or_else(|| get_raster('?', style.weight(), style.size.raster()));
        let Some(glyph) = glyph else { continue };
        for (row, line) in glyph.rows().enumerate() {
            for (col, &a) in line.iter().enumerate() {
                if a > 0 {
                    let u = i as i64 * advance + col as i64;
                    blend(
                        image,
                        x0 + row as i64,
                        y0 - u,
                        style.color,
                        a as f32 / 255.0,
                    );
                }
            }
        }
    }
}

fn origin(x: f64, y: f64, text: &str, style: &TextStyle) -> (i64, i64) {
    let w = text_width(text, style) as f64;
    let h = style.size.height() as f64;
    let left = match style.halign {
        HAlign::Left => x,
        HAlign::Center => x - w / 2.0,
        HAlign::Right => x - w,
    };
    let top = match style.valign {
        VAlign::Top => y,
        VAlign::Middle => y - h / 2.0,
        VAlign::Bottom => y - h,
    };
    (left.round() as i64, top.round() as i64)
}

/// Formats a number compactly for labels: plain decimals between 1e-3 and 1e5,
/// scientific notation (`1.5e-7`) outside, at most `digits` significant digits.
pub fn format_number(value: f64, digits: usize) -> String {
    if value == 0.0 {
        return "0".to_string();
    }
    if !value.is_finite() {
        return format!("{value}");
    }
    let digits = digits.max(1);
    let magnitude = value.abs().log10().floor() as i32;
    if (-3..5).contains(&magnitude) {
        let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
        let s = format!("{value:.decimals$}");
        trim_zeros(&s)
    } else {
        let s = format!("{:.*e}", digits - 1, value);
        match s.split_once('e') {
            Some((mantissa, exponent)) => format!("{}e{}", trim_zeros(mantissa), exponent),
            None => s,
        }
    }
}

fn trim_zeros(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_compact() {
        assert_eq!(format_number(0.0, 3), "0");
        assert_eq!(format_number(1.0, 3), "1");
        assert_eq!(format_number(0.25, 3), "0.25");
        assert_eq!(format_number(1234.7, 3), "1235");
        assert_eq!(format_number(1.5e-7, 3), "1.5e-7");
        assert_eq!(format_number(-2.0e6, 2), "-2e6");
    }
}
