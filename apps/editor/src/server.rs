//! [`EditorServer`]: the HTTP server on 127.0.0.1 that serves the page and the editing API.
//!
//! | method, path | answer |
//! |---|---|
//! | `GET /?token=…` and the page's files | the embedded page ([`crate::assets`]) |
//! | `GET /api/mesh` | the mesh payload ([`crate::payload`]) |
//! | `GET /api/field` | the current field frame |
//! | `POST /api/edit` | applies an [`EditOp`] (JSON body), answers with the new field frame |
//! | `GET /api/constraints` | the constraints and ω as a constraint file (download) |
//! | `GET /api/check` | [`crate::CheckReport`] as JSON: the held field against the constraints |
//! | `GET /api/fur?strands=N&length=L` | fur strands along the field (binary, for display) |
//! | `GET /api/fur.obj?strands=N&length=L` | the same strands as OBJ polylines (download) |
//! | `GET /api/ping` | `ok` |
//!
//! The page and every `/api/` call need the session token, and every request the server's own
//! `Host` (and `Origin`, if any): see [`crate::access`]; otherwise 403.
//!
//! Errors are answered with a 4xx/5xx status and a JSON body `{"error": "...", "ids": [...]}`.
//!
//! # Threat model
//!
//! The server is for the one user at this machine who ran `tvf edit`: it listens on 127.0.0.1
//! only, and everything else that can reach that address is assumed hostile, namely other
//! web pages in the user's browser and other local programs or users.
//!
//! - **Other web pages** can make the browser send requests to `127.0.0.1:PORT`. A page of
//!   another origin is refused by its `Origin`, and a DNS-rebinding page (its name resolving to
//!   127.0.0.1) by its `Host`; neither can read the page to learn the session token
//!   ([`crate::access`]).
//! - **Other local clients** need the session token (128 random bits, printed only to the
//!   user's terminal) for the page and every API call; without it they get 403 and change
//!   nothing.
//! - **Exhaustion** by any client, token or not: every size is capped (request head
//!   [`crate::http::MAX_HEAD_BYTES`] and [`crate::http::MAX_HEADERS`], body [`MAX_BODY_BYTES`],
//!   fur [`MAX_STRANDS`] and [`MAX_FUR_LENGTH`]); a slow client (slowloris: a head or body sent
//!   a byte at a time) is cut off at [`HEAD_DEADLINE`] or [`BODY_DEADLINE`] with 408, not at
//!   an idle timeout it can keep resetting ([`crate::http`]); connections that send nothing
//!   wait in a room of [`MAX_WAITING_CONNECTIONS`] seats in which a new one evicts the oldest
//!   ([`crate::waiting_room`]), so they cannot keep the page's requests out; answered requests
//!   are capped at [`MAX_CONNECTIONS`], uploads may not take the last [`RESERVED_CONNECTIONS`],
//!   and threads at [`MAX_THREADS`] (503 beyond). `tests/editor/security.rs` drives each of
//!   these over loopback (foreign `Host`/`Origin`, no token, stalled uploads, idle connections,
//!   a stress run with stalled uploads).
//!
//! Not in the model: TLS (the traffic never leaves the machine), and a local attacker who can
//! read the user's terminal or memory.
//!
//! # Why a server of its own
//!
//! It replaced `tiny_http` (0.12), which has neither a deadline for a request's head nor a
//! cap on connections: it reads every head on a thread of its own for as long as the client
//! takes, so idle or slow connections pile up threads without bound, and its request's body
//! reader has no deadline either (a stalled upload held its thread, and with enough of them
//! `/api/ping` went unanswered). `rouille` serves through `tiny_http`. `hyper` has a head
//! timeout but runs on an async runtime (`tokio`) that nothing else in tvf needs, for a server
//! that answers one user's page. What this one needs (one request per connection,
//! `Content-Length` bodies, `Connection: close`) is the small part of HTTP/1.1 in
//! [`crate::http`].

