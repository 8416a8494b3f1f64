//! [`UniformQuantizer`]: uniform scalar quantisation of Fourier coefficients.
//!
//! The basis is `M_X`-orthonormal, so a coefficient error `δc` is a field error of exactly
//! `‖δc‖₂` in the `M_X` norm: one step for all coefficients spreads the error evenly, which is
//! the mean-square-optimal choice at high rate. The step is chosen per frame so that the largest
//! coefficient maps to the largest `bits`-bit symbol.

use crate::codec::symbol_coder::{max_magnitude, SymbolCodingError};

/// `q = round(c / step)`, `ĉ = q · step`; `|c − ĉ| ≤ step / 2` for every coefficient.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UniformQuantizer {
    step: f64,
    bits: u32,
}

impl UniformQuantizer {
    /// The quantiser with `bits`-bit symbols (`|q| ≤ 2^(bits−1) − 1`) whose range just covers
    /// `max |c|` (step 1 for an all-zero input).
    pub fn for_coefficients(coefficients: &[f64], bits: u32) -> Result<Self, SymbolCodingError> {
        if !(2..=32).contains(&bits) {
            return Err(SymbolCodingError::UnsupportedBits(bits));
        }
        let largest = coefficients.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        let step = if largest > 0.0 {
            largest / max_magnitude(bits) as f64
        } else {
            1.0
        };
        Ok(Self { step, bits })
    }

    /// A quantiser with a given step (as stored in a file); `step` must be finite and > 0.
    pub fn with_step(step: f64, bits: u32) -> Option<Self> {
        ((2..=32).contains(&bits) && step.is_finite() && step > 0.0).then_some(Self { step, bits })
    }

    /// The step (same units as the coefficients).
    pub fn step(&self) -> f64 {
        self.step
    }

    /// Symbol size in bits.
    pub fn bits(&self) -> u32 {
        self.bits
    }

    /// The largest error of one coefficient, `step / 2`.
    pub fn max_error(&self) -> f64 {
        0.5 * self.step
    }

    /// The symbols of `coefficients` (rounded to nearest, clamped to the symbol range).
    pub fn quantize(&self, coefficients: &[f64]) -> Vec<i64> {
        let limit = max_magnitude(self.bits) as f64;
        coefficients
            .iter()
            .map(|c| (c / self.step).round().clamp(-limit, limit) as i64)
            .collect()
    }

    /// The coefficients `q · step` of `symbols`.
    pub fn dequantize(&self, symbols: &[i64]) -> Vec<f64> {
        symbols.iter().map(|&q| q as f64 * self.step).collect()
    }
}
