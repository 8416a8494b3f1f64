//! Demo step 5: papers/'s Figure 9 on the demo's test field: relative error against bits per
//! vertex for 64-bit coefficients (the paper's rate) and for quantised, range-coded ones.

use super::page::Section;
use super::Context;
use crate::compression::{figure9, rate_curve};
use crate::error::FigureError;
use tvf_spectral::{equal_error_comparison, CoefficientCoding};

/// Codings compared: the paper's 64-bit coefficients and two quantiser symbol sizes.
const CODINGS: [CoefficientCoding; 3] = [
    CoefficientCoding::Float64,
    CoefficientCoding::Quantized { bits: 8 },
    CoefficientCoding::Quantized { bits: 12 },
];

/// Compresses `field` with every coding at the pair counts of Figure 9 and plots the curves.
pub fn run(cx: &Context, field: &[f64]) -> Result<Section, FigureError> {
    let x = cx.experiment();
    let curves = CODINGS
        .iter()
        .map(|&coding| rate_curve(&x, field, "test field", coding))
        .collect::<Result<Vec<_>, _>>()?;
    let mut section = Section::from_finding(&figure9(&curves, &cx.config.output, cx.plot_size())?);
    let points: Vec<_> = curves
        .iter()
        .flat_map(|c| c.points.iter().cloned())
        .collect();
    if let Some((exact, quantised)) = equal_error_comparison(&points).last() {
        section.number(
            format!("at P = {} pairs the same error or less", exact.pairs),
            format!(
                "{} ({} pairs): {} bytes instead of {} ({:.1}× smaller)",
                quantised.coding.label(),
                quantised.pairs,
                quantised.bytes,
                exact.bytes,
                exact.bytes as f64 / quantised.bytes as f64
            ),
        );
    }
    Ok(section)
}