use std::net::{Shutdown, SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use tvf_render::{grow_fur, write_obj, FurOptions};

use crate::access::Access;
use crate::assets::{asset, page};
use crate::edit_op::EditOp;
use crate::editor::Editor;
use crate::error::EditorError;
use crate::http::{read_body, read_head, write_response, RequestHead};
use crate::payload::{encode_fur, encode_mesh};
use crate::waiting_room::WaitingRoom;

/// Largest accepted request body (a constraint set being loaded), bytes.
pub const MAX_BODY_BYTES: u64 = 8 << 20;
/// Most fur strands one request may ask for.
pub const MAX_STRANDS: usize = 200_000;
/// Longest fur strands one request may ask for (`length`, in bounding-box diagonals as in
/// [`FurOptions::length`]).
pub const MAX_FUR_LENGTH: f64 = 10.0;
/// Most connections waiting for their request head at once (one thread each): when one more
/// arrives, the one waiting longest is closed ([`WaitingRoom`]), so idle connections cannot
/// keep the page's requests out.
pub const MAX_WAITING_CONNECTIONS: usize = 64;
/// Most requests that passed the access checks ([`crate::access`]) answered at once (one
/// thread each); more are answered 503 at once.
pub const MAX_CONNECTIONS: usize = 64;
/// Most connection threads at all (waiting, answering, and closing evicted ones); a
/// connection beyond them is answered 503 at once.
pub const MAX_THREADS: usize = 4 * (MAX_WAITING_CONNECTIONS + MAX_CONNECTIONS);
/// Connections kept free for requests without a body (the page's reads and `/api/ping`): at
/// most `MAX_CONNECTIONS - RESERVED_CONNECTIONS` may be receiving a body at once.
pub const RESERVED_CONNECTIONS: usize = 8;
/// Time a client has to send its request head.
pub const HEAD_DEADLINE: Duration = Duration::from_secs(10);
/// Time a client has to send its request body (after the head).
pub const BODY_DEADLINE: Duration = Duration::from_secs(10);

/// How long a client may take to send its request: the head from when the connection is
/// taken up, the body from the end of the head; past either, the request is answered 408 and
/// the connection closed. `tvf edit` uses the default ([`HEAD_DEADLINE`], [`BODY_DEADLINE`]);
/// [`EditorServer::start_with_deadlines`] takes others (the tests wait out a shorter one).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ServerDeadlines {
    /// Time to send the request head.
    pub head: Duration,
    /// Time to send the request body, after the head.
    pub body: Duration,
}

impl Default for ServerDeadlines {
    fn default() -> Self {
        Self {
            head: HEAD_DEADLINE,
            body: BODY_DEADLINE,
        }
    }
}

/// A running editor server; stops with [`EditorServer::shutdown`] (or runs until the process
/// ends with [`EditorServer::join`]).
///
/// One thread accepts connections and starts one thread per connection; each answers one
/// request and closes. Heads and bodies are read against deadlines ([`ServerDeadlines`]);
/// connections still sending their head are at most
/// [`MAX_WAITING_CONNECTIONS`] (the longest waiting is closed for a new one), requests that
/// passed the [`crate::access`] checks at most [`MAX_CONNECTIONS`], and uploads may not take the
/// last [`RESERVED_CONNECTIONS`] of those: neither idle connections nor stalled uploads can keep
/// the page from being answered.
pub struct EditorServer {
    acceptor: JoinHandle<()>,
    stop: Arc<AtomicBool>,
    address: SocketAddr,
    token: String,
}

struct Shared {
    editor: Editor,
    mesh_payload: Vec<u8>,
    access: Access,
    deadlines: ServerDeadlines,
    waiting: WaitingRoom,
    threads: AtomicUsize,
    connections: AtomicUsize,
    uploads: AtomicUsize,
}

impl EditorServer {
    /// Listens on `127.0.0.1:port` (`port` 0: chosen by the OS) and starts answering, with the
    /// default [`ServerDeadlines`].
    pub fn start(editor: Editor, port: u16) -> Result<Self, EditorError> {
        Self::start_with_deadlines(editor, port, ServerDeadlines::default())
    }

    /// [`EditorServer::start`] with the request deadlines `deadlines`.
    pub fn start_with_deadlines(
        editor: Editor,
        port: u16,
        deadlines: ServerDeadlines,
    ) -> Result<Self, EditorError> {
        let listener =
            TcpListener::bind(("127.0.0.1", port)).map_err(|source| EditorError::Io {
                what: format!("listening on 127.0.0.1:{port}"),
                source,
            })?;
        let address = listener.local_addr().map_err(|source| EditorError::Io {
            what: "reading the server's address".into(),
            source,
        })?;
        let shared = Arc::new(Shared {
            mesh_payload: encode_mesh(editor.mesh())?,
            editor,
            access: Access::new(address.port()),
            deadlines,
            waiting: WaitingRoom::new(MAX_WAITING_CONNECTIONS),
            threads: AtomicUsize::new(0),
            connections: AtomicUsize::new(0),
            uploads: AtomicUsize::new(0),
        });
        let token = shared.access.token().to_string();
        let stop = Arc::new(AtomicBool::new(false));
        let acceptor = {
            let stop = Arc::clone(&stop);
            std::thread::Builder::new()
                .name("tvf-editor-accept".into())
                .spawn(move || accept(&listener, &shared, &stop))
                .map_err(|source| EditorError::Io {
                    what: "starting the HTTP accept thread".into(),
                    source,
                })?
        };
        Ok(Self {
            acceptor,
            stop,
            address,
            token,
        })
    }

    /// The address the server listens on.
    pub fn address(&self) -> SocketAddr {
        self.address
    }

