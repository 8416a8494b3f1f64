//! Fuzzes the `.tvfc` compressed-file parser: any bytes must give a file or a typed error,
//! never a panic; a file that parses is written back to bytes that parse again.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tvf_spectral::CompressedFields;

fuzz_target!(|data: &[u8]| {
    if let Ok(file) = CompressedFields::from_bytes(data) {
        assert!(CompressedFields::from_bytes(&file.to_bytes()).is_ok());
    }
});
