//! The textual SPEC grammar of a [`FrequencyResponse`], as typed on the command line.
//!
//! ```text
//! SPEC   := identity
//!         | lowpass:t=NUM                 gain e^{−tλ}          (t ≥ 0, length²)
//!         | highpass:t=NUM                gain 2 − e^{−tλ}      (t ≥ 0)
//!         | bandpass:lo=NUM,hi=NUM        gain 1 on lo ≤ √λ ≤ hi, else 0
//!         | cutoff:f=NUM                  gain 1 for √λ ≤ f, else 0
//!         | curve:F,G;F,G;...             piecewise linear through (frequency, gain) points
//!         | @PATH                         a curve in a JSON file
//! ```
//!
//! Frequencies are `√λ` (1/length). A curve's frequencies must increase strictly; gains are
//! finite and ≥ 0; beyond its ends the curve is constant (so `curve:0,0.5` is a constant gain
//! of one half). The JSON file holds `{"points": [[F, G], ...]}` or just `[[F, G], ...]`.
//!
//! ```
//! use tvf_spectral::FrequencyResponse;
//! let low: FrequencyResponse = "lowpass:t=0.01".parse()?;
//! assert_eq!(low, FrequencyResponse::LowPass { t: 0.01 });
//! let drawn: FrequencyResponse = "curve:0,1;5,0.5;10,0".parse()?;
//! assert_eq!(drawn.gain(7.5), 0.25);
//! assert!("lowpass:s=1".parse::<FrequencyResponse>().is_err());
//! # Ok::<(), tvf_spectral::FilterSpecError>(())
//! ```

use crate::filter_response::{FrequencyResponse, PiecewiseLinear};
use crate::filter_spec_error::FilterSpecError;
use std::path::Path;
use std::str::FromStr;

impl FromStr for FrequencyResponse {
    type Err = FilterSpecError;

    /// Parses a SPEC (see the module docs); `@PATH` reads the JSON file at `PATH`.
    fn from_str(spec: &str) -> Result<Self, FilterSpecError> {
        let spec = spec.trim();
        if spec.is_empty() {
            return Err(FilterSpecError::Empty);
        }
        if let Some(path) = spec.strip_prefix('@') {
            return read_curve_file(Path::new(path)).map(FrequencyResponse::Curve);
        }
        let (kind, arguments) = spec.split_once(':').unwrap_or((spec, ""));
        match kind.trim().to_ascii_lowercase().as_str() {
            "identity" => {
                if arguments.trim().is_empty() {
                    Ok(FrequencyResponse::Identity)
                } else {
                    Err(FilterSpecError::UnexpectedParameter {
                        kind: "identity",
                        text: arguments.to_string(),
                        example: "identity",
                    })
                }
            }
            "lowpass" => {
                let [t] = named_parameters("lowpass", arguments, ["t"], "lowpass:t=0.01")?;
                Ok(FrequencyResponse::LowPass { t })
            }
            "highpass" => {
                let [t] = named_parameters("highpass", arguments, ["t"], "highpass:t=0.01")?;
                Ok(FrequencyResponse::HighPass { t })
            }
            "bandpass" => {
                let [lo, hi] =
                    named_parameters("bandpass", arguments, ["lo", "hi"], "bandpass:lo=2,hi=8")?;
                if lo > hi {
                    return Err(FilterSpecError::BandOrder { lo, hi });
                }
                Ok(FrequencyResponse::BandPass { lo, hi })
            }
            "cutoff" => {
                let [f] = named_parameters("cutoff", arguments, ["f"], "cutoff:f=10")?;
                Ok(FrequencyResponse::Cutoff { f })
            }
            "curve" => parse_curve_points(arguments).map(FrequencyResponse::Curve),
            other => Err(FilterSpecError::UnknownKind {
                kind: other.to_string(),
            }),
        }
    }
}

