//! The entropy coder round-trips arbitrary symbol streams, and codes skewed streams compactly.

use proptest::prelude::*;
use tvf_spectral::range_coder::{BitModel, RangeDecoder, RangeEncoder};
use tvf_spectral::{decode_symbols, encode_symbols, max_magnitude, SymbolCodingError};

fn symbol_stream() -> impl Strategy<Value = (u32, Vec<i64>)> {
    (2u32..=32).prop_flat_map(|bits| {
        let limit = max_magnitude(bits);
        // Mix small and full-range symbols so both the unary lengths and the mantissas vary.
        let small = limit.min(3);
        let symbol = prop_oneof![-small..=small, -limit..=limit];
        (Just(bits), prop::collection::vec(symbol, 0..600))
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn symbol_streams_round_trip((bits, symbols) in symbol_stream()) {
        let bytes = encode_symbols(&symbols, bits).unwrap();
        let decoded = decode_symbols(&bytes, symbols.len(), bits).unwrap();
        prop_assert_eq!(decoded, symbols);
    }

    #[test]
    fn bit_streams_round_trip(bits in prop::collection::vec((any::<bool>(), 0usize..4), 0..2000)) {
        let mut encoder = RangeEncoder::new();
        let mut models = [BitModel::default(); 4];
        for &(bit, model) in &bits {
            encoder.encode(&mut models[model], bit);
        }
        let bytes = encoder.finish();
        let mut decoder = RangeDecoder::new(&bytes);
        let mut models = [BitModel::default(); 4];
        for &(bit, model) in &bits {
            prop_assert_eq!(decoder.decode(&mut models[model]), bit);
        }
        prop_assert_eq!(decoder.overrun(), 0);
        prop_assert_eq!(decoder.consumed(), bytes.len());
    }
}

#[test]
fn decaying_coefficients_cost_far_less_than_their_bit_budget() {
    // Magnitudes decaying like 1/i (a smooth field's spectrum) with pseudo-random signs.
    let bits = 12;
    let limit = max_magnitude(bits) as f64;
    let symbols: Vec<i64> = (1..=4000)
        .map(|i: i64| {
            let sign = if (i * 2_654_435_761) % 7 < 3 { -1 } else { 1 };
            sign * (limit / i as f64).round() as i64
        })
        .collect();
    let bytes = encode_symbols(&symbols, bits).unwrap();
    let bits_per_symbol = 8.0 * bytes.len() as f64 / symbols.len() as f64;
    assert!(bits_per_symbol < 3.5, "{bits_per_symbol} bits per symbol");
    assert_eq!(
        decode_symbols(&bytes, symbols.len(), bits).unwrap(),
        symbols
    );
}

#[test]
fn out_of_range_symbols_and_cut_streams_are_refused() {
    assert!(matches!(
        encode_symbols(&[0, 8], 4),
        Err(SymbolCodingError::SymbolTooLarge {
            index: 1,
            value: 8,
            bits: 4
        })
    ));
    assert!(matches!(
        encode_symbols(&[0], 1),
        Err(SymbolCodingError::UnsupportedBits(1))
    ));
    let symbols: Vec<i64> = (0..500).map(|i| (i % 37) - 18).collect();
    let bytes = encode_symbols(&symbols, 8).unwrap();
    assert!(matches!(
        decode_symbols(&bytes[..bytes.len() / 2], symbols.len(), 8),
        Err(SymbolCodingError::Damaged { .. })
    ));
    let mut longer = bytes.clone();
    longer.push(0);
    assert!(matches!(
        decode_symbols(&longer, symbols.len(), 8),
        Err(SymbolCodingError::Damaged { .. })
    ));
}
