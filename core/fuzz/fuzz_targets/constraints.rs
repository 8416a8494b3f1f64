//! Fuzzes the constraint-file reader: any bytes must give a constraint set or a typed error
//! naming the file, never a panic; a set that parses writes JSON that parses to the same set.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use tvf_design::ConstraintSet;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    match ConstraintSet::parse(&text, Path::new("fuzz.json")) {
        Ok(set) => {
            let again = ConstraintSet::parse(&set.to_json(), Path::new("again.json"));
            assert_eq!(again.ok().as_ref(), Some(&set));
        }
        Err(error) => assert!(error.to_string().starts_with("fuzz.json")),
    }
});