    /// The session token every API call must carry (see [`crate::access`]).
    pub fn token(&self) -> &str {
        &self.token
    }

    /// The page's URL with the session token, `http://127.0.0.1:PORT/?token=…`.
    pub fn url(&self) -> String {
        format!("http://{}/?token={}", self.address, self.token)
    }

    /// Blocks until the server stops (which it does not on its own).
    pub fn join(self) {
        let _ = self.acceptor.join();
    }

    /// Stops accepting connections (requests being answered finish on their own threads).
    pub fn shutdown(self) {
        self.stop.store(true, Ordering::SeqCst);
        // Wake the accept loop with a connection of our own.
        let _ = TcpStream::connect(self.address);
        let _ = self.acceptor.join();
    }
}

/// Accepts connections until `stop`, one thread each, at most [`MAX_THREADS`] at once.
fn accept(listener: &TcpListener, shared: &Arc<Shared>, stop: &AtomicBool) {
    for stream in listener.incoming() {
        if stop.load(Ordering::SeqCst) {
            return;
        }
        let Ok(mut stream) = stream else { continue };
        if shared.threads.fetch_add(1, Ordering::SeqCst) >= MAX_THREADS {
            shared.threads.fetch_sub(1, Ordering::SeqCst);
            respond(
                &mut stream,
                Err(EditorError::Busy {
                    what: "too many connections",
                }),
            );
            continue;
        }
        let shared_for_thread = Arc::clone(shared);
        let spawned = std::thread::Builder::new()
            .name("tvf-editor-http".into())
            .spawn(move || {
                let shared = shared_for_thread;
                // A panic while answering drops the connection, never the server.
                let _ = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    serve_connection(&shared, stream)
                }));
                shared.threads.fetch_sub(1, Ordering::SeqCst);
            });
        if spawned.is_err() {
            shared.threads.fetch_sub(1, Ordering::SeqCst);
        }
    }
}

/// Reads one request from `stream` (waiting for its head in the [`WaitingRoom`]), answers it
/// if it passes the access checks and a slot is free, and closes the connection.
fn serve_connection(shared: &Shared, mut stream: TcpStream) {
    let _ = stream.set_nodelay(true);
    let ticket = shared.waiting.enter(&stream);
    let head = read_head(&mut stream, Instant::now() + shared.deadlines.head);
    drop(ticket);
    let answer = head.and_then(|(head, rest)| {
        shared.access.check(&head)?;
        let _slot = take_slot(&shared.connections, MAX_CONNECTIONS, "too many connections")?;
        answer(shared, &head, rest, &mut stream)
    });
    respond(&mut stream, answer);
}

/// One of `limit` slots counted by `taken`, or [`EditorError::Busy`] with `what`.
fn take_slot<'a>(
    taken: &'a AtomicUsize,
    limit: usize,
    what: &'static str,
) -> Result<Slot<'a>, EditorError> {
    if taken.fetch_add(1, Ordering::SeqCst) >= limit {
        taken.fetch_sub(1, Ordering::SeqCst);
        return Err(EditorError::Busy { what });
    }
    Ok(Slot(taken))
}

/// A slot of a limited kind (a connection, an upload); released when dropped.
struct Slot<'a>(&'a AtomicUsize);

impl Drop for Slot<'_> {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

/// The body of a request, read before its deadline; 0 bytes without `Content-Length`.
fn body(
    shared: &Shared,
    head: &RequestHead,
    rest: Vec<u8>,
    stream: &mut TcpStream,
) -> Result<Vec<u8>, EditorError> {
    let length = head.content_length()?;
    if length as u64 > MAX_BODY_BYTES {
        return Err(EditorError::RequestTooLarge {
            what: "request body bytes",
            count: length,
            limit: MAX_BODY_BYTES as usize,
        });
    }
    if length == 0 {
        return Ok(Vec::new());
    }
    let limit = MAX_CONNECTIONS - RESERVED_CONNECTIONS;
    let _slot = take_slot(&shared.uploads, limit, "too many uploads at once")?;
    read_body(stream, rest, length, Instant::now() + shared.deadlines.body)
}

fn respond(stream: &mut TcpStream, answer: Answer) {
    let (status, body, content_type, attachment) = match answer {
        Ok((body, content_type, attachment)) => (200, body, content_type, attachment),
        Err(error) => {
            let body =
                serde_json::json!({ "error": error.to_string(), "ids": error.involved_ids() });
            (
                error.status_code(),
                body.to_string().into_bytes(),
                "application/json",
                None,
            )
        }
    };
    let disposition = attachment.map(|name| format!("attachment; filename=\"{name}\""));
    let mut headers = vec![
        ("Content-Type", content_type),
        ("Cache-Control", "no-store"),
        ("X-Content-Type-Options", "nosniff"),
    ];
    if let Some(d) = &disposition {
        headers.push(("Content-Disposition", d));
    }
    // The client may have gone away; nothing to do about it.
    if write_response(stream, status, &headers, &body).is_err() {
        let _ = stream.shutdown(Shutdown::Both);
    }
}

