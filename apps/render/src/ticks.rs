//! Axis scales and tick positions for the plots.

/// Linear or logarithmic axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxisScale {
    /// Equal distances for equal differences.
    Linear,
    /// Equal distances for equal ratios (base 10); non-positive values are not drawn.
    Log10,
}

impl AxisScale {
    /// Maps a data value to axis space (the value itself, or its base-10 logarithm).
    pub fn forward(self, v: f64) -> f64 {
        match self {
            AxisScale::Linear => v,
            AxisScale::Log10 => v.log10(),
        }
    }

    /// Whether `v` can be drawn on this scale.
    pub fn accepts(self, v: f64) -> bool {
        v.is_finite() && (self == AxisScale::Linear || v > 0.0)
    }
}

/// "Nice" step (1, 2 or 5 times a power of ten) close to `raw`.
fn nice_step(raw: f64) -> f64 {
    let power = 10f64.powf(raw.log10().floor());
    let f = raw / power;
    let m = if f < 1.5 {
        1.0
    } else if f < 3.0 {
        2.0
    } else if f < 7.0 {
        5.0
    } else {
        10.0
    };
    m * power
}

/// Major ticks (data values) inside `[lo, hi]`, and minor ticks (log scale only).
pub fn ticks(scale: AxisScale, lo: f64, hi: f64) -> (Vec<f64>, Vec<f64>) {
    match scale {
        AxisScale::Linear => (linear_ticks(lo, hi), Vec::new()),
        AxisScale::Log10 => {
            let (a, b) = (lo.log10(), hi.log10());
            if b - a < 1.0 {
                return (linear_ticks(lo, hi), Vec::new());
            }
            let every = ((b - a) / 8.0).ceil().max(1.0) as i32;
            let mut major = Vec::new();
            let mut minor = Vec::new();
            for k in a.floor() as i32..=b.ceil() as i32 {
                let decade = 10f64.powi(k);
                if k % every == 0 && decade >= lo * (1.0 - 1e-9) && decade <= hi * (1.0 + 1e-9) {
                    major.push(decade);
                }
                if every == 1 {
                    // Narrow ranges also label 2× and 5× each decade.
                    let labelled: &[u32] = if b - a < 2.5 { &[2, 5] } else { &[] };
                    for m in 2..10 {
                        let v = decade * m as f64;
                        if v >= lo && v <= hi {
                            if labelled.contains(&m) {
                                major.push(v);
                            } else {
                                minor.push(v);
                            }
                        }
                    }
                }
            }
            (major, minor)
        }
    }
}

fn linear_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let step = nice_step((hi - lo) / 6.0);
    if step.is_nan() || step <= 0.0 || !step.is_finite() {
        return vec![lo];
    }
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last)
        .map(|k| {
            let v = k as f64 * step;
            if v.abs() < 1e-12 * step {
                0.0
            } else {
                v
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_are_nice_and_inside() {
        let (t, _) = ticks(AxisScale::Linear, 0.0, 1.0);
        let expected = [0.0, 0.2, 0.4, 0.6, 0.8, 1.0];
        assert_eq!(t.len(), expected.len());
        assert!(t.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-12));
        let (t, _) = ticks(AxisScale::Linear, -3.3, 7.9);
        assert!(t.iter().all(|&v| (-3.3..=7.9).contains(&v)));
        assert_eq!(t[1] - t[0], 2.0);
    }

    #[test]
    fn log_ticks_are_decades() {
        let (t, minor) = ticks(AxisScale::Log10, 1e-4, 10.0);
        assert_eq!(t.len(), 6);
        let (narrow, _) = ticks(AxisScale::Log10, 0.4, 20.0);
        assert_eq!(narrow, vec![0.5, 1.0, 2.0, 5.0, 10.0, 20.0]);
        assert!((t[0] - 1e-4).abs() < 1e-18 && (t[5] - 10.0).abs() < 1e-12);
        assert!(minor.contains(&2.0));
    }
}
