//! Fuzzes the editor server's request parsing: the HTTP head parser and the edit JSON parser.
//! Any bytes must give a request or a typed 4xx error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tvf_editor::http::parse_head;
use tvf_editor::EditOp;

fuzz_target!(|data: &[u8]| {
    match parse_head(data) {
        Ok(head) => {
            let _ = head.content_length();
            let _ = (head.path(), head.query(), head.header("host"));
        }
        Err(error) => assert!((400..500).contains(&error.status_code())),
    }
    if let Err(error) = EditOp::parse(data) {
        assert!((400..500).contains(&error.status_code()));
    }
});
