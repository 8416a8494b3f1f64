//! Demo step 3: the Hodge decomposition of a test field into integrable, co-integrable and
//! harmonic parts.

use super::page::Section;
use super::Context;
use crate::error::FigureError;
use crate::test_fields::smooth_field;
use tvf_core::discretization::HodgeOperators;
use tvf_discretizations::HodgeDecomposer;
use tvf_render::{draw_field, grid, FaceQuantity, Overlays, Style, Tint};

/// Decomposes the test field, draws it and its parts; returns the section and the field.
pub fn run(cx: &Context) -> Result<(Section, Vec<f64>), FigureError> {
    let mut section = Section::new(
        "Hodge decomposition",
        "A test field (a gradient, a rotated gradient and a swirl about the torus axis) and its \
         three M_X-orthogonal parts: integrable (curl-free), co-integrable (divergence-free) and \
         harmonic. Colour: divergence for the integrable part, curl for the co-integrable part, \
         magnitude otherwise.",
    );
    let (field, parts, inner) = {
        let c = cx.discretization.as_ref();
        {
            let field = smooth_field(c, cx.mesh);
            let parts = HodgeDecomposer::new(c)?.decompose(&field)?;
            let inner = |a: &[f64], b: &[f64]| c.field_inner(a, b);
            let products = [
                inner(&parts.integrable, &parts.integrable),
                inner(&parts.cointegrable, &parts.cointegrable),
                inner(&parts.harmonic, &parts.harmonic),
                inner(&parts.integrable, &parts.cointegrable),
                inner(&parts.integrable, &parts.harmonic),
                inner(&parts.cointegrable, &parts.harmonic),
                inner(&field, &field),
            ];
            (field, parts, products)
        }
    };
    let panels = [
        (
            "test field",
            field.as_slice(),
            Tint::Quantity(FaceQuantity::Magnitude),
        ),
        (
            "integrable part (colour: divergence)",
            &parts.integrable,
            Tint::Quantity(FaceQuantity::Divergence),
        ),
        (
            "co-integrable part (colour: curl)",
            &parts.cointegrable,
            Tint::Quantity(FaceQuantity::Curl),
        ),
        (
            "harmonic part",
            &parts.harmonic,
            Tint::Quantity(FaceQuantity::Magnitude),
        ),
    ];
    let mut images = Vec::new();
    for (title, part, color) in panels {
        let overlays = Overlays {
            title: Some(title.to_string()),
            ..Default::default()
        };
        images.push(draw_field(
            cx.mesh,
            cx.discretization.as_ref(),
            Some(part),
            color,
            Style::Streamlines,
            overlays,
            cx.panel_view(),
        )?);
    }
    cx.save(&grid(&images, 2), "hodge.png")?;
    section.figure(
        "hodge.png",
        "Top: the field and its integrable part; bottom: its co-integrable and harmonic parts.",
    );
    let total = inner[6];
    section.number(
        "energy shares ‖·‖²/‖v‖² (integrable, co-integrable, harmonic)",
        format!(
            "{:.4}, {:.4}, {:.4} (sum {:.6})",
            inner[0] / total,
            inner[1] / total,
            inner[2] / total,
            (inner[0] + inner[1] + inner[2]) / total
        ),
    );
    let norms = [inner[0].sqrt(), inner[1].sqrt(), inner[2].sqrt()];
    let cosine = [
        inner[3] / (norms[0] * norms[1]).max(1e-300),
        inner[4] / (norms[0] * norms[2]).max(1e-300),
        inner[5] / (norms[1] * norms[2]).max(1e-300),
    ];
    section.number(
        "largest |cos| between two parts (orthogonality)",
        format!("{:.2e}", cosine.iter().fold(0.0f64, |m, c| m.max(c.abs()))),
    );
    Ok((section, field))
}
