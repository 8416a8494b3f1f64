//! Figure 1 (eigenfield pairs) and Figures 7 and 8 (spectral filtering of a noisy field and its
//! spectrum).

use crate::error::FigureError;
use crate::finding::{Experiment, Finding};
use crate::panels::{field_panel, save, save_magnitude_row};
use crate::test_fields::{designed_field, tangent_noise};
use tvf_render::{grid, Tint, COINTEGRABLE_RED, INTEGRABLE_GREEN};
use tvf_render::{Axis, AxisScale, Plot, Series, SeriesStyle};
use tvf_spectral::{
    relative_l2_error, FieldFamily, FrequencyResponse, PiecewiseLinear, SpectralAnalysis,
    SpectralFilter,
};

/// The pairs Figure 1 shows (1-based, as in the paper: the 1st, 21st, 51st and 71st).
pub const FIGURE1_PAIRS: [usize; 4] = [1, 21, 51, 71];

/// Basis indices of `family`, ascending eigenvalue.
fn family_indices(x: &Experiment, family: FieldFamily) -> Vec<usize> {
    (0..x.basis.len())
        .filter(|&i| x.basis.families()[i] == family)
        .collect()
}

/// Basis field `index` as a vector.
fn column(x: &Experiment, index: usize) -> Vec<f64> {
    x.basis.fields().col(index).iter().copied().collect()
}

/// Figure 1: pairs of eigenfields (1-based pair numbers `shown`; the paper's are
/// [`FIGURE1_PAIRS`]; pairs the basis does not hold are left out), integrable (green,
/// curl-free) above co-integrable (red, divergence-free).
pub fn figure1(x: &Experiment, shown: &[usize]) -> Result<Finding, FigureError> {
    let mut finding = Finding::new(
        "Figure 1",
        "Pairs of eigenfields: integrable (green, curl-free) above co-integrable (red, divergence-free)",
        x.name,
    );
    let integrable = family_indices(x, FieldFamily::Integrable);
    let cointegrable = family_indices(x, FieldFamily::Cointegrable);
    let pairs: Vec<usize> = shown
        .iter()
        .copied()
        .filter(|&k| k >= 1 && k <= integrable.len() && k <= cointegrable.len())
        .collect();
    let lambda = |i: usize| x.basis.eigenvalues()[i];
    let mut top = Vec::new();
    let mut bottom = Vec::new();
    let mut gaps = Vec::new();
    for &k in &pairs {
        let (a, b) = (integrable[k - 1], cointegrable[k - 1]);
        top.push(field_panel(
            x.mesh,
            x.complex,
            &column(x, a),
            &format!("integrable {k}: lambda {:.2}", lambda(a)),
            Tint::Solid(INTEGRABLE_GREEN),
            x.view,
        )?);
        bottom.push(field_panel(
            x.mesh,
            x.complex,
            &column(x, b),
            &format!("co-integrable {k}: lambda {:.2}", lambda(b)),
            Tint::Solid(COINTEGRABLE_RED),
            x.view,
        )?);
        let gap = (lambda(b) - lambda(a)).abs() / lambda(a).max(f64::MIN_POSITIVE);
        gaps.push(gap);
        finding.number(
            format!("pair {k}: eigenvalues (integrable, co-integrable)"),
            format!(
                "{:.4}, {:.4} (relative gap {:.1} %)",
                lambda(a),
                lambda(b),
                100.0 * gap
            ),
        );
    }
    top.extend(bottom);
    let file = "figure1_eigenfields.png";
    save(&grid(&top, pairs.len().max(1)), &x.out.join(file))?;
    finding.files.push(file.to_string());
    let mean_gap = gaps.iter().sum::<f64>() / gaps.len().max(1) as f64;
    finding.paper =
        "The 1st, 21st, 51st and 71st pairs on the centaur (not public); the two fields \
                     of a pair have only approximately the same eigenvalue."
            .to_string();
    finding.comparison = format!(
        "As in the paper, on another mesh ({}): the co-integrable field of a pair looks like the \
         integrable one turned by 90° (its sources and sinks become vortices); the two \
         eigenvalues of a pair (P1 against Crouzeix–Raviart Laplacian) differ by {:.1} % on \
         average, more at higher index.",
        x.name,
        100.0 * mean_gap
    );
    Ok(finding)
}

