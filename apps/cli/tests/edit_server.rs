//! End-to-end: `tvf edit` prints a URL with the session token; the server it started answers
//! the page and the API only with that token and its own Host.

mod common;

use common::tvf;
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
