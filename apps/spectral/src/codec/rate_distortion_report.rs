//! Rate–distortion points as `tvf rate-distortion` reports them ([`RateDistortionReport`]): a
//! table of the points and, for every 64-bit point, the smallest quantised file at equal or
//! lower error ([`crate::equal_error_comparison`]), as text lines or as JSON.

use crate::codec::rate_distortion::{equal_error_comparison, RatePoint};
use serde_json::{json, Value};

/// The measured points of a rate–distortion curve (as [`crate::rate_distortion`] returns them).
#[derive(Debug, Clone, Copy)]
pub struct RateDistortionReport<'a> {
    /// The points, one per compressed file.
    pub points: &'a [RatePoint],
}

impl RateDistortionReport<'_> {
    /// The table: a header, then one line per point (pairs, coding, bytes, bits per vertex,
    /// relative L2 error), columns aligned.
    pub fn table_lines(&self) -> Vec<String> {
        let header = format!(
            "{:>6} {:>34} {:>10} {:>12} {:>14}",
            "pairs", "coding", "bytes", "bits/vertex", "rel. L2 error"
        );
        let rows = self.points.iter().map(|p| {
            format!(
                "{:>6} {:>34} {:>10} {:>12.3} {:>14.4e}",
                p.pairs,
                p.coding.label(),
                p.bytes,
                p.bits_per_vertex,
                p.relative_error
            )
        });
        std::iter::once(header).chain(rows).collect()
    }

    /// The points as JSON: `[{pairs, coding, bytes, bits_per_vertex, relative_error}, ...]`.
    pub fn points_json(&self) -> Value {
        let rows: Vec<Value> = self
            .points
            .iter()
            .map(|p| {
                json!({
                    "pairs": p.pairs,
                    "coding": p.coding.label(),
                    "bytes": p.bytes,
                    "bits_per_vertex": p.bits_per_vertex,
                    "relative_error": p.relative_error,
                })
            })
            .collect();
        Value::Array(rows)
    }

    /// The equal-error comparison: a header, then one line per 64-bit point that a quantised
    /// file matches (both sizes and errors, and how many times smaller the quantised file is).
    pub fn comparison_lines(&self) -> Vec<String> {
        let header =
            "at equal or lower error (smallest quantised file per 64-bit point):".to_string();
        let rows = equal_error_comparison(self.points)
            .into_iter()
            .map(|(exact, quantised)| {
                format!(
                    "  P = {:>5}: 64-bit {:>9} bytes (error {:.3e})  vs  {} P = {} {:>8} bytes \
                 (error {:.3e}): {:.1}× smaller",
                    exact.pairs,
                    exact.bytes,
                    exact.relative_error,
                    quantised.coding.label(),
                    quantised.pairs,
                    quantised.bytes,
                    quantised.relative_error,
                    exact.bytes as f64 / quantised.bytes as f64
                )
            });
        std::iter::once(header).chain(rows).collect()
    }

    /// The equal-error comparison as JSON: `[{pairs, bytes, quantised_coding, quantised_pairs,
    /// quantised_bytes, ratio}, ...]` (`ratio`: 64-bit bytes over quantised bytes).
    pub fn comparison_json(&self) -> Value {
        let rows: Vec<Value> = equal_error_comparison(self.points)
            .into_iter()
            .map(|(exact, quantised)| {
                json!({
                    "pairs": exact.pairs,
                    "bytes": exact.bytes,
                    "quantised_coding": quantised.coding.label(),
                    "quantised_pairs": quantised.pairs,
                    "quantised_bytes": quantised.bytes,
                    "ratio": exact.bytes as f64 / quantised.bytes as f64,
                })
            })
            .collect();
        Value::Array(rows)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::CoefficientCoding;

    fn point(coding: CoefficientCoding, pairs: usize, bytes: usize, error: f64) -> RatePoint {
        RatePoint {
            coding,
            pairs,
            bytes,
            bits_per_vertex: bytes as f64 / 100.0,
            relative_error: error,
        }
    }

    #[test]
    fn the_table_and_the_comparison_list_every_point() {
        let q8 = CoefficientCoding::Quantized { bits: 8 };
        let points = [
            point(CoefficientCoding::Float64, 10, 4000, 0.2),
            point(CoefficientCoding::Float64, 20, 8000, 0.1),
            point(q8, 10, 500, 0.21),
            point(q8, 20, 1000, 0.1),
        ];
        let report = RateDistortionReport { points: &points };
        assert_eq!(report.table_lines().len(), 5);
        assert_eq!(report.points_json().as_array().unwrap().len(), 4);
        // 0.21 > 0.2: the 10-pair 64-bit file is matched by the 20-pair quantised one only.
        let comparisons = report.comparison_json();
        assert_eq!(comparisons[0]["quantised_pairs"], 20);
        assert_eq!(comparisons[0]["ratio"], 4.0);
        assert_eq!(comparisons[1]["ratio"], 8.0);
        let lines = report.comparison_lines();
        assert_eq!(lines.len(), 3);
        assert!(lines[1].ends_with(": 4.0× smaller"), "{}", lines[1]);
    }
}
