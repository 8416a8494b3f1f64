//! The editor server's HTTP/1.1 wire format: one request per connection, its head parsed with
//! caps on every size ([`parse_head`]), its body read against a deadline ([`read_body`]), and
//! the answer written with `Connection: close` ([`write_response`]).
//!
//! Only what the page needs is accepted: a request line `METHOD /target HTTP/1.x`, at most
//! [`MAX_HEADERS`] headers in at most [`MAX_HEAD_BYTES`] bytes, and a body announced by
//! `Content-Length` (chunked bodies are refused). A client that sends its head or body too slowly
//! gets 408 when its deadline passes, so a stalled upload holds its connection for a bounded time.
//! The threat model these caps serve, and why tvf has a server of its own, are in [`crate::server`].

use std::io::{Read, Write};
use std::net::{Shutdown, TcpStream};
use std::time::{Duration, Instant};

use crate::error::EditorError;

/// Largest accepted request head (request line and headers), bytes.
pub const MAX_HEAD_BYTES: usize = 16 << 10;
/// Most headers a request may have.
pub const MAX_HEADERS: usize = 64;

/// The request line and headers of one request.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RequestHead {
    /// The method, e.g. `GET`.
    pub method: String,
    /// The request target as sent: a path and an optional `?query`.
    pub target: String,
    /// Header names (lower case) and values (trimmed), in the order received.
    pub headers: Vec<(String, String)>,
}

impl RequestHead {
    /// The value of header `name` (lower case), if present once; several different values of
    /// one header are a bad request.
    pub fn header(&self, name: &str) -> Result<Option<&str>, EditorError> {
        let mut values = self
            .headers
            .iter()
            .filter(|(n, _)| n == name)
            .map(|(_, v)| v.as_str());
        let first = values.next();
        if let Some(other) = values.find(|v| Some(*v) != first) {
            return Err(bad(format!(
                "header {name} is given twice with different values ('{}' and '{other}')",
                first.unwrap_or_default()
            )));
        }
        Ok(first)
    }

    /// The path of the target (before `?`).
    pub fn path(&self) -> &str {
        self.target.split_once('?').map_or(&self.target, |(p, _)| p)
    }

    /// The query of the target (after `?`, empty if none).
    pub fn query(&self) -> &str {
        self.target.split_once('?').map_or("", |(_, q)| q)
    }

    /// The body length announced by `Content-Length` (0 without one); a chunked body is refused.
    pub fn content_length(&self) -> Result<usize, EditorError> {
        if self.header("transfer-encoding")?.is_some() {
            return Err(EditorError::BadRequest {
                reason: "chunked request bodies are not accepted: send Content-Length".into(),
            });
        }
        match self.header("content-length")? {
            None => Ok(0),
            Some(text) if !text.is_empty() && text.bytes().all(|b| b.is_ascii_digit()) => text
                .parse()
                .map_err(|_| bad(format!("Content-Length {text} is too large"))),
            Some(text) => Err(bad(format!("Content-Length '{text}' is not a number"))),
        }
    }
}

fn bad(reason: String) -> EditorError {
    EditorError::BadRequest { reason }
}

