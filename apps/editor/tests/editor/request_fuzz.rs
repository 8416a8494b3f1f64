//! Random-input smoke fuzzing of the editor server's request parsing (the HTTP head parser and
//! the edit JSON), the stable-toolchain counterpart of the `editor_request` target in
//! `core/fuzz`: mutated requests never panic and every refusal is a 4xx.
//!
//! Inputs: 5000 by default; set `TVF_FUZZ_CASES` for a longer run.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_editor::http::parse_head;
use tvf_editor::EditOp;

const HEADS: [&str; 3] = [
    "POST /api/edit HTTP/1.1\r\nHost: 127.0.0.1:8080\r\nOrigin: http://127.0.0.1:8080\r\nX-TVF-Token: 00112233445566778899aabbccddeeff\r\nContent-Type: application/json\r\nContent-Length: 42",
    "GET /api/fur?strands=100&length=0.5&token=abc HTTP/1.1\r\nHost: localhost:1",
    "GET / HTTP/1.0",
];

const EDITS: [&str; 5] = [
    r#"{"op": "add", "constraint": {"id": "a", "kind": "vector", "face": 2, "value": [1.0, 0.0, 0.0]}}"#,
    r#"{"op": "basis_size", "value": 40}"#,
    r#"{"op": "load", "set": {"omega": 0.2, "constraints": [{"id": "d", "kind": "divergence", "vertex": 1, "value": 1}]}}"#,
    r#"{"op": "clear"}"#,
    r#"{"op": "omega", "value": 0.1}"#,
];

fn mutate(seed: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for _ in 0..rng.random_range(1..5) {
        let at = rng.random_range(0..=bytes.len());
        match rng.random_range(0..5) {
            0 if at < bytes.len() => bytes[at] = rng.random(),
            1 => bytes.splice(at..at, *b"\r\n").for_each(drop),
            2 => bytes.truncate(at),
            3 => {
                let token: &[u8] = [
                    &b" "[..],
                    b":",
                    b"-1",
                    b"99999999999999999999",
                    b"\xff",
                    b"\"x\": 1,",
                ][rng.random_range(0..6)];
                bytes.splice(at..at, token.iter().copied()).for_each(drop);
            }
            _ => {
                let end = (at + rng.random_range(1..12)).min(bytes.len());
                bytes.drain(at..end);
            }
        }
    }
    bytes
}

#[test]
fn request_parsers_survive_mutated_requests() {
    let cases: usize = std::env::var("TVF_FUZZ_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(5000);
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let (mut heads, mut edits) = (0, 0);
    for _ in 0..cases {
        let head = mutate(HEADS[rng.random_range(0..HEADS.len())].as_bytes(), &mut rng);
        match parse_head(&head) {
            Ok(h) => {
                heads += 1;
                let _ = (h.content_length(), h.path(), h.query(), h.header("host"));
            }
            Err(e) => assert!((400..500).contains(&e.status_code()), "{e}"),
        }
        let edit = mutate(EDITS[rng.random_range(0..EDITS.len())].as_bytes(), &mut rng);
        match EditOp::parse(&edit) {
            Ok(_) => edits += 1,
            Err(e) => assert!((400..500).contains(&e.status_code()), "{e}"),
        }
    }
    println!("editor requests: {cases} heads ({heads} parsed), {cases} edits ({edits} parsed)");
}
