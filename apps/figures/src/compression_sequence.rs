//! The time-dependent compression experiment (Section 8.6, Figure 11): a sequence of fields on
//! the bumpy torus compressed with one basis; file sizes and the mean relative error per frame.

use crate::compression::available_pairs;
use crate::error::FigureError;
use crate::finding::{Experiment, Finding};
use crate::numbers::{seconds, thousands};
use crate::panels::save_magnitude_row;
use crate::test_fields::MovingFeatures;
use rayon::prelude::*;
use std::time::Instant;
use tvf_spectral::{
    basis_id, compress_with_report, CoefficientCoding, CompressionReport, FieldCodec,
};

/// Size of the sequence experiment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SequenceSize {
    /// Frames (the paper: 500).
    pub frames: usize,
    /// Pairs kept (the paper: 500 eigenfields, i.e. 250 pairs).
    pub pairs: usize,
    /// Moving sources and moving vortices (each).
    pub features: usize,
}

/// Megabytes (10⁶ bytes, as the paper counts).
fn megabytes(bytes: f64) -> String {
    format!("{:.2} MB", bytes / 1e6)
}

/// Compresses the sequence with 64-bit and with 16-bit quantised coefficients and draws one
/// frame (Figure 11) uncompressed beside compressed.
pub fn run(x: &Experiment, size: SequenceSize) -> Result<Finding, FigureError> {
    let moving = MovingFeatures::new(x.complex, x.mesh, size.features, 0.12, 11);
    let start = Instant::now();
    let frames: Vec<Vec<f64>> = (0..size.frames)
        .into_par_iter()
        .map(|k| moving.frame(x.complex, k as f64 / size.frames.max(1) as f64))
        .collect();
    let generate = start.elapsed().as_secs_f64();
    let mut finding = Finding::new(
        "Section 8.6 / Figure 11",
        "Compressing a time-dependent field (sequence of frames) with one basis",
        x.name,
    );
    let faces = x.mesh.face_count();
    let raw_floats = (size.frames * faces * 2 * 4) as f64;
    finding.number(
        "frames / faces",
        format!("{} / {}", size.frames, thousands(faces)),
    );
    finding.number(
        "uncompressed, two f32 per face (the paper's measure)",
        megabytes(raw_floats),
    );
    finding.number("generating the frames", seconds(generate));
    let mut mean_error = 0.0;
    let mut kept = 0;
    let mut codec64 = None;
    // The paper's size (64-bit and 16-bit quantised), then twice the pairs if the basis has them.
    let larger = 2 * size.pairs;
    let mut runs = vec![
        (size.pairs, CoefficientCoding::Float64),
        (size.pairs, CoefficientCoding::Quantized { bits: 16 }),
    ];
    if larger <= available_pairs(x) {
        runs.push((larger, CoefficientCoding::Float64));
    }
    let mut larger_error = None;
    for (pairs, coding) in runs {
        let (codec, report) = compress_once(x, &frames, pairs, coding, raw_floats, &mut finding)?;
        if pairs == larger {
            larger_error = Some(report.mean_error());
        } else if coding == CoefficientCoding::Float64 {
            kept = report.coefficients_per_frame;
            mean_error = report.mean_error();
            codec64 = Some(codec);
        }
    }
    let f32_bytes = (size.frames * kept * 4) as f64;
    finding.number(
        "coefficients per frame; as f32 (the paper's storage) the sequence is",
        format!("{kept}; {}", megabytes(f32_bytes)),
    );
    if let Some(codec) = codec64 {
        finding.files.push(draw_snapshot(x, &codec, &frames, kept)?);
    }
    finding.paper = "Bumpy torus (140,240 faces), 500 frames: 560.96 MB as two f32 per face, 1 MB \
                     with 500 eigenfields (f32 coefficients), mean relative L2 error about 10 %."
        .to_string();
    finding.comparison = format!(
        "Our bumpy torus has 31,752 faces (the public copy is coarser), so the raw sequence is \
         {} instead of 560.96 MB; with {kept} coefficients per frame stored as f32 the file is {} \
         (the paper: 1 MB, the same count). Mean error {:.1} % on our own moving-feature field \
         (the paper's field is not published; the error depends on how much fine detail the \
         field has).",
        megabytes(raw_floats),
        megabytes(f32_bytes),
        100.0 * mean_error
    );
    if let Some(e) = larger_error {
        finding.comparison.push_str(&format!(
            " With twice the pairs ({larger}) the mean error drops to {:.1} %.",
            100.0 * e
        ));
    }
    Ok(finding)
}

/// Compresses `frames` with `pairs` pairs and `coding` (file size, errors and time added to
/// `finding`, rates against `raw_floats` bytes); returns the codec and what it did.
fn compress_once<'a>(
    x: &Experiment<'a>,
    frames: &[Vec<f64>],
    pairs: usize,
    coding: CoefficientCoding,
    raw_floats: f64,
    finding: &mut Finding,
) -> Result<(FieldCodec<'a>, CompressionReport), FigureError> {
    let (fingerprint, id) = (x.mesh.fingerprint(), basis_id(x.basis));
    let codec = FieldCodec::new(x.basis, fingerprint, id, pairs, coding)?;
    let start = Instant::now();
    let (_, report) =
        compress_with_report(&codec, x.basis.field_mass(), frames, x.mesh.vertex_count())?;
    let elapsed = start.elapsed().as_secs_f64();
    let label = match coding {
        CoefficientCoding::Float64 => format!("{pairs} pairs, 64-bit coefficients"),
        CoefficientCoding::Quantized { bits } => {
            format!("{pairs} pairs, {bits}-bit quantised, range-coded")
        }
    };
    finding.number(
        format!("{label}: file size, rate against two f32 per face"),
        format!(
            "{} ({} bytes), {:.1}:1",
            megabytes(report.bytes as f64),
            thousands(report.bytes),
            raw_floats / report.bytes as f64
        ),
    );
    finding.number(
        format!("{label}: mean / worst relative L2 error per frame"),
        format!("{:.4} / {:.4}", report.mean_error(), report.worst_error()),
    );
    finding.number(
        format!("{label}: compress + decode + measure, all frames"),
        seconds(elapsed),
    );
    Ok((codec, report))
}

/// Figure 11: the frame three tenths into the sequence, uncompressed beside its round trip
/// through `codec` (`kept` coefficients); returns the picture's file name.
fn draw_snapshot(
    x: &Experiment,
    codec: &FieldCodec<'_>,
    frames: &[Vec<f64>],
    kept: usize,
) -> Result<String, FigureError> {
    let snapshot = frames.len() * 3 / 10;
    let original = &frames[snapshot];
    let compressed = codec.decode(&codec.encode(original)?)?;
    let file = "figure11_sequence_frame.png";
    save_magnitude_row(
        x,
        file,
        &[
            (original, &format!("frame {snapshot}: uncompressed")),
            (
                &compressed,
                &format!("frame {snapshot}: {kept} coefficients"),
            ),
        ],
    )?;
    Ok(file.to_string())
}