/// Parses a request head: the bytes before the blank line that ends it (`\r\n\r\n` excluded).
pub fn parse_head(bytes: &[u8]) -> Result<RequestHead, EditorError> {
    if bytes.len() > MAX_HEAD_BYTES {
        return Err(EditorError::RequestTooLarge {
            what: "request head bytes",
            count: bytes.len(),
            limit: MAX_HEAD_BYTES,
        });
    }
    let text =
        std::str::from_utf8(bytes).map_err(|_| bad("the request head is not UTF-8".into()))?;
    let mut lines = text.split("\r\n");
    let request_line = lines.next().unwrap_or_default();
    let mut parts = request_line.split(' ');
    let (Some(method), Some(target), Some(version), None) =
        (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        return Err(bad(format!("malformed request line '{request_line}'")));
    };
    if method.is_empty() || !method.bytes().all(is_token_byte) {
        return Err(bad(format!("malformed method '{method}'")));
    }
    if !target.starts_with('/') || !target.bytes().all(|b| b.is_ascii_graphic()) {
        return Err(bad(format!("malformed request target '{target}'")));
    }
    if version != "HTTP/1.1" && version != "HTTP/1.0" {
        return Err(bad(format!("unsupported protocol '{version}'")));
    }
    let mut headers = Vec::new();
    for line in lines {
        let Some((name, value)) = line.split_once(':') else {
            return Err(bad(format!("malformed header line '{line}'")));
        };
        if name.is_empty() || !name.bytes().all(is_token_byte) {
            return Err(bad(format!("malformed header name '{name}'")));
        }
        // RFC 9110: a field value holds no control characters but the tab (a NUL is refused).
        if value.chars().any(|c| c.is_control() && c != '\t') {
            return Err(bad(format!("header {name} holds a control character")));
        }
        if headers.len() == MAX_HEADERS {
            return Err(EditorError::RequestTooLarge {
                what: "request headers",
                count: MAX_HEADERS + 1,
                limit: MAX_HEADERS,
            });
        }
        headers.push((name.to_ascii_lowercase(), value.trim().to_string()));
    }
    Ok(RequestHead {
        method: method.to_string(),
        target: target.to_string(),
        headers,
    })
}

/// Whether `b` may appear in a method or header name (RFC 9110 `tchar`).
fn is_token_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b"!#$%&'*+-.^_`|~".contains(&b)
}

/// Reads from `stream` until the blank line that ends the head, before `deadline`. Returns the
/// parsed head and the bytes already read past it (the start of the body).
pub fn read_head(
    stream: &mut TcpStream,
    deadline: Instant,
) -> Result<(RequestHead, Vec<u8>), EditorError> {
    let mut buffer = Vec::with_capacity(1024);
    let mut chunk = [0u8; 4096];
    loop {
        if let Some(end) = find_blank_line(&buffer) {
            let head = parse_head(&buffer[..end])?;
            return Ok((head, buffer[end + 4..].to_vec()));
        }
        if buffer.len() > MAX_HEAD_BYTES {
            return Err(EditorError::RequestTooLarge {
                what: "request head bytes",
                count: buffer.len(),
                limit: MAX_HEAD_BYTES,
            });
        }
        let n = read_before(stream, &mut chunk, deadline, "the request head")?;
        if n == 0 {
            return Err(bad(
                "the connection closed before the request head ended".into()
            ));
        }
        buffer.extend_from_slice(&chunk[..n]);
    }
}

fn find_blank_line(bytes: &[u8]) -> Option<usize> {
    bytes.windows(4).position(|w| w == b"\r\n\r\n")
}

/// Reads a body of `length` bytes (of which `start` arrived with the head) before `deadline`.
pub fn read_body(
    stream: &mut TcpStream,
    mut start: Vec<u8>,
    length: usize,
    deadline: Instant,
) -> Result<Vec<u8>, EditorError> {
    start.truncate(length);
    let mut body = start;
    body.reserve(length - body.len());
    let mut chunk = [0u8; 16 << 10];
    while body.len() < length {
        let want = chunk.len().min(length - body.len());
        let n = read_before(stream, &mut chunk[..want], deadline, "the request body")?;
        if n == 0 {
            return Err(bad(format!(
                "the connection closed after {} of {length} body bytes",
                body.len()
            )));
        }
        body.extend_from_slice(&chunk[..n]);
    }
    Ok(body)
}

/// One `read` that gives up at `deadline` with [`EditorError::Timeout`].
fn read_before(
    stream: &mut TcpStream,
    buffer: &mut [u8],
    deadline: Instant,
    what: &'static str,
) -> Result<usize, EditorError> {
    let timeout = || EditorError::Timeout { what };
    loop {
        let left = deadline
            .checked_duration_since(Instant::now())
            .filter(|d| !d.is_zero())
            .ok_or_else(timeout)?;
        stream
            .set_read_timeout(Some(left))
            .map_err(|source| EditorError::Io {
                what: "setting a read timeout".into(),
                source,
            })?;
        match stream.read(buffer) {
            Ok(n) => return Ok(n),
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
                ) =>
            {
                return Err(timeout())
            }
            Err(e) => {
                return Err(bad(format!("reading {what}: {e}")));
            }
        }
    }
}

