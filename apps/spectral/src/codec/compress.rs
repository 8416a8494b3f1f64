//! [`FieldCodec`]: lossy compression of tangent fields by truncating their Fourier series
//! (Section 8.6 of the paper), with the coefficients stored as `f64` (the paper) or quantised and
//! range-coded (beyond the paper).

use crate::basis::FieldFamily;
use crate::codec::compression_error::CompressionError;
use crate::codec::quantization::UniformQuantizer;
use crate::codec::symbol_coder::{decode_symbols, encode_symbols};
use crate::formats::compressed_file::{
    CoefficientCoding, CompressedFields, FramePayload, TvfcHeader,
};
use crate::FieldBasis;
use rayon::prelude::*;

/// The basis fields kept when compressing with `pairs` pairs: the lowest `pairs` integrable, the
/// lowest `pairs` co-integrable and every harmonic field, as ascending basis indices
/// (`2·pairs + h` of them; the paper's rate `2·64·k/V` bits per vertex counts these pairs).
/// A family with fewer than `pairs` fields is kept whole (so a large enough `pairs` keeps a
/// complete basis whole); `pairs` beyond both families is an error.
pub fn pair_selection(
    basis: &dyn FieldBasis,
    pairs: usize,
) -> Result<Vec<usize>, CompressionError> {
    let mut integrable = 0;
    let mut cointegrable = 0;
    let mut selection = Vec::with_capacity(2 * pairs + 8);
    for (index, family) in basis.families().iter().enumerate() {
        let keep = match family {
            FieldFamily::Harmonic => true,
            FieldFamily::Integrable => {
                integrable += 1;
                integrable <= pairs
            }
            FieldFamily::Cointegrable => {
                cointegrable += 1;
                cointegrable <= pairs
            }
        };
        if keep {
            selection.push(index);
        }
    }
    if integrable < pairs && cointegrable < pairs {
        let (family, available) = if integrable >= cointegrable {
            ("integrable", integrable)
        } else {
            ("cointegrable", cointegrable)
        };
        return Err(CompressionError::NotEnoughFields {
            family,
            available,
            requested: pairs,
        });
    }
    Ok(selection)
}

/// Compresses and decompresses fields on one mesh in one basis.
///
/// A field `v` (`n1` pointwise coefficients) becomes the coefficients `c = U_Sᵀ M_X v` of the
/// kept basis fields `S` ([`pair_selection`]); decoding returns `U_S ĉ`. With `f64` storage
/// `ĉ = c` bit-exactly; with quantisation `|ĉ_i − c_i| ≤ step/2`, so the decoded field is within
/// `(step/2)·√|S|` (`M_X` norm) of the projection `U_S c`.
///
/// The basis is any [`FieldBasis`]: in memory, or a basis file read in blocks (whose
/// coefficients and syntheses equal the loaded basis's to round-off, see
/// [`crate::BasisFileBlocks`]).
#[derive(Clone)]
pub struct FieldCodec<'a> {
    basis: &'a dyn FieldBasis,
    header: TvfcHeader,
    selection: Vec<usize>,
}

impl std::fmt::Debug for FieldCodec<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FieldCodec")
            .field("basis_fields", &self.basis.len())
            .field("header", &self.header)
            .field("selection", &self.selection)
            .finish()
    }
}

impl<'a> FieldCodec<'a> {
    /// A codec keeping `pairs` pairs of `basis`, for files stamped with the mesh fingerprint and
    /// the basis id ([`basis_id`](crate::formats::basis_id) of `basis`, or
    /// [`field_basis_id`](crate::field_basis_id), passed in because it hashes the whole basis).
    pub fn new(
        basis: &'a dyn FieldBasis,
        mesh_fingerprint: u64,
        basis_id: u64,
        pairs: usize,
        coding: CoefficientCoding,
    ) -> Result<Self, CompressionError> {
        if let CoefficientCoding::Quantized { bits } = coding {
            if !(2..=32).contains(&bits) {
                return Err(crate::SymbolCodingError::UnsupportedBits(bits).into());
            }
        }
        let selection = pair_selection(basis, pairs)?;
        let header = TvfcHeader {
            mesh_fingerprint,
            basis_id,
            field_dimension: basis.field_dimension() as u64,
            pairs: u32::try_from(pairs).map_err(|_| {
                CompressionError::InvalidHeader(format!("{pairs} pairs do not fit 32 bits"))
            })?,
            coefficients: selection.len() as u32,
            coding,
        };
        Ok(Self {
            basis,
            header,
            selection,
        })
    }

    /// The codec that decodes `file`, after checking that it was made on this mesh (fingerprint)
    /// with this basis (id, dimension, coefficient count).
    pub fn for_file(
        basis: &'a dyn FieldBasis,
        mesh_fingerprint: u64,
        basis_id: u64,
        file: &TvfcHeader,
    ) -> Result<Self, CompressionError> {
        if file.mesh_fingerprint != mesh_fingerprint {
            return Err(CompressionError::MeshMismatch {
                file: file.mesh_fingerprint,
                mesh: mesh_fingerprint,
            });
        }
        if file.basis_id != basis_id {
            return Err(CompressionError::BasisMismatch {
                file: file.basis_id,
                basis: basis_id,
            });
        }
        let codec = Self::new(
            basis,
            mesh_fingerprint,
            basis_id,
            file.pairs as usize,
            file.coding,
        )?;
        if codec.header != *file {
            return Err(CompressionError::InvalidHeader(format!(
                "header {file:?} does not fit the basis (expected {:?})",
                codec.header
            )));
        }
        Ok(codec)
    }