/// Parses `name=value` pairs separated by commas; every name in `names` exactly once.
fn named_parameters<const N: usize>(
    kind: &'static str,
    arguments: &str,
    names: [&'static str; N],
    example: &'static str,
) -> Result<[f64; N], FilterSpecError> {
    let mut values = [None; N];
    for part in arguments
        .split(',')
        .map(str::trim)
        .filter(|p| !p.is_empty())
    {
        let unexpected = || FilterSpecError::UnexpectedParameter {
            kind,
            text: part.to_string(),
            example,
        };
        let (name, value) = part.split_once('=').ok_or_else(unexpected)?;
        let slot = names
            .iter()
            .position(|n| *n == name.trim())
            .ok_or_else(unexpected)?;
        if values[slot].is_some() {
            return Err(unexpected());
        }
        values[slot] = Some(parse_non_negative(
            &format!("{kind}: {}", names[slot]),
            value,
        )?);
    }
    let mut out = [0.0; N];
    for (slot, value) in values.iter().enumerate() {
        out[slot] = value.ok_or(FilterSpecError::MissingParameter {
            kind,
            name: names[slot],
            example,
        })?;
    }
    Ok(out)
}

fn parse_non_negative(what: &str, text: &str) -> Result<f64, FilterSpecError> {
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
        _ => Err(FilterSpecError::BadNumber {
            what: what.to_string(),
            text: text.trim().to_string(),
        }),
    }
}

/// `F,G;F,G;...` (a trailing `;` is allowed).
fn parse_curve_points(arguments: &str) -> Result<PiecewiseLinear, FilterSpecError> {
    let mut points = Vec::new();
    for (index, text) in arguments
        .split(';')
        .map(str::trim)
        .filter(|p| !p.is_empty())
        .enumerate()
    {
        let bad = || FilterSpecError::BadPoint {
            index,
            text: text.to_string(),
        };
        let (f, g) = text.split_once(',').ok_or_else(bad)?;
        let frequency = f.trim().parse::<f64>().map_err(|_| bad())?;
        let gain = g.trim().parse::<f64>().map_err(|_| bad())?;
        points.push((frequency, gain));
    }
    PiecewiseLinear::new(points)
}

/// Reads a curve from a JSON file: `{"points": [[F, G], ...]}` or `[[F, G], ...]`.
pub fn read_curve_file(path: &Path) -> Result<PiecewiseLinear, FilterSpecError> {
    let shown = path.display().to_string();
    let read_error = |message: String| FilterSpecError::FileRead {
        path: shown.clone(),
        message,
    };
    // A curve is a few points; 16 MiB is far more than any needs.
    let bytes =
        tvf_core::io::read_at_most(path, 16 << 20).map_err(|e| read_error(e.to_string()))?;
    let text = String::from_utf8(bytes).map_err(|_| read_error("not UTF-8 text".into()))?;
    // A leading byte-order mark (some editors write one) is not JSON.
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let json_error = |message: String| FilterSpecError::Json {
        path: shown.clone(),
        message,
    };
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| json_error(e.to_string()))?;
    let list = match &value {
        serde_json::Value::Array(list) => list,
        serde_json::Value::Object(map) => match map.get("points") {
            Some(serde_json::Value::Array(list)) => list,
            _ => return Err(json_error("no array \"points\"".to_string())),
        },
        _ => {
            return Err(json_error(
                "top level is neither an object nor an array".to_string(),
            ))
        }
    };
    let mut points = Vec::with_capacity(list.len());
    for (index, entry) in list.iter().enumerate() {
        let pair = entry
            .as_array()
            .filter(|p| p.len() == 2)
            .and_then(|p| Some((p[0].as_f64()?, p[1].as_f64()?)))
            .ok_or_else(|| {
                json_error(format!("point {index} is not [frequency, gain]: {entry}"))
            })?;
        points.push(pair);
    }
    PiecewiseLinear::new(points)
}