/// The reason phrase of a status code the server uses.
fn reason(status: u16) -> &'static str {
    match status {
        200 => "OK",
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        408 => "Request Timeout",
        409 => "Conflict",
        411 => "Length Required",
        413 => "Content Too Large",
        422 => "Unprocessable Content",
        503 => "Service Unavailable",
        _ => "Internal Server Error",
    }
}

/// Writes a response with `Content-Length` and `Connection: close`, then closes the connection
/// gracefully: the sending side first, then whatever the client still sends is read and dropped
/// for a moment, so the answer is not lost to a reset when a body was left unread.
pub fn write_response(
    stream: &mut TcpStream,
    status: u16,
    headers: &[(&str, &str)],
    body: &[u8],
) -> std::io::Result<()> {
    stream.set_write_timeout(Some(Duration::from_secs(10)))?;
    let mut head = format!("HTTP/1.1 {status} {}\r\n", reason(status));
    for (name, value) in headers {
        head.push_str(&format!("{name}: {value}\r\n"));
    }
    head.push_str(&format!(
        "Content-Length: {}\r\nConnection: close\r\n\r\n",
        body.len()
    ));
    stream.write_all(head.as_bytes())?;
    stream.write_all(body)?;
    stream.flush()?;
    stream.shutdown(Shutdown::Write)?;
    let deadline = Instant::now() + Duration::from_millis(200);
    let mut sink = [0u8; 16 << 10];
    let mut drained = 0usize;
    while drained < (1 << 20) {
        match read_before(stream, &mut sink, deadline, "the rest of the request") {
            Ok(0) | Err(_) => break,
            Ok(n) => drained += n,
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_head_is_parsed_with_lower_case_names() {
        let head = parse_head(
            b"POST /api/edit?x=1 HTTP/1.1\r\nHost: 127.0.0.1:80\r\nContent-Length:  12 ",
        )
        .unwrap();
        assert_eq!(head.method, "POST");
        assert_eq!((head.path(), head.query()), ("/api/edit", "x=1"));
        assert_eq!(head.header("host").unwrap(), Some("127.0.0.1:80"));
        assert_eq!(head.content_length().unwrap(), 12);
    }

    #[test]
    fn malformed_heads_are_bad_requests() {
        for bad in [
            &b""[..],
            b"GET",
            b"GET / HTTP/2",
            b"GET  / HTTP/1.1",
            b"GET relative HTTP/1.1",
            b"G\xffT / HTTP/1.1",
            b"GET / HTTP/1.1\r\nno colon",
            b"GET / HTTP/1.1\r\n: empty name",
            b"GET / HTTP/1.1\r\n folded: x",
            b"GET / HTTP/1.1\r\nx-a: a\0b",
        ] {
            assert!(
                parse_head(bad).is_err(),
                "{:?}",
                String::from_utf8_lossy(bad)
            );
        }
        let many: String = (0..=MAX_HEADERS).map(|k| format!("\r\nx{k}: 1")).collect();
        assert!(parse_head(format!("GET / HTTP/1.1{many}").as_bytes()).is_err());
    }

    #[test]
    fn lengths_must_be_plain_numbers_and_agree() {
        let length = |headers: &str| {
            parse_head(format!("POST / HTTP/1.1{headers}").as_bytes())
                .unwrap()
                .content_length()
        };
        assert_eq!(length("").unwrap(), 0);
        assert!(length("\r\nContent-Length: -1").is_err());
        assert!(length("\r\nContent-Length: 1e3").is_err());
        assert!(length("\r\nContent-Length: 99999999999999999999999").is_err());
        assert!(length("\r\nContent-Length: 3\r\nContent-Length: 4").is_err());
        assert_eq!(
            length("\r\nContent-Length: 3\r\nContent-Length: 3").unwrap(),
            3
        );
        assert!(length("\r\nTransfer-Encoding: chunked").is_err());
    }
}
