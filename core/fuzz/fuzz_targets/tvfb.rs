//! Fuzzes the `.tvfb` basis-file reader (through a temporary file: it reads from disk): any
//! bytes must give a basis or a typed error naming the file, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tvf_spectral::read_basis_file;

fuzz_target!(|data: &[u8]| {
    let Ok(dir) = tempfile::tempdir() else { return };
    let path = dir.path().join("fuzz.tvfb");
    if std::fs::write(&path, data).is_err() {
        return;
    }
    match read_basis_file(&path) {
        Ok((header, basis)) => assert_eq!(header.field_count, basis.len()),
        Err(error) => assert!(error.to_string().contains("fuzz.tvfb")),
    }
});
