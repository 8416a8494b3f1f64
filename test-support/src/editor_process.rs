//! The editor as the user runs it: a child process (`tvf edit`, or a downstream binary with the
//! same command line) that prints the page's URL with its session token, spoken to over plain
//! HTTP/1.1 with any `Host` header (a client library would not send a foreign one).

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// A running editor: started from a command, read until it printed the page's URL, killed when
/// dropped (the test passed or failed).
pub struct EditorProcess {
    child: Child,
    /// The lines it printed on stdout before the URL.
    pub printed: Vec<String>,
    /// The server's address, `127.0.0.1:PORT`.
    pub address: String,
    /// The session token of the URL.
    pub token: String,
}

impl EditorProcess {
    /// Spawns `command` (the editor's full command line; stdout piped, stderr discarded) and
    /// reads its stdout up to the line with the page's URL. Panics, with what it printed, if
    /// the process ends without one.
    pub fn start(mut command: Command) -> Self {
        let mut child = command
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("the editor starts");
        let stdout = child.stdout.take().expect("stdout is piped");
        let mut printed = Vec::new();
        let url = BufReader::new(stdout)
            .lines()
            .map_while(Result::ok)
            .find_map(|line| {
                let url = line
                    .split_whitespace()
                    .find(|w| w.starts_with("http://"))
                    .map(str::to_string);
                if url.is_none() {
                    printed.push(line);
                }
                url
            });
        // Kill the child if the URL is missing: `Self` is not built yet to do it on drop.
        let Some(url) = url else {
            let _ = child.kill();
            let _ = child.wait();
            panic!("no URL on stdout (printed: {printed:?})");
        };
        let rest = url.strip_prefix("http://").expect("an http:// URL");
        let (address, target) = rest.split_at(rest.find('/').expect("a path in the URL"));
        let token = target
            .strip_prefix("/?token=")
            .unwrap_or_else(|| panic!("no token in {url}"));
        Self {
            token: token.to_string(),
            address: address.to_string(),
            printed,
            child,
        }
    }

    /// The page's path with the token, as in the printed URL: `/?token=…`.
    pub fn page(&self) -> String {
        format!("/?token={}", self.token)
    }
}

impl Drop for EditorProcess {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Writes `head` (and `body`) on a new connection to `address`, waits at most `timeout` for
/// each read, reads the whole answer and returns its status code and body.
fn exchange(address: &str, head: &str, body: &str, timeout: Duration) -> (u16, Vec<u8>) {
    let mut stream = TcpStream::connect(address).expect("connect");
    stream.set_read_timeout(Some(timeout)).unwrap();
    write!(stream, "{head}\r\n{body}").unwrap();
    let mut answer = Vec::new();
    stream.read_to_end(&mut answer).unwrap();
    let split = answer
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .unwrap_or(answer.len());
    let status_line = String::from_utf8_lossy(&answer[..split]).to_string();
    let status = status_line
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no status in {status_line:?}"));
    (status, answer.get(split + 4..).unwrap_or_default().to_vec())
}

/// `method target` with `body` (JSON), the server's own `Host` and the session token → the
/// status code and the body of the answer (waiting up to two minutes: an edit may solve).
pub fn request(
    address: &str,
    method: &str,
    target: &str,
    token: &str,
    body: &str,
) -> (u16, Vec<u8>) {
    let head = format!(
        "{method} {target} HTTP/1.1\r\nHost: {address}\r\nX-TVF-Token: {token}\r\n\
         Content-Type: application/json\r\nContent-Length: {}\r\n",
        body.len()
    );
    exchange(address, &head, body, Duration::from_secs(120))
}

/// `GET target` with the header `Host: host` (any, to test the server's checks) and the token
/// header if given → the status code.
pub fn status(address: &str, host: &str, target: &str, token: Option<&str>) -> u16 {
    let token = token.map_or(String::new(), |t| format!("X-TVF-Token: {t}\r\n"));
    let head = format!("GET {target} HTTP/1.1\r\nHost: {host}\r\n{token}");
    exchange(address, &head, "", Duration::from_secs(20)).0
}
