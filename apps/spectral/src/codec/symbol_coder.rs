//! Entropy coding of quantised coefficients (signed integers) with the binary adaptive
//! [`range_coder`](crate::range_coder).
//!
//! Each symbol `q` is binarised as
//! 1. the bit length `L` of `|q|` (0 for `q = 0`, at most `bits − 1`), coded MSB-first through a
//!    binary tree of adaptive models (5 decisions for 32-bit symbols);
//! 2. for `q ≠ 0`: the sign (one adaptive model) and the `L − 1` bits below the leading one,
//!    modelled per (length, position).
//!
//! The tree used for `L` is selected by a context: the mean bit length of the two previous
//! symbols (coefficients are coded in order of frequency, and their size drifts slowly with
//! frequency, so the neighbours predict the next one well).

use crate::codec::range_coder::{BitModel, RangeDecoder, RangeEncoder};
use thiserror::Error;

/// Number of neighbourhood contexts (mean bit length of the two previous symbols: 0 to 31).
const CONTEXTS: usize = 32;

/// Why a symbol stream could not be coded or decoded.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum SymbolCodingError {
    /// `bits` is outside `2..=32`.
    #[error("quantisation uses {0} bits: supported are 2 to 32")]
    UnsupportedBits(u32),
    /// A symbol does not fit `bits` (`|q| ≤ 2^(bits−1) − 1`).
    #[error("symbol {index} = {value} does not fit {bits} bits")]
    SymbolTooLarge {
        /// Position in the stream.
        index: usize,
        /// The symbol.
        value: i64,
        /// The bit budget.
        bits: u32,
    },
    /// The coded stream ended before all symbols were decoded, or has bytes left over.
    #[error("entropy-coded stream of {length} bytes is damaged: decoding {count} symbols used {consumed} bytes")]
    Damaged {
        /// Bytes in the stream.
        length: usize,
        /// Bytes the decoder consumed.
        consumed: usize,
        /// Symbols that were to be decoded.
        count: usize,
    },
}

/// The adaptive models of one stream.
struct Models {
    max_length: usize,
    /// Levels of the length tree: `L ∈ 0..=max_length` takes `depth` binary decisions.
    depth: u32,
    /// `length[ctx << depth | node]`, node `1..2^depth` (heap order).
    length: Vec<BitModel>,
    sign: BitModel,
    /// `mantissa[L * max_length + j]`: bit `j` below the leading one of a length-`L` magnitude.
    mantissa: Vec<BitModel>,
}

impl Models {
    fn new(bits: u32) -> Result<Self, SymbolCodingError> {
        if !(2..=32).contains(&bits) {
            return Err(SymbolCodingError::UnsupportedBits(bits));
        }
        let max_length = bits as usize - 1;
        let depth = usize::BITS - max_length.leading_zeros();
        Ok(Self {
            max_length,
            depth,
            length: vec![BitModel::default(); CONTEXTS << depth],
            sign: BitModel::default(),
            mantissa: vec![BitModel::default(); (max_length + 1) * max_length],
        })
    }

    fn tree(&mut self, ctx: usize) -> &mut [BitModel] {
        let size = 1usize << self.depth;
        &mut self.length[ctx * size..(ctx + 1) * size]
    }
}

/// Largest magnitude a `bits`-bit symbol may have: `2^(bits−1) − 1`.
pub fn max_magnitude(bits: u32) -> i64 {
    (1i64 << (bits.clamp(2, 32) - 1)) - 1
}

fn bit_length(magnitude: u64) -> usize {
    (64 - magnitude.leading_zeros()) as usize
}

fn context(previous: [usize; 2]) -> usize {
    ((previous[0] + previous[1]).div_ceil(2)).min(CONTEXTS - 1)
}

/// Codes `symbols` (each `|q| ≤ 2^(bits−1) − 1`) into bytes.
pub fn encode_symbols(symbols: &[i64], bits: u32) -> Result<Vec<u8>, SymbolCodingError> {
    let mut models = Models::new(bits)?;
    let limit = max_magnitude(bits);
    let mut encoder = RangeEncoder::new();
    let mut previous = [0usize; 2];
    for (index, &value) in symbols.iter().enumerate() {
        if value.unsigned_abs() > limit as u64 {
            return Err(SymbolCodingError::SymbolTooLarge { index, value, bits });
        }
        let magnitude = value.unsigned_abs();
        let length = bit_length(magnitude);
        let depth = models.depth;
        let tree = models.tree(context(previous));
        let mut node = 1;
        for level in (0..depth).rev() {
            let bit = (length >> level) & 1 == 1;
            encoder.encode(&mut tree[node], bit);
            node = 2 * node + usize::from(bit);
        }
        if length > 0 {
            encoder.encode(&mut models.sign, value < 0);
            let m = models.max_length;
            for j in (0..length - 1).rev() {
                let bit = (magnitude >> j) & 1 == 1;
                encoder.encode(&mut models.mantissa[length * m + j], bit);
            }
        }
        previous = [length, previous[0]];
    }
    Ok(encoder.finish())
}

/// Decodes `count` symbols of `bits` bits from `bytes` (written by [`encode_symbols`]).
/// A stream that is cut short or has bytes left over is [`SymbolCodingError::Damaged`].
pub fn decode_symbols(
    bytes: &[u8],
    count: usize,
    bits: u32,
) -> Result<Vec<i64>, SymbolCodingError> {
    let mut models = Models::new(bits)?;
    let mut decoder = RangeDecoder::new(bytes);
    let mut symbols = Vec::with_capacity(count.min(bytes.len().saturating_mul(8)));
    let mut previous = [0usize; 2];
    for _ in 0..count {
        let depth = models.depth;
        let tree = models.tree(context(previous));
        let mut node = 1;
        for _ in 0..depth {
            node = 2 * node + usize::from(decoder.decode(&mut tree[node]));
        }
        let length = node - (1 << depth);
        let mut value = 0i64;
        if length > models.max_length {
            break; // impossible in an intact stream
        }
        if length > 0 {
            let negative = decoder.decode(&mut models.sign);
            let m = models.max_length;
            let mut magnitude = 1u64;
            for j in (0..length - 1).rev() {
                let bit = decoder.decode(&mut models.mantissa[length * m + j]);
                magnitude = (magnitude << 1) | u64::from(bit);
            }
            value = if negative {
                -(magnitude as i64)
            } else {
                magnitude as i64
            };
        }
        symbols.push(value);
        previous = [length, previous[0]];
        if decoder.overrun() > 0 {
            break;
        }
    }
    if decoder.overrun() > 0 || decoder.consumed() != bytes.len() || symbols.len() != count {
        return Err(SymbolCodingError::Damaged {
            length: bytes.len(),
            consumed: decoder.consumed(),
            count,
        });
    }
    Ok(symbols)
}
