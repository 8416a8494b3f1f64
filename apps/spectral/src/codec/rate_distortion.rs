//! Rate–distortion curves (the paper's Figure 9): relative `M_X` error against bits per vertex,
//! for several numbers of pairs and coefficient codings. Every point is a real file: its size is
//! the serialised `.tvfc` length and its error is measured on the decoded field.

use crate::codec::compress::FieldCodec;
use crate::codec::compression_error::CompressionError;
use crate::codec::sequence::relative_l2_error;
use crate::formats::compressed_file::{CoefficientCoding, CompressedFields};
use crate::FieldBasis;
use rayon::prelude::*;

/// One compressed file of the curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RatePoint {
    /// How the coefficients were stored.
    pub coding: CoefficientCoding,
    /// Pairs `k` kept.
    pub pairs: usize,
    /// File size in bytes (header and checksum included).
    pub bytes: usize,
    /// `8 · bytes / V`.
    pub bits_per_vertex: f64,
    /// `‖v − ṽ‖_{M_X} / ‖v‖_{M_X}`.
    pub relative_error: f64,
}

/// What one mesh and basis are identified by in the files.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FileStamp {
    /// Fingerprint of the mesh.
    pub mesh_fingerprint: u64,
    /// [`basis_id`](crate::formats::basis_id) of the basis.
    pub basis_id: u64,
    /// Vertices of the mesh (for bits per vertex).
    pub vertex_count: usize,
}

/// Compresses `field` (`n1` pointwise coefficients) once for every `(pairs, coding)` combination
/// and measures size and error; points in parallel, ordered by coding then pairs as given. The
/// basis is any [`FieldBasis`]: a basis file read in blocks synthesises each point's decoded
/// field in one pass over the file (its points equal the loaded basis's to round-off: the
/// projection sums in another order).
pub fn rate_distortion(
    basis: &dyn FieldBasis,
    field: &[f64],
    stamp: FileStamp,
    pairs: &[usize],
    codings: &[CoefficientCoding],
) -> Result<Vec<RatePoint>, CompressionError> {
    if let Some(index) = field.iter().position(|x| !x.is_finite()) {
        return Err(CompressionError::NonFinite {
            what: "field",
            index,
        });
    }
    let coefficients = basis.coefficients(field)?;
    let jobs: Vec<(CoefficientCoding, usize)> = codings
        .iter()
        .flat_map(|&coding| pairs.iter().map(move |&k| (coding, k)))
        .collect();
    // Every point's file and decoded coefficients in parallel, then all decoded fields in one
    // synthesis (one pass over a basis file read in blocks).
    let files = jobs
        .par_iter()
        .map(|&(coding, k)| {
            let codec = FieldCodec::new(basis, stamp.mesh_fingerprint, stamp.basis_id, k, coding)?;
            let frame = codec.encode_coefficients(&coefficients)?;
            let decoded = codec.decode_coefficients(&frame)?;
            let file = CompressedFields {
                header: *codec.header(),
                frames: vec![frame],
            };
            Ok((file.to_bytes().len(), decoded))
        })
        .collect::<Result<Vec<_>, CompressionError>>()?;
    let sets: Vec<&[f64]> = files
        .iter()
        .map(|(_, decoded)| decoded.as_slice())
        .collect();
    let decoded = basis.reconstruct_many(&sets)?;
    Ok(jobs
        .iter()
        .zip(&files)
        .zip(&decoded)
        .map(|((&(coding, k), &(bytes, _)), decoded)| RatePoint {
            coding,
            pairs: k,
            bytes,
            bits_per_vertex: 8.0 * bytes as f64 / stamp.vertex_count.max(1) as f64,
            relative_error: relative_l2_error(basis.field_mass(), field, decoded),
        })
        .collect())
}

/// For every `f64` point, the smallest quantised file with an error at most as large:
/// `(f64 point, quantised point)` pairs (the saving is the ratio of their sizes). `f64` points
/// no quantised point matches are left out.
pub fn equal_error_comparison(points: &[RatePoint]) -> Vec<(RatePoint, RatePoint)> {
    points
        .iter()
        .filter(|p| p.coding == CoefficientCoding::Float64)
        .filter_map(|exact| {
            points
                .iter()
                .filter(|q| {
                    matches!(q.coding, CoefficientCoding::Quantized { .. })
                        && q.relative_error <= exact.relative_error
                })
                .min_by_key(|q| q.bytes)
                .map(|q| (*exact, *q))
        })
        .collect()
}

/// The points as CSV: a header `coding,bits,pairs,bytes,bits_per_vertex,relative_error`, then
/// one line per point (`f64` coding as `f64,64`, quantised as `quantized,Q`).
pub fn rate_distortion_csv(points: &[RatePoint]) -> String {
    let mut csv = String::from("coding,bits,pairs,bytes,bits_per_vertex,relative_error\n");
    for p in points {
        let (name, bits) = match p.coding {
            CoefficientCoding::Float64 => ("f64", 64),
            CoefficientCoding::Quantized { bits } => ("quantized", bits),
        };
        csv.push_str(&format!(
            "{name},{bits},{},{},{:.6},{:e}\n",
            p.pairs, p.bytes, p.bits_per_vertex, p.relative_error
        ));
    }
    csv
}
