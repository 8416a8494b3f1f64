//! [`Access`]: who may use the editor server. Only the page opened from the URL `tvf edit`
//! prints, as Jupyter's and VS Code's local servers do:
//!
//! - `Host` must name the loopback address and the port the server listens on
//!   (`127.0.0.1:PORT` or `localhost:PORT`): a foreign name means DNS rebinding;
//! - an `Origin`, when sent, must be that same server (`http://127.0.0.1:PORT` or
//!   `http://localhost:PORT`): any other web page is refused, even for requests a browser sends
//!   without a CORS preflight;
//! - the page (`/`) and every `/api/` call need the session's random token: in the
//!   `X-TVF-Token` header (what the page's scripts send) or a `token=` query parameter (the URL
//!   printed, and download links). The page embeds the token it was opened with.
//!
//! Everything else is answered 403 and changes nothing. The page's static scripts and style
//! sheet need only the `Host` and `Origin` checks (they hold no data).

use crate::error::EditorError;
use crate::http::RequestHead;
use rand::Rng;

/// Name of the header carrying the session token.
pub const TOKEN_HEADER: &str = "x-tvf-token";

/// The access rules of one server: its port and its session token.
#[derive(Debug, Clone)]
pub struct Access {
    port: u16,
    token: String,
}

impl Access {
    /// The rules for a server on `127.0.0.1:port`, with a fresh random token (128 bits from the
    /// operating system's cryptographic generator via `rand`, as 32 hex digits).
    pub fn new(port: u16) -> Self {
        let bytes: [u8; 16] = rand::rng().random();
        let token = bytes.iter().map(|b| format!("{b:02x}")).collect();
        Self { port, token }
    }

    /// The session token.
    pub fn token(&self) -> &str {
        &self.token
    }

    /// Checks `head` against the rules: `Ok` if it may be answered.
    pub fn check(&self, head: &RequestHead) -> Result<(), EditorError> {
        let forbidden = |reason: String| Err(EditorError::Forbidden { reason });
        let host = head.header("host")?.unwrap_or_default();
        if !self.is_own_host(host) {
            return forbidden(format!(
                "Host '{host}' is not this server (127.0.0.1:{})",
                self.port
            ));
        }
        if let Some(origin) = head.header("origin")? {
            let own = origin
                .strip_prefix("http://")
                .is_some_and(|h| self.is_own_host(h));
            if !own {
                return forbidden(format!("requests from origin '{origin}' are not accepted"));
            }
        }
        let path = head.path();
        let needs_token = path == "/" || path == "/index.html" || path.starts_with("/api/");
        if needs_token && !self.has_token(head)? {
            return forbidden(
                "missing or wrong session token: open the URL that `tvf edit` printed".into(),
            );
        }
        Ok(())
    }

    fn is_own_host(&self, host: &str) -> bool {
        let port = self.port.to_string();
        ["127.0.0.1", "localhost"].iter().any(|name| {
            host.strip_prefix(name)
                .and_then(|rest| rest.strip_prefix(':'))
                .is_some_and(|p| p == port)
        })
    }

    fn has_token(&self, head: &RequestHead) -> Result<bool, EditorError> {
        if let Some(given) = head.header(TOKEN_HEADER)? {
            return Ok(constant_time_equal(given, &self.token));
        }
        Ok(head.query().split('&').any(|pair| {
            pair.strip_prefix("token=")
                .is_some_and(|given| constant_time_equal(given, &self.token))
        }))
    }
}

/// Compares two strings in time independent of where they differ.
fn constant_time_equal(a: &str, b: &str) -> bool {
    a.len() == b.len() && a.bytes().zip(b.bytes()).fold(0u8, |d, (x, y)| d | (x ^ y)) == 0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::http::parse_head;

    fn head(target: &str, headers: &str) -> RequestHead {
        parse_head(format!("GET {target} HTTP/1.1{headers}").as_bytes()).unwrap()
    }

    #[test]
    fn only_the_own_host_origin_and_token_pass() {
        let access = Access::new(8123);
        let token = access.token().to_string();
        assert_eq!(token.len(), 32);
        assert_ne!(Access::new(8123).token(), token, "tokens are random");
        let with = format!("\r\nX-TVF-Token: {token}");
        let ok = [
            head("/api/ping", &format!("\r\nHost: 127.0.0.1:8123{with}")),
            head("/api/ping", &format!("\r\nHost: localhost:8123{with}")),
            head(&format!("/?token={token}"), "\r\nHost: 127.0.0.1:8123"),
            head(
                "/api/edit",
                &format!("\r\nHost: 127.0.0.1:8123\r\nOrigin: http://127.0.0.1:8123{with}"),
            ),
            head("/app.js", "\r\nHost: 127.0.0.1:8123"),
        ];
        for h in &ok {
            assert!(access.check(h).is_ok(), "{h:?}");
        }
        let refused = [
            head("/api/ping", &with),
            head("/api/ping", &format!("\r\nHost: evil.example.com{with}")),
            head("/api/ping", &format!("\r\nHost: 127.0.0.1:8124{with}")),
            head("/api/ping", &format!("\r\nHost: 127.0.0.1:81234{with}")),
            head("/app.js", "\r\nHost: evil.example.com:8123"),
            head(
                "/api/ping",
                &format!("\r\nHost: 127.0.0.1:8123\r\nOrigin: http://evil.example.com{with}"),
            ),
            head(
                "/api/ping",
                &format!("\r\nHost: 127.0.0.1:8123\r\nOrigin: null{with}"),
            ),
            head("/api/ping", "\r\nHost: 127.0.0.1:8123"),
            head("/", "\r\nHost: 127.0.0.1:8123"),
            head(
                "/api/ping",
                "\r\nHost: 127.0.0.1:8123\r\nX-TVF-Token: 0123456789abcdef0123456789abcdef",
            ),
        ];
        for h in &refused {
            let error = access.check(h).unwrap_err();
            assert_eq!(error.status_code(), 403, "{h:?}");
        }
    }
}