    /// The basis the codec projects on and synthesises from.
    pub fn basis(&self) -> &'a dyn FieldBasis {
        self.basis
    }

    /// The header of files this codec writes.
    pub fn header(&self) -> &TvfcHeader {
        &self.header
    }

    /// The kept basis indices, ascending.
    pub fn selection(&self) -> &[usize] {
        &self.selection
    }

    /// Encodes a field given all `d` of its basis coefficients (`Uᵀ M_X v`).
    pub fn encode_coefficients(
        &self,
        coefficients: &[f64],
    ) -> Result<FramePayload, CompressionError> {
        if coefficients.len() != self.basis.len() {
            return Err(crate::SpectralBasisError::LengthMismatch {
                what: "coefficients",
                expected: self.basis.len(),
                actual: coefficients.len(),
            }
            .into());
        }
        let kept: Vec<f64> = self.selection.iter().map(|&i| coefficients[i]).collect();
        if let Some(index) = kept.iter().position(|c| !c.is_finite()) {
            return Err(CompressionError::NonFinite {
                what: "coefficient",
                index,
            });
        }
        Ok(match self.header.coding {
            CoefficientCoding::Float64 => FramePayload::Float64(kept),
            CoefficientCoding::Quantized { bits } => {
                let quantizer = UniformQuantizer::for_coefficients(&kept, bits)?;
                let bytes = encode_symbols(&quantizer.quantize(&kept), bits)?;
                FramePayload::Quantized {
                    step: quantizer.step(),
                    bytes,
                }
            }
        })
    }

    /// Encodes a field (`n1` pointwise coefficients).
    pub fn encode(&self, field: &[f64]) -> Result<FramePayload, CompressionError> {
        if let Some(index) = field.iter().position(|x| !x.is_finite()) {
            return Err(CompressionError::NonFinite {
                what: "field",
                index,
            });
        }
        self.encode_coefficients(&self.basis.coefficients(field)?)
    }

    /// The decoded coefficients of all `d` basis fields (zero outside the selection).
    pub fn decode_coefficients(
        &self,
        payload: &FramePayload,
    ) -> Result<Vec<f64>, CompressionError> {
        let n = self.selection.len();
        let kept = match (payload, self.header.coding) {
            (FramePayload::Float64(values), CoefficientCoding::Float64) if values.len() == n => {
                values.clone()
            }
            (FramePayload::Quantized { step, bytes }, CoefficientCoding::Quantized { bits }) => {
                let quantizer = UniformQuantizer::with_step(*step, bits).ok_or_else(|| {
                    CompressionError::InvalidHeader(format!(
                        "quantisation step {step} is not a positive number"
                    ))
                })?;
                quantizer.dequantize(&decode_symbols(bytes, n, bits)?)
            }
            _ => {
                return Err(CompressionError::InvalidHeader(
                    "frame does not match the file's coefficient coding".to_string(),
                ))
            }
        };
        let mut all = vec![0.0; self.basis.len()];
        for (&index, value) in self.selection.iter().zip(kept) {
            all[index] = value;
        }
        Ok(all)
    }

    /// Decodes one frame into a field (`n1` pointwise coefficients).
    pub fn decode(&self, payload: &FramePayload) -> Result<Vec<f64>, CompressionError> {
        Ok(self
            .basis
            .reconstruct(&self.decode_coefficients(payload)?)?)
    }

    /// Compresses every field (frames in parallel).
    pub fn compress(&self, fields: &[Vec<f64>]) -> Result<CompressedFields, CompressionError> {
        if fields.is_empty() {
            return Err(CompressionError::NoFrames);
        }
        let frames = fields
            .par_iter()
            .map(|field| self.encode(field))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(CompressedFields {
            header: self.header,
            frames,
        })
    }

    /// Decompresses every frame of a file made by this codec (the syntheses through
    /// [`FieldBasis::reconstruct_many`]: a basis file read in blocks is read once).
    pub fn decompress(&self, file: &CompressedFields) -> Result<Vec<Vec<f64>>, CompressionError> {
        if file.header != self.header {
            return Err(CompressionError::InvalidHeader(
                "file header does not match the codec (use FieldCodec::for_file)".to_string(),
            ));
        }
        let coefficients = file
            .frames
            .par_iter()
            .map(|frame| self.decode_coefficients(frame))
            .collect::<Result<Vec<_>, _>>()?;
        let sets: Vec<&[f64]> = coefficients.iter().map(Vec::as_slice).collect();
        Ok(self.basis.reconstruct_many(&sets)?)
    }
}
