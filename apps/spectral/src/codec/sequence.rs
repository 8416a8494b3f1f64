//! Compressing one field or a time-dependent sequence of fields with one basis, and measuring
//! what it cost: [`compress_with_report`] (with progress: [`compress_with_progress`]),
//! [`CompressionReport`]; decoding with progress: [`decompress_with_progress`].

use crate::codec::compress::FieldCodec;
use crate::codec::compression_error::CompressionError;
use crate::formats::compressed_file::CompressedFields;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use tvf_core::discretization::Mass;

/// Relative `M1` error `‖v − ṽ‖_{M1} / ‖v‖_{M1}` of an approximation (`mass` is the complex's
/// field mass; the absolute error if `v = 0`).
pub fn relative_l2_error(mass: &Mass, original: &[f64], approximation: &[f64]) -> f64 {
    let (difference, norm) = match mass.diagonal_values() {
        Some(mass) => {
            let mut difference = 0.0;
            let mut norm = 0.0;
            for ((v, a), m) in original.iter().zip(approximation).zip(mass) {
                difference += (v - a) * (v - a) * m;
                norm += v * v * m;
            }
            (difference, norm)
        }
        None => {
            let error: Vec<f64> = original
                .iter()
                .zip(approximation)
                .map(|(v, a)| v - a)
                .collect();
            (mass.inner(&error, &error), mass.inner(original, original))
        }
    };
    if norm > 0.0 {
        (difference / norm).sqrt()
    } else {
        difference.sqrt()
    }
}

/// Size and distortion of a compressed field or sequence.
#[derive(Debug, Clone, PartialEq)]
pub struct CompressionReport {
    /// Size of the whole `.tvfc` file (header, frames, checksum) in bytes.
    pub bytes: usize,
    /// Number of fields (frames).
    pub frames: usize,
    /// Vertices of the mesh (for bits per vertex).
    pub vertex_count: usize,
    /// Field coefficients `n1` of one frame (`2F` for face fields, `E` for 1-forms).
    pub field_dimension: usize,
    /// Coefficients kept per frame (`2k + h`).
    pub coefficients_per_frame: usize,
    /// Relative `M1` error of every frame.
    pub relative_errors: Vec<f64>,
}

impl CompressionReport {
    /// Mean relative error over the frames.
    pub fn mean_error(&self) -> f64 {
        self.relative_errors.iter().sum::<f64>() / self.relative_errors.len().max(1) as f64
    }

    /// Largest relative error over the frames.
    pub fn worst_error(&self) -> f64 {
        self.relative_errors.iter().fold(0.0, |m, &e| m.max(e))
    }

    /// File bits per vertex and frame, `8 · bytes / (V · T)` (the paper's `2·64·k/V` for `f64`
    /// coefficients, plus the small header).
    pub fn bits_per_vertex(&self) -> f64 {
        8.0 * self.bytes as f64 / (self.vertex_count.max(1) * self.frames.max(1)) as f64
    }

    /// Compression rate against the uncompressed frames, one double per field coefficient,
    /// `8 n1 T / bytes` (for face fields two doubles per face, `16 F T / bytes`).
    pub fn rate_against_two_doubles(&self) -> f64 {
        (8 * self.field_dimension * self.frames) as f64 / self.bytes.max(1) as f64
    }

    /// Compression rate against one single-precision float per field coefficient and frame,
    /// `4 n1 T / bytes` (for face fields two floats per face).
    pub fn rate_against_two_floats(&self) -> f64 {
        0.5 * self.rate_against_two_doubles()
    }
}

/// Compresses `fields` (one or many frames, `n1` pointwise coefficients each) and decodes the
/// result again to measure the error of every frame; frames run in parallel.
/// Returns the file and its report.
pub fn compress_with_report(
    codec: &FieldCodec<'_>,
    mass: &Mass,
    fields: &[Vec<f64>],
    vertex_count: usize,
) -> Result<(CompressedFields, CompressionReport), CompressionError> {
    compress_with_progress(codec, mass, fields, vertex_count, &|_| {})
}

/// [`compress_with_report`], calling `on_frame(done)` each time a frame has been encoded and
/// measured (`done` frames so far; frames finish in any order, from several threads).
pub fn compress_with_progress(
    codec: &FieldCodec<'_>,
    mass: &Mass,
    fields: &[Vec<f64>],
    vertex_count: usize,
    on_frame: &(dyn Fn(usize) + Sync),
) -> Result<(CompressedFields, CompressionReport), CompressionError> {
    if fields.is_empty() {
        return Err(CompressionError::NoFrames);
    }
    let done = AtomicUsize::new(0);
    let encoded = fields
        .par_iter()
        .map(|field| {
            let payload = codec.encode(field)?;
            let error = relative_l2_error(mass, field, &codec.decode(&payload)?);
            on_frame(done.fetch_add(1, Ordering::Relaxed) + 1);
            Ok((payload, error))
        })
        .collect::<Result<Vec<_>, CompressionError>>()?;
    let (frames, relative_errors): (Vec<_>, Vec<_>) = encoded.into_iter().unzip();
    let file = CompressedFields {
        header: *codec.header(),
        frames,
    };
    let report = CompressionReport {
        bytes: file.to_bytes().len(),
        frames: fields.len(),
        vertex_count,
        field_dimension: mass.len(),
        coefficients_per_frame: codec.selection().len(),
        relative_errors,
    };
    Ok((file, report))
}

/// Frames decoded together by [`decompress_with_progress`]: one synthesis
/// ([`crate::FieldBasis::reconstruct_many`]) per group, so that a basis file read in blocks is
/// read once per group, not once per frame, and progress is reported per group.
const DECODE_GROUP: usize = 16;

/// Decodes every frame of `file` (made by `codec`, see [`FieldCodec::for_file`]), a group of
/// [`DECODE_GROUP`] frames at a time (each group's coefficients in parallel, then synthesised
/// together), calling `on_frame(done)` after each group. Each field is the one
/// [`FieldCodec::decode`] gives, bit for bit.
pub fn decompress_with_progress(
    codec: &FieldCodec<'_>,
    file: &CompressedFields,
    on_frame: &(dyn Fn(usize) + Sync),
) -> Result<Vec<Vec<f64>>, CompressionError> {
    let mut fields = Vec::with_capacity(file.frames.len());
    for group in file.frames.chunks(DECODE_GROUP) {
        let coefficients = group
            .par_iter()
            .map(|payload| codec.decode_coefficients(payload))
            .collect::<Result<Vec<_>, _>>()?;
        let sets: Vec<&[f64]> = coefficients.iter().map(Vec::as_slice).collect();
        fields.extend(codec.basis().reconstruct_many(&sets)?);
        on_frame(fields.len());
    }
    Ok(fields)
}
