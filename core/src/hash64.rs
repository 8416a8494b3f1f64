//! [`Hash64`]: a fast streaming 64-bit hash (checksums of files, fingerprints of meshes).
//!
//! The hash reads 8-byte little-endian words; every step `h ← rotl((h ⊕ w) · P, 29)` is a
//! bijection both of `h` and of `w`, so changing any single word (in particular flipping any
//! number of bits inside one 8-byte word) always changes the result. It is a checksum against
//! damage and a key for caches, not a cryptographic hash.

const P1: u64 = 0x9e37_79b9_7f4a_7c15;
const P2: u64 = 0xc2b2_ae3d_27d4_eb4f;
const P3: u64 = 0x1656_67b1_9e37_79f9;

/// Incremental 64-bit hash of a byte stream (see the module docs).
#[derive(Debug, Clone)]
pub struct Hash64 {
    state: u64,
    length: u64,
    tail: [u8; 8],
    tail_len: usize,
}

impl Default for Hash64 {
    fn default() -> Self {
        Self::new()
    }
}

impl Hash64 {
    /// A fresh hash.
    pub fn new() -> Self {
        Self {
            state: P3,
            length: 0,
            tail: [0; 8],
            tail_len: 0,
        }
    }

    #[inline]
    fn word(&mut self, w: u64) {
        self.state = (self.state ^ w).wrapping_mul(P1).rotate_left(29);
    }

    /// Feeds bytes.
    pub fn update(&mut self, mut bytes: &[u8]) {
        self.length += bytes.len() as u64;
        if self.tail_len > 0 {
            let take = (8 - self.tail_len).min(bytes.len());
            self.tail[self.tail_len..self.tail_len + take].copy_from_slice(&bytes[..take]);
            self.tail_len += take;
            bytes = &bytes[take..];
            if self.tail_len < 8 {
                return;
            }
            let w = u64::from_le_bytes(self.tail);
            self.word(w);
            self.tail_len = 0;
        }
        let mut chunks = bytes.chunks_exact(8);
        for chunk in &mut chunks {
            let mut w = [0u8; 8];
            w.copy_from_slice(chunk);
            self.word(u64::from_le_bytes(w));
        }
        let rest = chunks.remainder();
        self.tail[..rest.len()].copy_from_slice(rest);
        self.tail_len = rest.len();
    }

    /// Feeds one `u64` as 8 little-endian bytes.
    pub fn update_u64(&mut self, value: u64) {
        self.update(&value.to_le_bytes());
    }

    /// Feeds the exact bits of an `f64` (so `0.0` and `-0.0` differ).
    pub fn update_f64(&mut self, value: f64) {
        self.update_u64(value.to_bits());
    }

    /// The hash of everything fed so far (the hasher can keep going).
    pub fn finish(&self) -> u64 {
        let mut h = self.state;
        if self.tail_len > 0 {
            let mut w = [0u8; 8];
            w[..self.tail_len].copy_from_slice(&self.tail[..self.tail_len]);
            h = (h ^ u64::from_le_bytes(w)).wrapping_mul(P1).rotate_left(29);
        }
        h ^= self.length.wrapping_mul(P2);
        h ^= h >> 33;
        h = h.wrapping_mul(P2);
        h ^= h >> 29;
        h = h.wrapping_mul(P3);
        h ^ (h >> 32)
    }

    /// The hash of one byte slice.
    pub fn of(bytes: &[u8]) -> u64 {
        let mut h = Self::new();
        h.update(bytes);
        h.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streaming_equals_one_shot_and_detects_changes() {
        let data: Vec<u8> = (0..1000u32).map(|i| (i * 7 % 251) as u8).collect();
        let whole = Hash64::of(&data);
        let mut h = Hash64::new();
        for piece in data.chunks(13) {
            h.update(piece);
        }
        assert_eq!(h.finish(), whole);
        for position in [0, 7, 8, 500, 999] {
            let mut damaged = data.clone();
            damaged[position] ^= 0x10;
            assert_ne!(Hash64::of(&damaged), whole);
        }
        assert_ne!(Hash64::of(&data[..999]), whole);
        assert_ne!(Hash64::of(&[]), Hash64::of(&[0]));
    }
}
