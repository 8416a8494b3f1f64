//! Demo step 2: the lowest eigenfield pairs (papers/'s Figure 1 on the demo's mesh) and the
//! harmonic fields.

use super::page::Section;
use super::Context;
use crate::eigenfields_and_filtering::figure1;
use crate::error::FigureError;
use tvf_render::{draw_field, grid, FaceQuantity, Overlays, Style, Tint};
use tvf_spectral::FieldFamily;

/// The pairs shown (1-based): the lowest three, where the paper shows the 1st, 21st, 51st and
/// 71st of a basis of 500 pairs.
const PAIRS_SHOWN: [usize; 3] = [1, 2, 3];

/// Harmonic fields shown at most.
const HARMONIC_SHOWN: usize = 4;

/// Figure 1 on the demo's basis, then the harmonic fields.
pub fn run(cx: &Context) -> Result<Section, FigureError> {
    let mut section = Section::from_finding(&figure1(&cx.experiment(), &PAIRS_SHOWN)?);
    let harmonic: Vec<usize> = (0..cx.basis.len())
        .filter(|&i| cx.basis.families()[i] == FieldFamily::Harmonic)
        .collect();
    if !harmonic.is_empty() {
        let panels = harmonic
            .iter()
            .take(HARMONIC_SHOWN)
            .enumerate()
            .map(|(k, &i)| {
                let field: Vec<f64> = cx.basis.fields().col(i).iter().copied().collect();
                draw_field(
                    cx.mesh,
                    cx.discretization.as_ref(),
                    Some(&field),
                    Tint::Quantity(FaceQuantity::Magnitude),
                    Style::Lic,
                    Overlays::titled(format!("harmonic {}", k + 1)),
                    cx.panel_view(),
                )
            })
            .collect::<Result<Vec<_>, _>>()?;
        cx.save(&grid(&panels, 2), "harmonic.png")?;
        section.figure(
            "harmonic.png",
            "Harmonic fields (eigenvalue 0: neither divergence nor curl): 2g on a closed surface, \
             2g + b − 1 with b boundary loops.",
        );
    }
    section.number("harmonic fields", harmonic.len().to_string());
    Ok(section)
}
