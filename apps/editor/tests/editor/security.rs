//! The editor server over loopback as an adversary sees it: requests from other web pages
//! (foreign Host or Origin, no token) are refused with 403 and change nothing, stalled uploads
//! do not keep `/api/ping` from being answered, bad parameters and unknown JSON fields are 400,
//! an edit whose field would not be finite is refused, and a bounded stress run keeps every
//! answer correct.

use crate::common::{error_message, icosphere_server, icosphere_server_with_deadlines, Client};
use serde_json::json;
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::{Duration, Instant};
use tvf_editor::decode_field_frame;
use tvf_editor::server::ServerDeadlines;

/// Sends `request` as raw bytes and returns (status, body) of the answer.
fn raw(address: SocketAddr, request: &str) -> (u16, String) {
    let mut stream = TcpStream::connect(address).expect("connect");
    stream
        .set_read_timeout(Some(Duration::from_secs(30)))
        .unwrap();
    stream.write_all(request.as_bytes()).expect("send");
    let mut answer = Vec::new();
    stream.read_to_end(&mut answer).expect("answer");
    let text = String::from_utf8_lossy(&answer).into_owned();
    let status = text
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no status line in {text:?}"));
    let body = text
        .split_once("\r\n\r\n")
        .map_or(String::new(), |(_, b)| b.to_string());
    (status, body)
}

fn vector(id: &str, face: usize, value: [f64; 3]) -> serde_json::Value {
    json!({"id": id, "kind": "vector", "face": face, "value": value})
}

fn version(client: &Client) -> u64 {
    let (status, body) = client.get("/api/field");
    assert_eq!(status, 200);
    decode_field_frame(&body).unwrap().status["version"]
        .as_u64()
        .unwrap()
}

#[test]
fn requests_from_elsewhere_get_403_and_change_nothing() {
    let server = icosphere_server();
    let client = Client::new(&server);
    let address = server.address();
    let host = format!("Host: {address}");
    let token = format!("X-TVF-Token: {}", server.token());
    assert_eq!(
        client
            .edit(json!({"op": "add", "constraint": vector("a", 5, [1.0, 0.0, 0.0])}))
            .0,
        200
    );
    let before = version(&client);
    let edit = r#"{"op":"clear"}"#;
    let post = |headers: &[&str]| {
        raw(
            address,
            &format!(
                "POST /api/edit HTTP/1.1\r\n{}\r\nContent-Type: text/plain\r\nContent-Length: {}\r\n\r\n{edit}",
                headers.join("\r\n"),
                edit.len()
            ),
        )
    };
    let get = |target: &str, headers: &[&str]| {
        raw(
            address,
            &format!("GET {target} HTTP/1.1\r\n{}\r\n\r\n", headers.join("\r\n")),
        )
    };
    // The issue's attack: a foreign page posting text/plain (no CORS preflight).
    let evil = ["Host: evil.example.com", "Origin: http://evil.example.com"];
    assert_eq!(post(&evil).0, 403);
    assert_eq!(
        post(&[evil[0], &token]).0,
        403,
        "foreign Host with the token"
    );
    assert_eq!(
        post(&[&host, evil[1], &token]).0,
        403,
        "foreign Origin with the token"
    );
    assert_eq!(post(&[&host, "Origin: null", &token]).0, 403);
    assert_eq!(post(&[&host]).0, 403, "no token");
    assert_eq!(post(&[&host, "X-TVF-Token: 0123"]).0, 403, "wrong token");
    // DNS rebinding: a foreign Host reading the data.
    let (status, body) = get("/api/constraints", &["Host: evil.example.com:1", &token]);
    assert_eq!(status, 403);
    assert!(!body.contains("\"a\""), "{body}");
    assert_eq!(get("/api/constraints", &[&host]).0, 403, "no token");
    assert_eq!(get("/", &[&host]).0, 403, "the page without its token");
    let (status, page) = get(&format!("/?token={}", server.token()), &[&host]);
    assert_eq!(status, 200);
    assert!(page.contains(server.token()), "the page embeds the token");
    assert_eq!(
        get("/app.js", &[&host]).0,
        200,
        "static scripts need no token"
    );
    assert_eq!(get("/app.js", &["Host: evil.example.com"]).0, 403);
    // Nothing changed; the page's own requests work.
    assert_eq!(version(&client), before);
    let (status, body) = post(&[&host, &format!("Origin: http://{address}"), &token]);
    assert_eq!(status, 200, "{body}");
    assert!(server.url().contains(server.token()));
    server.shutdown();
}

