//! Demo step 4 (paper Figures 7 and 8): a noisy field, low-pass filtered in the spectral
//! basis, and the coefficient spectra before and after.

use super::page::Section;
use super::test_fields::noise;
use super::Context;
use crate::face_quantities::ColorBy;
use crate::picture::{draw, grid, Overlays, Style};
use anyhow::Result;
use tvf_core::discretization::HodgeOperators;
use tvf_render::{Axis, AxisScale, Plot, Series, SeriesStyle};
use tvf_spectral::{
    relative_l2_error, FieldFamily, FrequencyResponse, SpectralAnalysis, SpectralFilter,
};

/// Noise amplitude relative to the clean field's RMS magnitude.
const NOISE_LEVEL: f64 = 0.8;

/// Filters a noisy copy of `clean` and plots the spectra.
pub fn run(cx: &Context, clean: &[f64]) -> Result<Section> {
    let basis = cx.basis;
    let mass = basis.field_mass();
    let area = cx.discretization.total_area();
    let rms = (basis.inner_product(clean, clean) / area).sqrt();
    // Uniform noise in each face's frame coordinates, as tangent vectors per face, turned into a
    // field of the discretization (face fields: exactly those coordinates).
    let sampling = cx.discretization.require_sampling()?;
    let per_face = noise(2 * sampling.face_count(), NOISE_LEVEL * rms, 17);
    let vectors: Vec<[f64; 3]> = per_face
        .chunks_exact(2)
        .enumerate()
        .map(|(t, ab)| {
            let [e1, e2] = sampling.frame(t);
            std::array::from_fn(|k| ab[0] * e1[k] + ab[1] * e2[k])
        })
        .collect();
    let noise_field = sampling.from_face_vectors(&vectors)?.field;
    let noisy: Vec<f64> = clean.iter().zip(noise_field).map(|(a, b)| a + b).collect();
    // Gain 1/2 at the eigenvalue a sixth of the way up the basis.
    let reference = basis.eigenvalues()[basis.len() / 6].max(1e-12);
    let t = std::f64::consts::LN_2 / reference;
    let filter = SpectralFilter {
        integrable: FrequencyResponse::LowPass { t },
        cointegrable: FrequencyResponse::LowPass { t },
        harmonic_gain: 1.0,
        rest_gain: 0.0,
    };
    let filtered = filter.apply(basis, &noisy)?;
    let mut section = Section::new(
        "Filtering a noisy field (Figures 7 and 8)",
        format!(
            "The test field plus seeded noise (each face-frame coordinate uniform in ±{NOISE_LEVEL} × \
             the field's RMS magnitude), filtered with the low-pass e^(−tλ) on both families \
             (t = {t:.4}, gain 1/2 at λ = {reference:.2}), the harmonic part kept and the rest field \
             (what {} basis fields cannot represent) dropped.",
            basis.len()
        ),
    );
    let mut panels = Vec::new();
    for (title, field) in [
        ("clean", clean),
        ("noisy", noisy.as_slice()),
        ("low-pass filtered", filtered.field.as_slice()),
    ] {
        let overlays = Overlays {
            title: Some(title.to_string()),
            ..Default::default()
        };
        panels.push(draw(
            cx.mesh,
            cx.discretization,
            Some(field),
            ColorBy::Magnitude,
            Style::Lic,
            overlays,
            cx.panel_view(),
        )?);
    }
    cx.save(&grid(&panels, 3), "filtering.png")?;
    section.figure(
        "filtering.png",
        "Clean test field, noisy field, and the low-pass filtered noisy field (LIC, colour: magnitude).",
    );

    let before = SpectralAnalysis::new(basis, &noisy)?;
    let after = SpectralAnalysis::new(basis, &filtered.field)?;
    let points = |analysis: &SpectralAnalysis, family| -> Vec<(f64, f64)> {
        analysis
            .family(family)
            .map(|e| (e.frequency, e.coefficient.abs()))
            .collect()
    };
    let series = vec![
        colored(
            Series::new(
                "noisy: integrable |alpha|",
                points(&before, FieldFamily::Integrable),
                SeriesStyle::Scatter,
            ),
            [150, 190, 230],
        ),
        colored(
            Series::new(
                "noisy: co-integrable |beta|",
                points(&before, FieldFamily::Cointegrable),
                SeriesStyle::Scatter,
            ),
            [240, 170, 160],
        ),
        colored(
            Series::new(
                "filtered: integrable |alpha|",
                points(&after, FieldFamily::Integrable),
                SeriesStyle::Scatter,
            ),
            [31, 119, 180],
        ),
        colored(
            Series::new(
                "filtered: co-integrable |beta|",
                points(&after, FieldFamily::Cointegrable),
                SeriesStyle::Scatter,
            ),
            [214, 39, 40],
        ),
    ];
    let plot = Plot {
        title: "Fourier coefficients against frequency".to_string(),
        x: Axis::new("frequency sqrt(lambda)", AxisScale::Linear),
        y: Axis::new("|coefficient|", AxisScale::Log10),
        series,
        width: cx.config.width.max(200),
        height: (cx.config.height * 3 / 4).max(150),
    };
    cx.save(&plot.render()?, "spectrum.png")?;
    section.figure(
        "spectrum.png",
        "Coefficient magnitudes of both families against frequency, before (light) and after \
         (dark) filtering: the noise is spread over all frequencies, the filter removes the high ones.",
    );
    section.number(
        "relative L2 error of the noisy field",
        format!("{:.4}", relative_l2_error(mass, clean, &noisy)),
    );
    section.number(
        "relative L2 error after filtering",
        format!("{:.4}", relative_l2_error(mass, clean, &filtered.field)),
    );
    section.number(
        "rest field of the noisy input (relative)",
        format!("{:.4}", before.relative_rest_norm()),
    );
    Ok(section)
}

fn colored(mut series: Series, color: [u8; 3]) -> Series {
    series.color = Some(color);
    series
}
