//! End-to-end: `tvf edit` prints a URL with the session token; the server it started answers
//! the page and the API only with that token and its own Host. On the raw `bunny.obj` of
//! `../shared/meshes` (where it exists; CI has it): the dropped unreferenced vertices are
//! reported and an edit over HTTP gives a field that meets its constraint.

use crate::common::tvf;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Stdio};
use std::time::Duration;

/// Kills the server when the test ends, passed or failed.
struct Server(Child);

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// `GET target` with `Host: host` (and the token header, if given) → status code.
fn status(address: &str, host: &str, target: &str, token: Option<&str>) -> u16 {
    let mut stream = TcpStream::connect(address).expect("connect");
    stream
        .set_read_timeout(Some(Duration::from_secs(20)))
        .unwrap();
    let token = token.map_or(String::new(), |t| format!("X-TVF-Token: {t}\r\n"));
    write!(
        stream,
        "GET {target} HTTP/1.1\r\nHost: {host}\r\n{token}\r\n"
    )
    .unwrap();
    let mut answer = String::new();
    stream.read_to_string(&mut answer).unwrap();
    answer
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{answer:?}"))
}

/// `method target` with the server's own Host, the token and `body` → (status, body).
fn request(address: &str, method: &str, target: &str, token: &str, body: &str) -> (u16, Vec<u8>) {
    let mut stream = TcpStream::connect(address).expect("connect");
    stream
        .set_read_timeout(Some(Duration::from_secs(120)))
        .unwrap();
    write!(
        stream,
        "{method} {target} HTTP/1.1\r\nHost: {address}\r\nX-TVF-Token: {token}\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut answer = Vec::new();
    stream.read_to_end(&mut answer).unwrap();
    let split = answer
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a header");
    let head = String::from_utf8_lossy(&answer[..split]).to_string();
    let status = head
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{head:?}"));
    (status, answer[split + 4..].to_vec())
}

/// Starts `tvf edit` with `args`; returns the server, the lines it printed before the URL, the
/// address and the token.
fn start_editor(args: &[&str], cache: &std::path::Path) -> (Server, Vec<String>, String, String) {
    let child = tvf()
        .args(["-q", "edit"])
        .args(args)
        .arg("--cache-dir")
        .arg(cache)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("tvf edit starts");
    let mut server = Server(child);
    let stdout = server.0.stdout.take().unwrap();
    let mut before = Vec::new();
    let url = BufReader::new(stdout)
        .lines()
        .map_while(Result::ok)
        .find_map(|line| {
            let url = line
                .split_whitespace()
                .find(|w| w.starts_with("http://"))
                .map(str::to_string);
            if url.is_none() {
                before.push(line);
            }
            url
        })
        .unwrap_or_else(|| panic!("a URL on stdout (printed: {before:?})"));
    let rest = url.strip_prefix("http://").unwrap();
    let (address, target) = rest.split_at(rest.find('/').unwrap());
    let token = target
        .strip_prefix("/?token=")
        .unwrap_or_else(|| panic!("no token in {url}"));
    (server, before, address.to_string(), token.to_string())
}

#[test]
fn the_raw_bunny_is_edited_over_http() {
    // Uses ../shared/meshes/bunny.obj (five boundary loops, unreferenced vertices); runs where it
    // exists.
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/meshes/bunny.obj");
    if !path.exists() {
        eprintln!("skipping: {} is not present", path.display());
        return;
    }
    let loaded = tvf_core::io::load_mesh(&path).unwrap();
    let dropped = loaded
        .report
        .warnings
        .iter()
        .find_map(|w| match w {
            tvf_core::ValidationWarning::UnreferencedVertices { count, .. } => Some(*count),
            _ => None,
        })
        .expect("the raw bunny has unreferenced vertices");
    let cache = tempfile::tempdir().unwrap();
    let (server, printed, address, token) =
        start_editor(&[path.to_str().unwrap(), "-k", "20"], cache.path());
    let printed = printed.join("\n");
    assert!(
        printed.contains(&format!("{dropped} unreferenced vertices dropped")),
        "{printed}"
    );
    assert!(
        printed.contains("conforming-barycentric+tangential"),
        "{printed}"
    );
    let (code, frame) = request(
        &address,
        "POST",
        "/api/edit",
        &token,
        r#"{"op": "add", "constraint": {"id": "v", "kind": "vector", "face": 100, "value": [0.3, 1.0, -0.2]}}"#,
    );
    assert_eq!(code, 200, "{}", String::from_utf8_lossy(&frame));
    assert!(!frame.is_empty(), "the edit answers with the new field");
    let (code, check) = request(&address, "GET", "/api/check", &token, "");
    assert_eq!(code, 200);
    let check: serde_json::Value = serde_json::from_slice(&check).expect("JSON check");
    assert_eq!(check["constraints"].as_array().unwrap().len(), 1, "{check}");
    assert!(
        check["max_relative"].as_f64().unwrap() < 1e-9,
        "the field misses the constraint: {check}"
    );
    // A constraint the mesh cannot hold is refused with a message naming it.
    let (code, answer) = request(
        &address,
        "POST",
        "/api/edit",
        &token,
        &format!(
            r#"{{"op": "add", "constraint": {{"id": "far", "kind": "vector", "face": {}, "value": [1.0, 0.0, 0.0]}}}}"#,
            loaded.mesh.face_count()
        ),
    );
    assert!(code >= 400, "an out-of-range face is refused");
    assert!(
        String::from_utf8_lossy(&answer).contains("far"),
        "{}",
        String::from_utf8_lossy(&answer)
    );
    drop(server);
}

#[test]
fn the_printed_url_carries_the_token_the_server_requires() {
    let cache = tempfile::tempdir().unwrap();
    let child = tvf()
        .args([
            "-q",
            "edit",
            "--example",
            "icosphere",
            "-k",
            "20",
            "--cache-dir",
        ])
        .arg(cache.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("tvf edit starts");
    let mut server = Server(child);
    let stdout = server.0.stdout.take().unwrap();
    let url = BufReader::new(stdout)
        .lines()
        .map_while(Result::ok)
        .find_map(|line| {
            line.split_whitespace()
                .find(|w| w.starts_with("http://"))
                .map(str::to_string)
        })
        .expect("a URL on stdout");
    let rest = url.strip_prefix("http://").unwrap();
    let (address, target) = rest.split_at(rest.find('/').unwrap());
    let token = target
        .strip_prefix("/?token=")
        .unwrap_or_else(|| panic!("no token in {url}"));
    assert!(token.len() >= 32, "{token}");
    assert_eq!(status(address, address, target, None), 200);
    assert_eq!(status(address, address, "/", None), 403);
    assert_eq!(status(address, address, "/api/ping", Some(token)), 200);
    assert_eq!(status(address, address, "/api/ping", None), 403);
    assert_eq!(
        status(address, "evil.example.com", "/api/ping", Some(token)),
        403
    );
    drop(server);
}