#[test]
fn bad_parameters_unknown_fields_and_malformed_requests_are_400() {
    let server = icosphere_server();
    let client = Client::new(&server);
    let address = server.address();
    for query in ["length=-1", "length=0", "length=1e9", "length=nan"] {
        let (status, body) = client.get(&format!("/api/fur?{query}"));
        assert_eq!(status, 400, "{query}: {}", String::from_utf8_lossy(&body));
        assert!(error_message(&body).contains("length"), "{query}");
    }
    for op in [
        json!({"op": "clear", "extra": 1}),
        json!({"op": "undo", "extra": 1}),
        json!({"op": "omega", "value": 0.1, "extra": 1}),
        json!({"op": "add", "constraint": {"id": "x", "kind": "vector", "face": 1, "value": [1, 0, 0], "extra": 1}}),
    ] {
        let (status, body) = client.edit(op.clone());
        assert_eq!(status, 400, "{op}: {}", String::from_utf8_lossy(&body));
        assert!(error_message(&body).contains("extra"), "{op}");
    }
    let host = format!("Host: {address}\r\nX-TVF-Token: {}", server.token());
    for request in [
        "GARBAGE\r\n\r\n".to_string(),
        format!("GET /api/ping HTTP/9\r\n{host}\r\n\r\n"),
        format!("POST /api/edit HTTP/1.1\r\n{host}\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n\r\n"),
        format!("POST /api/edit HTTP/1.1\r\n{host}\r\nContent-Length: x\r\n\r\n"),
        format!("POST /api/edit HTTP/1.1\r\n{host}\r\nContent-Length: 3\r\nContent-Length: 4\r\n\r\nabcd"),
    ] {
        assert_eq!(raw(address, &request).0, 400, "{request:?}");
    }
    let (status, body) = raw(
        address,
        &format!("POST /api/edit HTTP/1.1\r\n{host}\r\nContent-Length: 999999999\r\n\r\n"),
    );
    assert_eq!(status, 413);
    // The message is about the request, not about a payload format.
    let message = error_message(body.as_bytes());
    assert!(
        message.contains("request is too large") && message.contains("999999999"),
        "{message}"
    );
    assert!(!message.contains("binary format"), "{message}");
    server.shutdown();
}

#[test]
fn a_refused_basis_size_explains_itself_and_keeps_the_version() {
    let server = icosphere_server();
    let client = Client::new(&server);
    assert_eq!(
        client
            .edit(json!({"op": "add", "constraint": vector("v1", 5, [1.0, 0.0, 0.0])}))
            .0,
        200
    );
    let before = version(&client);
    let (status, body) = client.edit(json!({"op": "basis_size", "value": 1}));
    assert_eq!(status, 409, "{}", String::from_utf8_lossy(&body));
    let message = error_message(&body);
    assert!(
        message.contains("'v1'")
            && message.contains("1 basis fields")
            && message.contains("larger basis"),
        "{message}"
    );
    assert!(!message.contains("['v1']"), "{message}");
    assert_eq!(
        version(&client),
        before,
        "a refused edit bumped the version"
    );
    let (status, _) = client.edit(json!({"op": "basis_size", "value": 500}));
    assert_eq!(status, 400);
    assert_eq!(version(&client), before);
    server.shutdown();
}

