//! A compressed field or sequence as `tvf compress` reports it: [`CompressionSummary`], as text
//! lines or as one JSON object.

use crate::codec::sequence::CompressionReport;
use crate::formats::compressed_file::CoefficientCoding;
use serde_json::{json, Value};
use std::fmt::Write as _;
use std::path::Path;

impl CoefficientCoding {
    /// How a report names the coding: `f64`, or `quantised Q bits, range-coded`.
    pub fn description(self) -> String {
        match self {
            CoefficientCoding::Float64 => "f64".to_string(),
            CoefficientCoding::Quantized { bits } => {
                format!("quantised {bits} bits, range-coded")
            }
        }
    }
}

/// A `.tvfc` file written, with what it cost.
#[derive(Debug, Clone, Copy)]
pub struct CompressionSummary<'a> {
    /// Size and distortion of the file.
    pub report: &'a CompressionReport,
    /// The file.
    pub output: &'a Path,
    /// Coefficient pairs kept (`P`).
    pub pairs: usize,
    /// How the coefficients are stored.
    pub coding: CoefficientCoding,
    /// Whether the input was a sequence (an array or folder of frames), not one field.
    pub sequence: bool,
}

impl CompressionSummary<'_> {
    /// The summary as JSON: `output`, `frames`, `sequence`, `pairs`, `coefficients_per_frame`,
    /// `coding`, `bytes`, `bits_per_vertex`, `rate_against_two_doubles`,
    /// `rate_against_two_floats`, `mean_relative_error`, `worst_relative_error` and
    /// `relative_errors` (one per frame).
    pub fn to_json(&self) -> Value {
        let report = self.report;
        json!({
            "output": self.output.display().to_string(),
            "frames": report.frames,
            "sequence": self.sequence,
            "pairs": self.pairs,
            "coefficients_per_frame": report.coefficients_per_frame,
            "coding": self.coding.description(),
            "bytes": report.bytes,
            "bits_per_vertex": report.bits_per_vertex(),
            "rate_against_two_doubles": report.rate_against_two_doubles(),
            "rate_against_two_floats": report.rate_against_two_floats(),
            "mean_relative_error": report.mean_error(),
            "worst_relative_error": report.worst_error(),
            "relative_errors": report.relative_errors,
        })
    }

    /// The summary as aligned text lines, each ending in a newline.
    pub fn text(&self) -> String {
        let report = self.report;
        let mut text = String::new();
        let _ = writeln!(text, "frames                {}", report.frames);
        let _ = writeln!(
            text,
            "coefficients/frame    {} ({} pairs, {})",
            report.coefficients_per_frame,
            self.pairs,
            self.coding.description()
        );
        let _ = writeln!(text, "file size             {} bytes", report.bytes);
        let _ = writeln!(
            text,
            "bits per vertex       {:.3} (per frame)",
            report.bits_per_vertex()
        );
        let _ = writeln!(
            text,
            "rate vs 2 doubles/face {:.2}",
            report.rate_against_two_doubles()
        );
        let _ = writeln!(
            text,
            "rate vs 2 floats/face {:.2}",
            report.rate_against_two_floats()
        );
        let _ = writeln!(
            text,
            "relative L2 error     mean {:.4e}, worst {:.4e}",
            report.mean_error(),
            report.worst_error()
        );
        let _ = writeln!(text, "wrote                 {}", self.output.display());
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{
        basis_id, compress_with_progress, compute_basis, decompress_with_progress, BasisRequest,
        FieldCodec,
    };
    use std::sync::atomic::{AtomicUsize, Ordering};
    use tvf_discretizations::DEFAULT_DISCRETIZATION;

    #[test]
    fn every_frame_is_reported_and_summarised() {
        let (mesh, complex) = crate::test_torus::torus_complex(DEFAULT_DISCRETIZATION);
        let basis = compute_basis(complex.as_ref(), &BasisRequest::pairs(6)).unwrap();
        let column = |j: usize| -> Vec<f64> {
            (0..basis.field_dimension())
                .map(|i| basis.fields()[(i, j)])
                .collect()
        };
        let frames = vec![column(3), column(5), column(9)];
        let coding = CoefficientCoding::Quantized { bits: 12 };
        let codec = FieldCodec::new(&basis, 1, basis_id(&basis), 6, coding).unwrap();
        let (calls, largest) = (AtomicUsize::new(0), AtomicUsize::new(0));
        let on_frame = |done: usize| {
            calls.fetch_add(1, Ordering::Relaxed);
            largest.fetch_max(done, Ordering::Relaxed);
        };
        let mass = basis.field_mass();
        let (file, report) =
            compress_with_progress(&codec, mass, &frames, mesh.vertex_count(), &on_frame).unwrap();
        assert_eq!(
            (
                calls.load(Ordering::Relaxed),
                largest.load(Ordering::Relaxed)
            ),
            (3, 3)
        );
        let decoded = decompress_with_progress(&codec, &file, &on_frame).unwrap();
        // The three frames are one decoding group: one call, with all three done.
        assert_eq!(calls.load(Ordering::Relaxed), 4);
        assert_eq!(decoded.len(), 3);
        // Basis fields are kept: decoded up to quantisation.
        assert!(report.worst_error() < 1e-2, "{}", report.worst_error());
        assert!((decoded[1][0] - frames[1][0]).abs() < 1e-2);
        let summary = CompressionSummary {
            report: &report,
            output: Path::new("f.tvfc"),
            pairs: 6,
            coding,
            sequence: true,
        };
        let json = summary.to_json();
        assert_eq!(json["coding"], "quantised 12 bits, range-coded");
        assert_eq!(json["relative_errors"].as_array().unwrap().len(), 3);
        let text = summary.text();
        assert_eq!(text.lines().count(), 8);
        assert!(text.ends_with("wrote                 f.tvfc\n"), "{text}");
    }
}
