//! Demo step 2 (paper Figure 1): the lowest eigenfields, integrable beside co-integrable, and
//! the harmonic fields.

use super::page::Section;
use super::Context;
use crate::face_quantities::ColorBy;
use crate::picture::{draw, grid, Overlays, Style};
use anyhow::Result;
use tvf_spectral::FieldFamily;

/// Pairs shown.
const PAIRS_SHOWN: usize = 3;

/// Draws basis field `index` as one panel.
fn panel(cx: &Context, index: usize, title: String) -> Result<image::RgbaImage> {
    let field: Vec<f64> = cx.basis.fields().col(index).iter().copied().collect();
    let overlays = Overlays {
        title: Some(title),
        ..Default::default()
    };
    draw(
        cx.mesh,
        cx.discretization,
        Some(&field),
        ColorBy::Magnitude,
        Style::Lic,
        overlays,
        cx.panel_view(),
    )
}

/// Renders the pairs grid and the harmonic fields.
pub fn run(cx: &Context) -> Result<Section> {
    let mut section = Section::new(
        "Eigenfields (Figure 1)",
        "The lowest eigenfields of the Hodge–Laplacian: left the integrable ones (normalised \
         gradients of Laplace eigenfunctions, curl-free), right the co-integrable ones \
         (rotated gradients of Crouzeix–Raviart eigenfunctions, divergence-free); line \
         integral convolution shows the direction, colour the magnitude.",
    );
    let of = |family| -> Vec<usize> {
        (0..cx.basis.len())
            .filter(|&i| cx.basis.families()[i] == family)
            .collect()
    };
    let integrable = of(FieldFamily::Integrable);
    let cointegrable = of(FieldFamily::Cointegrable);
    let harmonic = of(FieldFamily::Harmonic);
    let lambda = |i: usize| cx.basis.eigenvalues()[i];
    let mut panels = Vec::new();
    for k in 0..PAIRS_SHOWN.min(integrable.len()).min(cointegrable.len()) {
        let (a, b) = (integrable[k], cointegrable[k]);
        panels.push(panel(
            cx,
            a,
            format!("integrable {}  lambda = {:.3}", k + 1, lambda(a)),
        )?);
        panels.push(panel(
            cx,
            b,
            format!("co-integrable {}  lambda = {:.3}", k + 1, lambda(b)),
        )?);
        section.number(
            format!("pair {}: eigenvalues", k + 1),
            format!(
                "{:.4} (integrable), {:.4} (co-integrable)",
                lambda(a),
                lambda(b)
            ),
        );
    }
    if !panels.is_empty() {
        cx.save(&grid(&panels, 2), "eigenfields.png")?;
        section.figure(
            "eigenfields.png",
            "The three lowest eigenfield pairs: integrable (left) and co-integrable (right).",
        );
    }
    if !harmonic.is_empty() {
        let panels = harmonic
            .iter()
            .take(4)
            .enumerate()
            .map(|(k, &i)| panel(cx, i, format!("harmonic {}", k + 1)))
            .collect::<Result<Vec<_>>>()?;
        cx.save(&grid(&panels, 2), "harmonic.png")?;
        section.figure(
            "harmonic.png",
            "Harmonic fields (eigenvalue 0: neither divergence nor curl), 2g of them.",
        );
    }
    section.number("harmonic fields", harmonic.len().to_string());
    Ok(section)
}