#[test]
fn an_edit_whose_field_is_not_finite_is_refused_naming_the_constraint() {
    let server = icosphere_server();
    let client = Client::new(&server);
    assert_eq!(
        client
            .edit(json!({"op": "add", "constraint": vector("calm", 9, [1.0, 0.0, 0.0])}))
            .0,
        200
    );
    let before = version(&client);
    for (op, id) in [
        (
            json!({"op": "add", "constraint": vector("huge", 5, [1e308, 1e308, -1e308])}),
            "'huge'",
        ),
        (
            json!({"op": "set", "constraint": vector("calm", 9, [1e308, -1e308, 1e308])}),
            "'calm'",
        ),
    ] {
        let (status, body) = client.edit(op.clone());
        assert_eq!(status, 422, "{op}: {}", String::from_utf8_lossy(&body));
        let message = error_message(&body);
        assert!(
            message.contains(id) && message.contains("NaN") && message.contains("overflow"),
            "{message}"
        );
    }
    // Nothing changed: the field and its check are those before the edits.
    assert_eq!(version(&client), before);
    let check = client.check();
    assert_eq!(check["constraints"].as_array().unwrap().len(), 1, "{check}");
    assert!(check["max_relative"].as_f64().unwrap() < 1e-9, "{check}");
    server.shutdown();
}

/// Opens `count` connections that announce a 2 MB body and send only its first kilobyte.
fn stalled_uploads(address: SocketAddr, token: &str, count: usize) -> Vec<TcpStream> {
    (0..count)
        .map(|_| {
            let mut stream = TcpStream::connect(address).unwrap();
            let head = format!(
                "POST /api/edit HTTP/1.1\r\nHost: {address}\r\nX-TVF-Token: {token}\r\nContent-Length: 2000000\r\n\r\n"
            );
            stream.write_all(head.as_bytes()).unwrap();
            stream.write_all(&[b' '; 1000]).unwrap();
            stream
        })
        .collect()
}

/// The body deadline of [`stalled_uploads_do_not_block_ping_and_time_out`]'s server: long
/// enough for its pings to be answered while the uploads still wait (each ping takes
/// milliseconds), short enough not to be waited out for the default's 10 s.
const STALLED_BODY_DEADLINE: Duration = Duration::from_secs(3);

#[test]
fn stalled_uploads_do_not_block_ping_and_time_out() {
    let server = icosphere_server_with_deadlines(ServerDeadlines {
        body: STALLED_BODY_DEADLINE,
        ..ServerDeadlines::default()
    });
    let client = Client::new(&server);
    let started = Instant::now();
    let mut stalled = stalled_uploads(server.address(), server.token(), 8);
    std::thread::sleep(Duration::from_millis(200));
    for _ in 0..20 {
        let start = Instant::now();
        let (status, body) = client.get("/api/ping");
        assert_eq!((status, body.as_slice()), (200, &b"ok"[..]));
        assert!(
            start.elapsed() < Duration::from_secs(2),
            "{:?}",
            start.elapsed()
        );
    }
    // The pings were answered while every upload still waited for its body: none of them has
    // been answered yet.
    for stream in &stalled {
        stream.set_nonblocking(true).unwrap();
        let mut byte = [0u8; 1];
        let pending = stream.peek(&mut byte);
        assert!(
            matches!(&pending, Err(e) if e.kind() == std::io::ErrorKind::WouldBlock),
            "an upload was answered before its deadline, after {:?}: {pending:?}",
            started.elapsed()
        );
        stream.set_nonblocking(false).unwrap();
    }
    // The stalled uploads are answered 408 when their body deadline passes, not before.
    let mut answer = String::new();
    stalled[0]
        .set_read_timeout(Some(Duration::from_secs(30)))
        .unwrap();
    let _ = stalled[0].read_to_string(&mut answer);
    assert!(answer.starts_with("HTTP/1.1 408"), "{answer:?}");
    let elapsed = started.elapsed();
    assert!(elapsed >= STALLED_BODY_DEADLINE, "{elapsed:?}");
    assert!(
        elapsed < STALLED_BODY_DEADLINE + Duration::from_secs(15),
        "{elapsed:?}"
    );
    server.shutdown();
}

