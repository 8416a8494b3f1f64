//! [`FrequencyResponse`]: the gain a spectral filter applies to a coefficient, as a function of
//! the frequency `√λ` of its basis field (Section 8.5 of the paper, the functions `F_α`, `F_β`).

use crate::filter_spec_error::FilterSpecError;

/// A gain as a function of frequency `f = √λ` (units 1/length; `λ` is an eigenvalue of the
/// Hodge–Laplacian `L`). Every gain is finite and non-negative.
///
/// | variant | gain `F(f)` |
/// |---|---|
/// | `Identity` | `1` |
/// | `LowPass { t }` | `e^{−t f²}` = `e^{−tλ}` (heat kernel; `t` has units length²) |
/// | `HighPass { t }` | `2 − e^{−t f²}` (sharpening: low frequencies kept, high ones doubled) |
/// | `BandPass { lo, hi }` | `1` for `lo ≤ f ≤ hi`, else `0` |
/// | `Cutoff { f }` | `1` for frequencies `≤ f`, else `0` (ideal low-pass) |
/// | `Curve` | piecewise linear through the control points, constant beyond the ends |
#[derive(Debug, Clone, PartialEq)]
pub enum FrequencyResponse {
    /// Gain 1 everywhere.
    Identity,
    /// `e^{−tλ}`, `t ≥ 0`.
    LowPass {
        /// Diffusion time (length²).
        t: f64,
    },
    /// `2 − e^{−tλ}`, `t ≥ 0`.
    HighPass {
        /// Diffusion time (length²).
        t: f64,
    },
    /// `1` on the closed frequency interval `[lo, hi]`, `0` outside.
    BandPass {
        /// Lowest frequency passed.
        lo: f64,
        /// Highest frequency passed.
        hi: f64,
    },
    /// `1` up to and including frequency `f`, `0` above.
    Cutoff {
        /// Cut-off frequency.
        f: f64,
    },
    /// A user-drawn curve.
    Curve(PiecewiseLinear),
}

impl FrequencyResponse {
    /// The gain at frequency `frequency` (`√λ`, ≥ 0).
    pub fn gain(&self, frequency: f64) -> f64 {
        let lambda = frequency * frequency;
        match self {
            FrequencyResponse::Identity => 1.0,
            FrequencyResponse::LowPass { t } => (-t * lambda).exp(),
            FrequencyResponse::HighPass { t } => 2.0 - (-t * lambda).exp(),
            FrequencyResponse::BandPass { lo, hi } => {
                if (*lo..=*hi).contains(&frequency) {
                    1.0
                } else {
                    0.0
                }
            }
            FrequencyResponse::Cutoff { f } => {
                if frequency <= *f {
                    1.0
                } else {
                    0.0
                }
            }
            FrequencyResponse::Curve(curve) => curve.evaluate(frequency),
        }
    }

    /// The largest gain the response can take (`τ` in the paper).
    pub fn max_gain(&self) -> f64 {
        match self {
            FrequencyResponse::HighPass { .. } => 2.0,
            FrequencyResponse::Curve(curve) => curve.points().iter().fold(0.0, |m, p| m.max(p.1)),
            _ => 1.0,
        }
    }

    /// Whether the gain never exceeds 1 (such a filter cannot increase any energy that is
    /// diagonal in the basis, e.g. the `M_X` norm or the Dirichlet energy `vᵀ S v`).
    pub fn is_contraction(&self) -> bool {
        self.max_gain() <= 1.0
    }
}

/// A piecewise linear curve through control points `(frequency, gain)` with strictly increasing
/// frequencies, finite non-negative frequencies and gains, at least one point. Constant
/// extrapolation beyond the first and last point.
#[derive(Debug, Clone, PartialEq)]
pub struct PiecewiseLinear {
    points: Vec<(f64, f64)>,
}

impl PiecewiseLinear {
    /// Checks and stores the control points.
    pub fn new(points: Vec<(f64, f64)>) -> Result<Self, FilterSpecError> {
        if points.is_empty() {
            return Err(FilterSpecError::EmptyCurve);
        }
        for (index, &(frequency, gain)) in points.iter().enumerate() {
            if !frequency.is_finite() || frequency < 0.0 || !gain.is_finite() || gain < 0.0 {
                return Err(FilterSpecError::BadControlPoint {
                    index,
                    frequency,
                    gain,
                });
            }
            if index > 0 && frequency <= points[index - 1].0 {
                return Err(FilterSpecError::UnsortedControlPoints {
                    index,
                    previous: points[index - 1].0,
                    frequency,
                });
            }
        }
        Ok(Self { points })
    }

    /// The control points `(frequency, gain)`, frequencies strictly increasing.
    pub fn points(&self) -> &[(f64, f64)] {
        &self.points
    }

    /// The gain at `frequency`: linear interpolation between the neighbouring control points,
    /// the end gains beyond the ends.
    pub fn evaluate(&self, frequency: f64) -> f64 {
        let points = &self.points;
        let first = points[0];
        let last = points[points.len() - 1];
        if frequency <= first.0 {
            return first.1;
        }
        if frequency >= last.0 {
            return last.1;
        }
        // First point with a frequency above `frequency`; exists and is > 0 by the checks above.
        let upper = points.partition_point(|p| p.0 <= frequency);
        let (f0, g0) = points[upper - 1];
        let (f1, g1) = points[upper];
        let s = (frequency - f0) / (f1 - f0);
        g0 + s * (g1 - g0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curve_interpolates_and_extrapolates_constantly() {
        let curve = PiecewiseLinear::new(vec![(1.0, 2.0), (3.0, 0.0)]).unwrap();
        assert_eq!(curve.evaluate(0.0), 2.0);
        assert_eq!(curve.evaluate(2.0), 1.0);
        assert_eq!(curve.evaluate(2.5), 0.5);
        assert_eq!(curve.evaluate(10.0), 0.0);
    }

    #[test]
    fn presets_have_the_documented_values() {
        let low = FrequencyResponse::LowPass { t: 0.5 };
        assert!((low.gain(2.0) - (-2.0f64).exp()).abs() < 1e-15);
        let high = FrequencyResponse::HighPass { t: 0.5 };
        assert!((high.gain(2.0) - (2.0 - (-2.0f64).exp())).abs() < 1e-15);
        assert_eq!(high.gain(0.0), 1.0);
        let band = FrequencyResponse::BandPass { lo: 1.0, hi: 2.0 };
        assert_eq!(
            (
                band.gain(0.5),
                band.gain(1.0),
                band.gain(2.0),
                band.gain(2.1)
            ),
            (0.0, 1.0, 1.0, 0.0)
        );
        let cut = FrequencyResponse::Cutoff { f: 1.0 };
        assert_eq!((cut.gain(1.0), cut.gain(1.0 + 1e-12)), (1.0, 0.0));
        assert!(low.is_contraction() && !high.is_contraction());
    }
}
