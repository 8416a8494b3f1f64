//! Demo step 5 (paper Figure 9): spectral compression of the test field, relative error
//! against bits per vertex for 64-bit and for quantised, range-coded coefficients.

use super::page::Section;
use super::Context;
use crate::commands::rate_distortion::{coding_label, rate_distortion_plot};
use anyhow::Result;
use tvf_spectral::{
    basis_id, equal_error_comparison, mesh_fingerprint, rate_distortion, CoefficientCoding,
    FieldFamily, FileStamp,
};

/// Quantiser symbol sizes shown.
const BITS: [u32; 2] = [8, 12];

/// Compresses `field` at several numbers of pairs and plots the curves.
pub fn run(cx: &Context, field: &[f64]) -> Result<Section> {
    // Pairs the basis can keep: the smaller family decides.
    let pairs_available = cx
        .basis
        .count(FieldFamily::Integrable)
        .min(cx.basis.count(FieldFamily::Cointegrable));
    let mut ks: Vec<usize> = std::iter::successors(Some(2usize), |k| Some(k * 2))
        .take_while(|&k| k < pairs_available)
        .collect();
    ks.push(pairs_available);
    let stamp = FileStamp {
        mesh_fingerprint: mesh_fingerprint(cx.mesh),
        basis_id: basis_id(cx.basis),
        vertex_count: cx.mesh.vertex_count(),
    };
    let mut codings = vec![CoefficientCoding::Float64];
    codings.extend(
        BITS.iter()
            .map(|&bits| CoefficientCoding::Quantized { bits }),
    );
    let points = rate_distortion(cx.basis, field, stamp, &ks, &codings)?;
    let plot = rate_distortion_plot(
        &points,
        &codings,
        "Rate-distortion of spectral compression".to_string(),
        (
            cx.config.width.max(200),
            (cx.config.height * 3 / 4).max(150),
        ),
    );
    cx.save(&plot.render()?, "rate_distortion.png")?;
    let mut section = Section::new(
        "Compression: rate and distortion (Figure 9)",
        "The test field stored as its lowest P coefficient pairs in a .tvfc file: as 64-bit \
         numbers (the paper's rate) or quantised and range-coded. Every point is a real file \
         (size with header and checksum) and its error is measured on the decoded field.",
    );
    section.figure(
        "rate_distortion.png",
        "Relative L2 error against bits per vertex (log–log), one curve per coding.",
    );
    for p in points
        .iter()
        .filter(|p| p.coding == CoefficientCoding::Float64)
    {
        section.number(
            format!("P = {} pairs, 64-bit", p.pairs),
            format!(
                "{} bytes, {:.2} bits/vertex, error {:.3e}",
                p.bytes, p.bits_per_vertex, p.relative_error
            ),
        );
    }
    if let Some((exact, quantised)) = equal_error_comparison(&points).last() {
        section.number(
            format!("at P = {} pairs the same error or less", exact.pairs),
            format!(
                "{} ({} pairs): {} bytes instead of {} ({:.1}× smaller)",
                coding_label(quantised.coding),
                quantised.pairs,
                quantised.bytes,
                exact.bytes,
                exact.bytes as f64 / quantised.bytes as f64
            ),
        );
    }
    Ok(section)
}
