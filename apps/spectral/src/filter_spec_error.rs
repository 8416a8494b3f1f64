//! [`FilterSpecError`]: why a filter SPEC (`filter_spec.rs`) or the control points of a curve
//! (`filter_response.rs`) were refused.

use thiserror::Error;

/// Why a filter SPEC was refused.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FilterSpecError {
    /// The SPEC was empty.
    #[error("empty filter spec (expected identity, lowpass:t=.., highpass:t=.., bandpass:lo=..,hi=.., cutoff:f=.., curve:F,G;.. or @FILE.json)")]
    Empty,
    /// The part before `:` names no filter.
    #[error("unknown filter '{kind}' (expected identity, lowpass, highpass, bandpass, cutoff, curve or @FILE.json)")]
    UnknownKind {
        /// The unknown name.
        kind: String,
    },
    /// A required `name=value` parameter is missing.
    #[error("filter '{kind}' needs the parameter '{name}=' (e.g. {example})")]
    MissingParameter {
        /// Filter name.
        kind: &'static str,
        /// Parameter name.
        name: &'static str,
        /// A correct example.
        example: &'static str,
    },
    /// A parameter the filter does not take, or a part without `=`.
    #[error("filter '{kind}' does not take '{text}' (e.g. {example})")]
    UnexpectedParameter {
        /// Filter name.
        kind: &'static str,
        /// The offending text.
        text: String,
        /// A correct example.
        example: &'static str,
    },
    /// A value is not a finite number ≥ 0.
    #[error("{what}: '{text}' is not a finite number ≥ 0")]
    BadNumber {
        /// Which value.
        what: String,
        /// The text that failed.
        text: String,
    },
    /// `bandpass` with `lo > hi`.
    #[error("bandpass: lo = {lo} is above hi = {hi}")]
    BandOrder {
        /// Lower bound.
        lo: f64,
        /// Upper bound.
        hi: f64,
    },
    /// A curve point is not `FREQUENCY,GAIN`.
    #[error("curve point {index} '{text}' is not FREQUENCY,GAIN (e.g. curve:0,1;5,0.5;10,0)")]
    BadPoint {
        /// Position of the point (0-based).
        index: usize,
        /// Its text.
        text: String,
    },
    /// A curve with no control point.
    #[error("a curve needs at least one control point (e.g. curve:0,1;5,0.5;10,0)")]
    EmptyCurve,
    /// A control point with a negative or non-finite coordinate.
    #[error(
        "curve point {index} ({frequency}, {gain}): frequency and gain must be finite and ≥ 0"
    )]
    BadControlPoint {
        /// Position of the point.
        index: usize,
        /// Its frequency.
        frequency: f64,
        /// Its gain.
        gain: f64,
    },
    /// Control points whose frequencies do not increase strictly.
    #[error("curve point {index}: frequency {frequency} does not increase (previous point at {previous})")]
    UnsortedControlPoints {
        /// Position of the point.
        index: usize,
        /// Frequency of the previous point.
        previous: f64,
        /// Frequency of this point.
        frequency: f64,
    },
    /// The `@FILE` could not be read.
    #[error("cannot read filter file {path}: {message}")]
    FileRead {
        /// The file.
        path: String,
        /// The I/O error.
        message: String,
    },
    /// The `@FILE` is not a curve in JSON.
    #[error("filter file {path}: {message} (expected {{\"points\": [[frequency, gain], ...]}})")]
    Json {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
}