/// Idle connections (opened, nothing sent) beyond the server's capacity do not keep the page's
/// token-bearing requests out: each is answered at once.
#[test]
fn idle_connections_do_not_keep_the_page_out() {
    let server = icosphere_server();
    let client = Client::new(&server);
    let address = server.address();
    let idle: Vec<TcpStream> = (0..IDLE_CONNECTIONS)
        .map(|_| TcpStream::connect(address).unwrap())
        .collect();
    std::thread::sleep(Duration::from_millis(300));
    for _ in 0..10 {
        let start = Instant::now();
        let (status, body) = client.get("/api/ping");
        assert_eq!(
            (status, body.as_slice()),
            (200, &b"ok"[..]),
            "{}",
            String::from_utf8_lossy(&body)
        );
        assert!(
            start.elapsed() < Duration::from_secs(2),
            "{:?}",
            start.elapsed()
        );
        let (status, _) = client.get("/api/field");
        assert_eq!(status, 200);
    }
    drop(idle);
    server.shutdown();
}

/// Twice the connections the server lets wait for their request head.
const IDLE_CONNECTIONS: usize = 2 * tvf_editor::server::MAX_WAITING_CONNECTIONS;

/// The `p`-quantile of `values` (sorted in place).
fn quantile(values: &mut [f64], p: f64) -> f64 {
    values.sort_by(f64::total_cmp);
    values[((values.len() - 1) as f64 * p).round() as usize]
}

#[test]
fn stress_eight_clients_and_four_stalled_uploads_stay_correct() {
    let server = icosphere_server();
    let _stalled = stalled_uploads(server.address(), server.token(), 4);
    let clients = 8;
    let requests = 200;
    let pings: Vec<f64> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..clients)
            .map(|c| {
                let server = &server;
                scope.spawn(move || {
                    let client = Client::new(server);
                    let id = format!("c{c}");
                    let face = 40 * c + 3;
                    let (status, body) = client.edit(
                        json!({"op": "add", "constraint": vector(&id, face, [1.0, 0.0, 0.0])}),
                    );
                    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
                    let mut pings = Vec::new();
                    for k in 0..requests {
                        match k % 4 {
                            0 => {
                                let start = Instant::now();
                                let (status, body) = client.get("/api/ping");
                                pings.push(start.elapsed().as_secs_f64() * 1e3);
                                assert_eq!((status, body.as_slice()), (200, &b"ok"[..]));
                            }
                            1 => {
                                let value = [1.0, 0.01 * k as f64, 0.0];
                                let (status, body) = client.edit(
                                    json!({"op": "set", "constraint": vector(&id, face, value)}),
                                );
                                assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
                                let frame = decode_field_frame(&body).expect("field frame");
                                assert!(frame.coefficients.iter().all(|x| x.is_finite()));
                            }
                            2 => {
                                let (status, body) = client.get("/api/field");
                                assert_eq!(status, 200);
                                decode_field_frame(&body).expect("field frame");
                            }
                            _ => {
                                let check = client.check();
                                assert!(check["max_relative"].as_f64().unwrap() < 1e-8, "{check}");
                            }
                        }
                    }
                    pings
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("client thread"))
            .collect()
    });
    let mut pings = pings;
    let p50 = quantile(&mut pings, 0.5);
    let p95 = quantile(&mut pings, 0.95);
    let max = quantile(&mut pings, 1.0);
    println!(
        "stress: {clients} clients x {requests} requests + 4 stalled uploads: /api/ping p50 {p50:.2} ms, p95 {p95:.2} ms, max {max:.2} ms ({} pings)",
        pings.len()
    );
    // Generous bound (a shared 2-core machine); the measured figure is printed above.
    assert!(p95 < 1000.0, "p95 of /api/ping {p95:.1} ms");
    let check = Client::new(&server).check();
    assert_eq!(check["constraints"].as_array().unwrap().len(), clients);
    assert!(check["max_relative"].as_f64().unwrap() < 1e-8, "{check}");
    server.shutdown();
}