type Answer = Result<(Vec<u8>, &'static str, Option<&'static str>), EditorError>;

/// The answer to a request that passed the access checks.
fn answer(shared: &Shared, head: &RequestHead, rest: Vec<u8>, stream: &mut TcpStream) -> Answer {
    let (method, path, query) = (head.method.as_str(), head.path(), head.query());
    let not_allowed = || EditorError::MethodNotAllowed {
        method: method.to_string(),
        path: path.to_string(),
    };
    const BINARY: &str = "application/octet-stream";
    const JSON: &str = "application/json";
    match path {
        "/api/edit" => {
            if method != "POST" {
                return Err(not_allowed());
            }
            let body = body(shared, head, rest, stream)?;
            let op = EditOp::parse(&body)?;
            Ok((shared.editor.edit(op)?, BINARY, None))
        }
        _ if method != "GET" => Err(not_allowed()),
        "/api/mesh" => Ok((shared.mesh_payload.clone(), BINARY, None)),
        "/api/field" => Ok((shared.editor.field_frame()?, BINARY, None)),
        "/api/ping" => Ok((b"ok".to_vec(), "text/plain", None)),
        "/api/constraints" => Ok((
            shared.editor.constraint_set_json()?.into_bytes(),
            JSON,
            Some("constraints.json"),
        )),
        "/api/check" => {
            let report = shared.editor.check()?;
            let text = serde_json::to_string(&report).map_err(|e| EditorError::BadRequest {
                reason: e.to_string(),
            })?;
            Ok((text.into_bytes(), JSON, None))
        }
        "/api/fur" => Ok((encode_fur(&fur(shared, query, 6000)?)?, BINARY, None)),
        "/api/fur.obj" => Ok((fur_obj(shared, query)?, "text/plain", Some("fur.obj"))),
        "/" | "/index.html" => Ok((
            page(shared.access.token()).into_bytes(),
            "text/html; charset=utf-8",
            None,
        )),
        _ => match asset(path) {
            Some(a) => Ok((a.body.as_bytes().to_vec(), a.content_type, None)),
            None => Err(EditorError::NotFound {
                path: path.to_string(),
            }),
        },
    }
}

/// Reads `name=value` from a query string; `None` if absent.
fn query_number(query: &str, name: &str) -> Result<Option<f64>, EditorError> {
    for pair in query.split('&') {
        if let Some((key, value)) = pair.split_once('=') {
            if key == name {
                return value
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .map(Some)
                    .ok_or_else(|| EditorError::BadRequest {
                        reason: format!("query parameter {name}={value} is not a finite number"),
                    });
            }
        }
    }
    Ok(None)
}

/// Fur along the current field, with `strands` (default `default_strands`, at most
/// [`MAX_STRANDS`]) and `length` (mean edge lengths) from the query.
fn fur(
    shared: &Shared,
    query: &str,
    default_strands: usize,
) -> Result<Vec<Vec<[f64; 3]>>, EditorError> {
    let strands = query_number(query, "strands")?.unwrap_or(default_strands as f64);
    if !(1.0..=MAX_STRANDS as f64).contains(&strands) || strands.fract() != 0.0 {
        return Err(EditorError::BadRequest {
            reason: format!(
                "strands must be a whole number between 1 and {MAX_STRANDS}, got {strands}"
            ),
        });
    }
    let defaults = FurOptions::default();
    let length = query_number(query, "length")?.unwrap_or(defaults.length);
    if !(length > 0.0 && length <= MAX_FUR_LENGTH) {
        return Err(EditorError::BadRequest {
            reason: format!(
                "length must be positive and at most {MAX_FUR_LENGTH} (bounding-box diagonals), \
                 got {length}"
            ),
        });
    }
    let options = FurOptions {
        strand_count: strands as usize,
        length,
        ..defaults
    };
    let vectors = shared.editor.face_vectors()?;
    Ok(grow_fur(shared.editor.mesh(), &vectors, &options)?)
}

/// The fur as OBJ polylines, written by tvf-render's OBJ exporter.
fn fur_obj(shared: &Shared, query: &str) -> Result<Vec<u8>, EditorError> {
    let strands = fur(shared, query, 20_000)?;
    let io = |what: &str| {
        let what = what.to_string();
        move |source| EditorError::Io { what, source }
    };
    let dir = tempfile::tempdir().map_err(io("creating a temporary directory"))?;
    let path = dir.path().join("fur.obj");
    write_obj(&path, None, &strands)?;
    std::fs::read(&path).map_err(io("reading the exported fur"))
}