/// Noise amplitude relative to the clean field's RMS magnitude (Figure 7).
const NOISE_LEVEL: f64 = 0.8;

/// Figures 7 and 8: a designed field (soft design, [`crate::seeded_constraints::DESIGNED_FIELD_CONSTRAINTS`] seeded
/// constraints) plus noise, a low-pass filter that also enhances the
/// integrable low frequencies, a high-pass view without the integrable low frequencies, and
/// the coefficient spectrum of the input.
pub fn figures7_8(x: &Experiment, plot_size: (u32, u32)) -> Result<Vec<Finding>, FigureError> {
    let basis = x.basis;
    let clean = designed_field(
        x.complex,
        x.mesh,
        crate::seeded_constraints::DESIGNED_FIELD_CONSTRAINTS,
        1.0,
        7,
    )?;
    let rms = (basis.inner_product(&clean, &clean) / x.mesh.total_area()).sqrt();
    let noisy: Vec<f64> = clean
        .iter()
        .zip(tangent_noise(x.complex, NOISE_LEVEL * rms, 17)?)
        .map(|(a, b)| a + b)
        .collect();
    Ok(vec![
        figure7(x, &clean, &noisy)?,
        figure8(x, &clean, &noisy, plot_size)?,
    ])
}

/// Figure 7: the noisy field, the low-pass with the integrable low frequencies enhanced, and
/// the high-pass without them (reference frequency: a sixth of the way up the basis).
fn figure7(x: &Experiment, clean: &[f64], noisy: &[f64]) -> Result<Finding, FigureError> {
    let basis = x.basis;
    let mass = basis.field_mass();
    // Reference frequency: a sixth of the way up the basis.
    let f_ref = basis.eigenvalues()[basis.len() / 6].max(1e-12).sqrt();
    let t = std::f64::consts::LN_2 / (f_ref * f_ref);
    let smoothing = SpectralFilter {
        integrable: FrequencyResponse::Curve(PiecewiseLinear::new(vec![
            (0.0, 2.0),
            (f_ref, 1.0),
            (2.0 * f_ref, 0.0),
        ])?),
        cointegrable: FrequencyResponse::LowPass { t },
        harmonic_gain: 1.0,
        rest_gain: 0.0,
    };
    let sharpening = SpectralFilter {
        integrable: FrequencyResponse::Curve(PiecewiseLinear::new(vec![
            (0.0, 0.0),
            (f_ref, 0.0),
            (3.0 * f_ref, 2.0),
        ])?),
        cointegrable: FrequencyResponse::HighPass { t },
        harmonic_gain: 0.0,
        rest_gain: 1.0,
    };
    let smoothed = smoothing.apply(basis, noisy)?;
    let denoised =
        SpectralFilter::both(FrequencyResponse::LowPass { t }, 0.0).apply(basis, noisy)?;
    let sharpened = sharpening.apply(basis, noisy)?;
    let file7 = "figure7_filtering.png";
    save_magnitude_row(
        x,
        file7,
        &[
            (noisy, "input: designed field + noise"),
            (&smoothed.field, "low-pass, integrable lows x2"),
            (&sharpened.field, "high-pass, integrable lows removed"),
        ],
    )?;
    let mut f7 = Finding::new(
        "Figure 7",
        "Spectral filtering of a noisy field, the two families filtered separately",
        x.name,
    );
    f7.files.push(file7.to_string());
    f7.number(
        "noise",
        format!("each face's frame coordinates uniform in ±{NOISE_LEVEL} × the clean field's RMS"),
    );
    f7.number(
        "reference frequency f_ref (basis field len/6)",
        format!("{f_ref:.3}"),
    );
    let (input_error, denoised_error) = (
        relative_l2_error(mass, clean, noisy),
        relative_l2_error(mass, clean, &denoised.field),
    );
    f7.number(
        "relative L2 distance to the clean field: input / plain low-pass on both families",
        format!("{input_error:.3} / {denoised_error:.3}"),
    );
    f7.number(
        "rest field of the input (relative)",
        format!(
            "{:.3}",
            smoothed.rest_norm / basis.inner_product(noisy, noisy).sqrt()
        ),
    );
    f7.paper = "A custom field on the centaur: low-pass with the integrable low frequencies \
                enhanced gives a smoother, more structured field; enhancing high frequencies and \
                removing the integrable low ones isolates the noisy features (two vortices)."
        .to_string();
    f7.comparison = format!(
        "Same kind of filters on our own field (a designed field + seeded noise) on the hand: the middle \
         panel is smooth and dominated by the enhanced integrable low frequencies, the right one \
         shows the noise. A plain low-pass brings the field from {input_error:.3} to \
         {denoised_error:.3} relative distance to the clean field. The paper gives no numbers."
    );
    Ok(f7)
}

