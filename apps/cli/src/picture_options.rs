//! Picture options of the command line: parsing of views, sizes, colour quantities and field
//! styles (the pictures themselves are `tvf_render::draw_field`, constraint markers
//! `tvf_figures::constraint_markers`).

use anyhow::{bail, Result};
use tvf_render::{FaceQuantity, Style};

/// Parses `YAW,PITCH` in degrees.
pub fn parse_view(text: &str) -> Result<(f64, f64)> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if let [yaw, pitch] = parts[..] {
        if let (Ok(yaw), Ok(pitch)) = (yaw.parse::<f64>(), pitch.parse::<f64>()) {
            if yaw.is_finite() && pitch.is_finite() {
                return Ok((yaw, pitch));
            }
        }
    }
    bail!("'{text}' is not a view: give YAW,PITCH in degrees, e.g. 30,20")
}

/// Parses `WxH` in pixels (each 16..=16384).
pub fn parse_size(text: &str) -> Result<(u32, u32)> {
    let lower = text.to_ascii_lowercase();
    if let Some((w, h)) = lower.split_once('x') {
        if let (Ok(w), Ok(h)) = (w.trim().parse::<u32>(), h.trim().parse::<u32>()) {
            if (16..=16384).contains(&w) && (16..=16384).contains(&h) {
                return Ok((w, h));
            }
        }
    }
    bail!("'{text}' is not an image size: give WxH with each side 16..16384, e.g. 800x600")
}

/// Accepts a per-face quantity name (magnitude, divergence, curl, energy, none).
pub fn face_quantity_arg(text: &str) -> Result<FaceQuantity, String> {
    FaceQuantity::from_name(text)
        .ok_or_else(|| format!("'{text}' is not one of: {}", FaceQuantity::NAMES.join(", ")))
}

/// Accepts a field style name (arrows, streamlines, lic, none).
pub fn style_arg(text: &str) -> Result<Style, String> {
    Style::from_name(text)
        .ok_or_else(|| format!("'{text}' is not one of: {}", Style::NAMES.join(", ")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn views_and_sizes_parse_and_reject_garbage() {
        assert_eq!(parse_view("30,-15").unwrap(), (30.0, -15.0));
        assert!(parse_view("30").is_err());
        assert!(parse_view("a,b").is_err());
        assert_eq!(parse_size("800x600").unwrap(), (800, 600));
        assert_eq!(parse_size("64X48").unwrap(), (64, 48));
        assert!(parse_size("8x600").is_err());
        assert!(parse_size("800").is_err());
    }
}
