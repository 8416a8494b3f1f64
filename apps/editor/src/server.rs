//! [`EditorServer`]: the HTTP server on 127.0.0.1 that serves the page and the editing API.
//!
//! | method, path | answer |
//! |---|---|
//! | `GET /` and the page's files | the embedded page ([`crate::assets`]) |
//! | `GET /api/mesh` | the mesh payload ([`crate::payload`]) |
//! | `GET /api/field` | the current field frame |
//! | `POST /api/edit` | applies an [`EditOp`] (JSON body), answers with the new field frame |
//! | `GET /api/constraints` | the constraints and ω as a constraint file (download) |
//! | `GET /api/check` | [`crate::CheckReport`] as JSON: the held field against the constraints |
//! | `GET /api/fur?strands=N&length=L` | fur strands along the field (binary, for display) |
//! | `GET /api/fur.obj?strands=N&length=L` | the same strands as OBJ polylines (download) |
//! | `GET /api/ping` | `ok` |
//!
//! Errors are answered with a 4xx/5xx status and a JSON body `{"error": "...", "ids": [...]}`.

use std::io::Read;
use std::net::SocketAddr;
use std::sync::Arc;
use std::thread::JoinHandle;

use tiny_http::{Header, Method, Request, Response, Server};
use tvf_render::{grow_fur, write_obj, FurOptions};

use crate::assets::asset;
use crate::edit_op::EditOp;
use crate::editor::Editor;
use crate::error::EditorError;
use crate::payload::{encode_fur, encode_mesh};

/// Largest accepted request body (a constraint set being loaded), bytes.
pub const MAX_BODY_BYTES: u64 = 8 << 20;
/// Most fur strands one request may ask for.
pub const MAX_STRANDS: usize = 200_000;
/// Worker threads answering requests (edits are still applied one at a time by the engine).
const WORKERS: usize = 4;

/// A running editor server; stops with [`EditorServer::shutdown`] (or runs until the process
/// ends with [`EditorServer::join`]).
pub struct EditorServer {
    server: Arc<Server>,
    workers: Vec<JoinHandle<()>>,
    address: SocketAddr,
}

struct Shared {
    editor: Editor,
    mesh_payload: Vec<u8>,
}

impl EditorServer {
    /// Listens on `127.0.0.1:port` (`port` 0: chosen by the OS) and starts answering.
    pub fn start(editor: Editor, port: u16) -> Result<Self, EditorError> {
        let server = Server::http(("127.0.0.1", port)).map_err(|e| EditorError::Io {
            what: format!("listening on 127.0.0.1:{port}"),
            source: std::io::Error::other(e.to_string()),
        })?;
        let address = server
            .server_addr()
            .to_ip()
            .ok_or_else(|| EditorError::Io {
                what: "reading the server's address".into(),
                source: std::io::Error::other("not an IP socket"),
            })?;
        let shared = Arc::new(Shared {
            mesh_payload: encode_mesh(editor.mesh())?,
            editor,
        });
        let server = Arc::new(server);
        let mut workers = Vec::with_capacity(WORKERS);
        for k in 0..WORKERS {
            let server = Arc::clone(&server);
            let shared = Arc::clone(&shared);
            let worker = std::thread::Builder::new()
                .name(format!("tvf-editor-http-{k}"))
                .spawn(move || {
                    while let Ok(request) = server.recv() {
                        // A panic while answering one request must not take the worker down;
                        // the request is then dropped, which answers 500.
                        let _ = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                            handle(&shared, request)
                        }));
                    }
                })
                .map_err(|source| EditorError::Io {
                    what: "starting an HTTP worker thread".into(),
                    source,
                })?;
            workers.push(worker);
        }
        Ok(Self {
            server,
            workers,
            address,
        })
    }

    /// The address the server listens on.
    pub fn address(&self) -> SocketAddr {
        self.address
    }

    /// The page's URL, `http://127.0.0.1:PORT/`.
    pub fn url(&self) -> String {
        format!("http://{}/", self.address)
    }

    /// Blocks until the server stops (which it does not on its own).
    pub fn join(self) {
        for w in self.workers {
            let _ = w.join();
        }
    }

    /// Stops accepting requests and waits for the workers.
    pub fn shutdown(self) {
        for _ in 0..self.workers.len() {
            self.server.unblock();
        }
        for w in self.workers {
            let _ = w.join();
        }
    }
}

fn header(name: &str, value: &str) -> Header {
    // Names and values are ASCII constants of this file.
    Header::from_bytes(name.as_bytes(), value.as_bytes())
        .unwrap_or_else(|_| Header::from_bytes(&b"X-Invalid"[..], &b"1"[..]).expect("ASCII header"))
}

type Answer = Result<(Vec<u8>, &'static str, Option<&'static str>), EditorError>;

fn handle(shared: &Shared, mut request: Request) {
    let method = request.method().clone();
    let url = request.url().to_string();
    let (path, query) = url.split_once('?').unwrap_or((url.as_str(), ""));
    let answer = route(shared, &method, path, query, &mut request);
    let response = match answer {
        Ok((body, content_type, attachment)) => {
            let mut r = Response::from_data(body)
                .with_header(header("Content-Type", content_type))
                .with_header(header("Cache-Control", "no-store"));
            if let Some(name) = attachment {
                r = r.with_header(header(
                    "Content-Disposition",
                    &format!("attachment; filename=\"{name}\""),
                ));
            }
            r
        }
        Err(error) => {
            let body =
                serde_json::json!({ "error": error.to_string(), "ids": error.involved_ids() });
            Response::from_data(body.to_string().into_bytes())
                .with_status_code(error.status_code())
                .with_header(header("Content-Type", "application/json"))
        }
    };
    // The client may have gone away; nothing to do about it.
    let _ = request.respond(response);
}

fn route(
    shared: &Shared,
    method: &Method,
    path: &str,
    query: &str,
    request: &mut Request,
) -> Answer {
    let not_allowed = || EditorError::MethodNotAllowed {
        method: method.to_string(),
        path: path.to_string(),
    };
    const BINARY: &str = "application/octet-stream";
    const JSON: &str = "application/json";
    match path {
        "/api/edit" => {
            if *method != Method::Post {
                return Err(not_allowed());
            }
            let body = read_body(request)?;
            let op = EditOp::parse(&body)?;
            Ok((shared.editor.edit(op)?, BINARY, None))
        }
        _ if *method != Method::Get => Err(not_allowed()),
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
        _ => match asset(path) {
            Some(a) => Ok((a.body.as_bytes().to_vec(), a.content_type, None)),
            None => Err(EditorError::NotFound {
                path: path.to_string(),
            }),
        },
    }
}

fn read_body(request: &mut Request) -> Result<Vec<u8>, EditorError> {
    let mut body = Vec::new();
    request
        .as_reader()
        .take(MAX_BODY_BYTES + 1)
        .read_to_end(&mut body)
        .map_err(|e| EditorError::BadRequest {
            reason: format!("reading the request body: {e}"),
        })?;
    if body.len() as u64 > MAX_BODY_BYTES {
        return Err(EditorError::TooLarge {
            what: "request body bytes",
            count: body.len(),
        });
    }
    Ok(body)
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
    if !(1.0..=MAX_STRANDS as f64).contains(&strands) {
        return Err(EditorError::BadRequest {
            reason: format!("strands must be between 1 and {MAX_STRANDS}, got {strands}"),
        });
    }
    let defaults = FurOptions::default();
    let options = FurOptions {
        strand_count: strands as usize,
        length: query_number(query, "length")?.unwrap_or(defaults.length),
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