/// Figure 8: the coefficients of the noisy input of Figure 7 against frequency, each family in
/// its colour, over those of the clean field (grey).
fn figure8(
    x: &Experiment,
    clean: &[f64],
    noisy: &[f64],
    plot_size: (u32, u32),
) -> Result<Finding, FigureError> {
    let basis = x.basis;
    let analysis = SpectralAnalysis::new(basis, noisy)?;
    let clean_analysis = SpectralAnalysis::new(basis, clean)?;
    let points = |a: &SpectralAnalysis, family| -> Vec<(f64, f64)> {
        a.family(family)
            .map(|e| (e.frequency, e.coefficient.abs().max(1e-12)))
            .collect()
    };
    let both_clean = points(&clean_analysis, FieldFamily::Integrable)
        .into_iter()
        .chain(points(&clean_analysis, FieldFamily::Cointegrable))
        .collect();
    let series = [
        (
            "without the noise: both families",
            both_clean,
            [170, 170, 170],
        ),
        (
            "input: integrable |alpha|",
            points(&analysis, FieldFamily::Integrable),
            [31, 119, 180],
        ),
        (
            "input: co-integrable |beta|",
            points(&analysis, FieldFamily::Cointegrable),
            [214, 39, 40],
        ),
    ]
    .into_iter()
    .map(|(name, points, color)| {
        let mut series = Series::new(name, points, SeriesStyle::Scatter);
        series.color = Some(color);
        series
    })
    .collect();
    let plot = Plot {
        title: format!("Spectrum of the Figure 7 input ({})", x.name),
        x: Axis::new("frequency sqrt(lambda)", AxisScale::Linear),
        y: Axis::new("|coefficient|", AxisScale::Log10),
        series,
        width: plot_size.0,
        height: plot_size.1,
    };
    let file8 = "figure8_spectrum.png";
    save(&plot.render()?, &x.out.join(file8))?;
    let mut f8 = Finding::new(
        "Figure 8",
        "Spectral analysis: coefficients of both families against frequency",
        x.name,
    );
    f8.files.push(file8.to_string());
    let energy = &analysis.energy;
    f8.number(
        "energy shares of the input: integrable / co-integrable / harmonic / rest",
        format!(
            "{:.3} / {:.3} / {:.3} / {:.3}",
            energy.integrable / energy.total(),
            energy.cointegrable / energy.total(),
            (energy.harmonic / energy.total()).max(0.0),
            energy.rest / energy.total()
        ),
    );
    f8.paper =
        "Coefficients of the Figure 7 field for both families against frequency.".to_string();
    f8.comparison = "Same kind of plot: the largest coefficients are the lowest frequencies; the \
                     noise adds a nearly flat floor over all frequencies (white noise has about \
                     equal energy per eigenfield) above the clean field's coefficients (grey)."
        .to_string();
    Ok(f8)
}
