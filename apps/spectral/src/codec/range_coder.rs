//! A binary adaptive range coder (the carry-propagating design of LZMA): 32-bit range, 11-bit
//! probabilities adapted by a shift of 5 after every coded bit.
//!
//! The encoder turns a sequence of bits, each coded with an adaptive [`BitModel`], into bytes
//! whose length is close to the bits' information content under the adapting models; the
//! decoder, fed the same models in the same order, returns the same bits.

/// Number of bits of a probability.
const PROBABILITY_BITS: u32 = 11;
/// `1.0` in probability units.
const PROBABILITY_ONE: u16 = 1 << PROBABILITY_BITS;
/// Adaptation speed: the probability moves `1/2^5` of the way towards the coded bit.
const ADAPTATION_SHIFT: u32 = 5;
/// The range is renormalised (a byte shifted out) when it falls below this.
const TOP: u32 = 1 << 24;

/// An adaptive estimate of the probability that the next bit is 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BitModel {
    probability_of_zero: u16,
}

impl Default for BitModel {
    fn default() -> Self {
        Self {
            probability_of_zero: PROBABILITY_ONE / 2,
        }
    }
}

impl BitModel {
    fn bound(&self, range: u32) -> u32 {
        (range >> PROBABILITY_BITS) * u32::from(self.probability_of_zero)
    }

    fn update(&mut self, bit: bool) {
        if bit {
            self.probability_of_zero -= self.probability_of_zero >> ADAPTATION_SHIFT;
        } else {
            self.probability_of_zero +=
                (PROBABILITY_ONE - self.probability_of_zero) >> ADAPTATION_SHIFT;
        }
    }
}

/// Encodes bits into a byte vector.
#[derive(Debug, Clone)]
pub struct RangeEncoder {
    low: u64,
    range: u32,
    cache: u8,
    cache_size: u64,
    output: Vec<u8>,
}

impl Default for RangeEncoder {
    fn default() -> Self {
        Self::new()
    }
}

impl RangeEncoder {
    /// An empty encoder.
    pub fn new() -> Self {
        Self {
            low: 0,
            range: u32::MAX,
            cache: 0,
            cache_size: 1,
            output: Vec::new(),
        }
    }

    /// Codes `bit` with `model` and adapts the model.
    pub fn encode(&mut self, model: &mut BitModel, bit: bool) {
        let bound = model.bound(self.range);
        if bit {
            self.low += u64::from(bound);
            self.range -= bound;
        } else {
            self.range = bound;
        }
        model.update(bit);
        while self.range < TOP {
            self.range <<= 8;
            self.shift_low();
        }
    }

    fn shift_low(&mut self) {
        if self.low < 0xFF00_0000 || self.low > 0xFFFF_FFFF {
            let carry = (self.low >> 32) as u8;
            let mut pending = self.cache;
            loop {
                self.output.push(pending.wrapping_add(carry));
                pending = 0xFF;
                self.cache_size -= 1;
                if self.cache_size == 0 {
                    break;
                }
            }
            self.cache = ((self.low >> 24) & 0xFF) as u8;
        }
        self.cache_size += 1;
        self.low = (self.low & 0x00FF_FFFF) << 8;
    }

    /// Flushes the state and returns the bytes.
    pub fn finish(mut self) -> Vec<u8> {
        for _ in 0..5 {
            self.shift_low();
        }
        self.output
    }
}

/// Decodes bits from bytes written by [`RangeEncoder`]. Reading past the end yields zero bytes;
/// [`overrun`](Self::overrun) tells how many were invented, so a caller can refuse a stream that
/// was cut short.
#[derive(Debug, Clone)]
pub struct RangeDecoder<'a> {
    input: &'a [u8],
    position: usize,
    range: u32,
    code: u32,
}

impl<'a> RangeDecoder<'a> {
    /// Starts decoding `input`.
    pub fn new(input: &'a [u8]) -> Self {
        let mut decoder = Self {
            input,
            position: 0,
            range: u32::MAX,
            code: 0,
        };
        for _ in 0..5 {
            decoder.code = (decoder.code << 8) | u32::from(decoder.next_byte());
        }
        decoder
    }

    fn next_byte(&mut self) -> u8 {
        let byte = self.input.get(self.position).copied().unwrap_or(0);
        self.position += 1;
        byte
    }

    fn normalize(&mut self) {
        while self.range < TOP {
            self.range <<= 8;
            self.code = (self.code << 8) | u32::from(self.next_byte());
        }
    }

    /// Decodes one bit with `model` and adapts the model.
    pub fn decode(&mut self, model: &mut BitModel) -> bool {
        let bound = model.bound(self.range);
        let bit = if self.code < bound {
            self.range = bound;
            false
        } else {
            self.code -= bound;
            self.range -= bound;
            true
        };
        model.update(bit);
        self.normalize();
        bit
    }

    /// Number of bytes read beyond the end of the input (0 for an intact stream).
    pub fn overrun(&self) -> usize {
        self.position.saturating_sub(self.input.len())
    }

    /// Number of input bytes consumed so far (the encoder's output length once all bits are
    /// decoded).
    pub fn consumed(&self) -> usize {
        self.position
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn skewed_bits_cost_less_than_one_bit_each() {
        let mut encoder = RangeEncoder::new();
        let mut model = BitModel::default();
        let bits: Vec<bool> = (0..10_000).map(|i| i % 50 == 0).collect();
        for &bit in &bits {
            encoder.encode(&mut model, bit);
        }
        let bytes = encoder.finish();
        // Entropy of p = 0.02 is 0.14 bit; allow adaptation overhead.
        assert!(bytes.len() * 8 < 10_000 / 4, "{} bytes", bytes.len());
        let mut decoder = RangeDecoder::new(&bytes);
        let mut model = BitModel::default();
        for &bit in &bits {
            assert_eq!(decoder.decode(&mut model), bit);
        }
        assert_eq!(decoder.overrun(), 0);
    }
}
