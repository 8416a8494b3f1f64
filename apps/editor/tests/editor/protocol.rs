//! The editor's HTTP API driven by a scripted client (no browser): every edit answers with a
//! field that satisfies the constraints, refused edits answer 4xx and leave the state alone.

use crate::common::{error_message, icosphere_server, polygon_server, Client, FACES};
use serde_json::json;
use tvf_core::generate::icosphere;
use tvf_editor::decode_field_frame;
use tvf_editor::payload::{FIELD_MAGIC, MESH_MAGIC};

fn frame(status: u16, body: &[u8]) -> tvf_editor::FieldFrame {
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(body));
    decode_field_frame(body).expect("field frame")
}

fn vector(id: &str, face: usize, value: [f64; 3]) -> serde_json::Value {
    json!({"id": id, "kind": "vector", "face": face, "barycentric": [0.2, 0.3, 0.5], "value": value})
}

/// The face frame (e1, e2) of face t of icosphere(3), as the page reconstructs it.
fn frame_of(t: usize) -> [[f64; 3]; 2] {
    let mesh = icosphere(3);
    let p = mesh.positions();
    let f = mesh.faces()[t];
    let e1 = tvf_core::geometry::normalize(tvf_core::geometry::sub(p[f[1]], p[f[0]]));
    [e1, tvf_core::geometry::cross(mesh.face_normal(t), e1)]
}

#[test]
fn serves_the_page_and_the_mesh() {
    let server = icosphere_server();
    let client = Client::new(&server);
    let (status, page) = client.get("/");
    assert_eq!(status, 200);
    let page = String::from_utf8(page).unwrap();
    assert!(page.contains("<canvas id=\"view\""));
    assert!(
        !page.contains("http://") && !page.contains("https://"),
        "the page must not load anything from elsewhere"
    );
    for script in [
        "/app.js",
        "/mesh.js",
        "/camera.js",
        "/gl.js",
        "/net.js",
        "/style.css",
    ] {
        let (status, body) = client.get(script);
        assert_eq!(status, 200, "{script}");
        assert!(body.len() > 100, "{script}");
    }
    let (status, mesh) = client.get("/api/mesh");
    assert_eq!(status, 200);
    let word = |k: usize| u32::from_le_bytes(mesh[4 * k..4 * k + 4].try_into().unwrap());
    assert_eq!(word(0), MESH_MAGIC);
    assert_eq!((word(1), word(2)), (642, FACES as u32));
    // The display triangles, then the faces (here the same triangles) and each triangle's face.
    assert_eq!(
        mesh.len(),
        12 + 12 * 642 + 12 * FACES + 8 + 4 * FACES + 12 * FACES + 4 * FACES
    );
    let at = 3 + 3 * 642 + 3 * FACES;
    assert_eq!((word(at), word(at + 1)), (FACES as u32, 3 * FACES as u32));
    assert!((0..FACES).all(|t| word(at + 2 + t) == 3 && word(at + 2 + 4 * FACES + t) == t as u32));
    let (status, field) = client.get("/api/field");
    let initial = frame(status, &field);
    assert_eq!(
        u32::from_le_bytes(field[..4].try_into().unwrap()),
        FIELD_MAGIC
    );
    assert_eq!(initial.coefficients.len(), 2 * FACES);
    assert!(
        initial.coefficients.iter().all(|&x| x == 0.0),
        "no constraint: zero field"
    );
    assert_eq!(initial.status["max_basis_size"], 100);
    server.shutdown();
}

#[test]
fn edits_keep_the_constraints_satisfied() {
    let server = icosphere_server();
    let client = Client::new(&server);
    let (s, b) =
        client.edit(json!({"op": "add", "constraint": vector("a", 17, [1.0, 0.5, -0.25])}));
    let first = frame(s, &b);
    assert_eq!(first.status["constraints"].as_array().unwrap().len(), 1);
    assert!(first.status["residual"].as_f64().unwrap() < 1e-9);
    // The f32 field the page gets carries the prescribed vector (tangential part) in face 17.
    let [e1, e2] = frame_of(17);
    let (a, c) = (first.coefficients[34] as f64, first.coefficients[35] as f64);
    let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let value = [1.0, 0.5, -0.25];
    assert!(
        (a - dot(value, e1)).abs() < 1e-5 && (c - dot(value, e2)).abs() < 1e-5,
        "{a} {c}"
    );
    let check = client.check();
    assert!(check["max_relative"].as_f64().unwrap() < 1e-9, "{check}");

    // A source, a sink (at a vertex) and a vortex.
    let edits = [
        json!({"id": "s", "kind": "divergence", "face": 300, "barycentric": [0.3, 0.3, 0.4], "value": 2.0}),
        json!({"id": "k", "kind": "divergence", "vertex": 100, "value": -2.0}),
        json!({"id": "r", "kind": "curl", "face": 900, "barycentric": [0.5, 0.25, 0.25], "value": 1.5}),
    ];
    let mut version = first.status["version"].as_u64().unwrap();
    for c in edits {
        let (s, b) = client.edit(json!({"op": "add", "constraint": c}));
        let f = frame(s, &b);
        assert!(f.status["version"].as_u64().unwrap() > version);
        version = f.status["version"].as_u64().unwrap();
    }
    let check = client.check();
    assert_eq!(check["constraints"].as_array().unwrap().len(), 4);
    assert!(check["max_relative"].as_f64().unwrap() < 1e-9, "{check}");
    assert!(check["f32_deviation"].as_f64().unwrap() < 1e-5, "{check}");

    // Dragging: value changes of "a", then moving it to another face.
    for k in 0..10 {
        let angle = k as f64 * 0.3;
        let (s, b) = client.edit(
            json!({"op": "set", "constraint": vector("a", 17, [angle.cos(), angle.sin(), 0.0])}),
        );
        let dragged = frame(s, &b);
        // The first value change prepares the drag cache, the others use it; either way the
        // f32 field sent is U v for the exact coefficients v.
        let expected = if k == 0 { "cache built" } else { "cached" };
        assert_eq!(dragged.status["update"], expected);
        let check = client.check();
        assert!(check["max_relative"].as_f64().unwrap() < 1e-9, "{check}");
        assert!(check["f32_deviation"].as_f64().unwrap() < 1e-5, "{check}");
    }
    let (s, b) = client.edit(json!({"op": "set", "constraint": vector("a", 640, [0.0, 1.0, 0.0])}));
    let moved = frame(s, &b);
    assert_eq!(moved.status["anchors"][0]["face"], 640);
    assert!(client.check()["max_relative"].as_f64().unwrap() < 1e-9);

    // ω and the basis size: constraints still hold in the smaller basis.
    frame_ok(client.edit(json!({"op": "omega", "value": 2.0})));
    let small = frame_ok(client.edit(json!({"op": "basis_size", "value": 40})));
    assert_eq!(small.status["basis_size"], 40);
    assert!(client.check()["max_relative"].as_f64().unwrap() < 1e-9);

    // Undo walks back: basis size, then ω, then the move.
    assert_eq!(
        frame_ok(client.edit(json!({"op": "undo"}))).status["basis_size"],
        100
    );
    assert_eq!(
        frame_ok(client.edit(json!({"op": "undo"}))).status["omega"],
        0.1
    );
    let back = frame_ok(client.edit(json!({"op": "undo"})));
    assert_eq!(
        back.status["anchors"][0]["face"], 17,
        "the drag is one undo step"
    );
    let back = frame_ok(client.edit(json!({"op": "undo"})));
    assert_eq!(back.status["anchors"][0]["face"], 17);
    assert_eq!(
        back.status["constraints"][0]["value"],
        json!([1.0, 0.5, -0.25]),
        "the whole drag is one undo step"
    );
    assert!(client.check()["max_relative"].as_f64().unwrap() < 1e-9);

    // Save, clear, load: the same field comes back.
    let (s, saved) = client.get("/api/constraints");
    assert_eq!(s, 200);
    let saved: serde_json::Value = serde_json::from_slice(&saved).unwrap();
    let before = frame_ok(client.get_field(&client));
    let cleared = frame_ok(client.edit(json!({"op": "clear"})));
    assert!(cleared.coefficients.iter().all(|&x| x == 0.0));
    let loaded = frame_ok(client.edit(json!({"op": "load", "set": saved})));
    assert_eq!(loaded.status["constraints"], before.status["constraints"]);
    for (x, y) in loaded.coefficients.iter().zip(&before.coefficients) {
        assert!((x - y).abs() <= 1e-5 * (1.0 + y.abs()));
    }
    server.shutdown();
}

trait FieldGetter {
    fn get_field(&self, client: &Client) -> (u16, Vec<u8>);
}
impl FieldGetter for Client {
    fn get_field(&self, client: &Client) -> (u16, Vec<u8>) {
        client.get("/api/field")
    }
}

fn frame_ok((status, body): (u16, Vec<u8>)) -> tvf_editor::FieldFrame {
    frame(status, &body)
}

#[test]
fn refused_edits_answer_4xx_and_change_nothing() {
    let server = icosphere_server();
    let mesh_fingerprint = format!("{:016x}", icosphere(3).fingerprint());
    let client = Client::new(&server);
    frame_ok(client.edit(json!({"op": "add", "constraint": vector("a", 5, [1.0, 0.0, 0.0])})));
    let cases: Vec<(serde_json::Value, u16, &str)> = vec![
        // the same face again with another value: conflicting, names both ids
        (
            json!({"op": "add", "constraint": vector("b", 5, [0.0, 1.0, 0.0])}),
            409,
            "conflicting",
        ),
        (
            json!({"op": "add", "constraint": vector("a", 9, [0.0, 1.0, 0.0])}),
            409,
            "already active",
        ),
        (
            json!({"op": "add", "constraint": vector("c", 99999, [0.0, 1.0, 0.0])}),
            400,
            "99999",
        ),
        (
            json!({"op": "add", "constraint": {"id": "d", "kind": "vortex", "face": 1, "value": 1.0}}),
            400,
            "vortex",
        ),
        (
            json!({"op": "set", "constraint": vector("nope", 5, [1.0, 0.0, 0.0])}),
            404,
            "nope",
        ),
        (json!({"op": "remove", "id": "nope"}), 404, "nope"),
        (json!({"op": "omega", "value": -1.0}), 400, "omega"),
        (json!({"op": "basis_size", "value": 0}), 400, "basis size"),
        (json!({"op": "basis_size", "value": 101}), 400, "basis size"),
        (json!({"op": "jump"}), 400, "jump"),
        // a constraint set made for another mesh: refused naming both fingerprints
        (
            json!({"op": "load", "set": {"mesh_fingerprint": "0000000000000000",
                "constraints": [vector("z", 3, [1.0, 0.0, 0.0])]}}),
            400,
            "0000000000000000",
        ),
        (
            json!({"op": "load", "set": {"mesh_fingerprint": "0000000000000000",
                "constraints": []}}),
            400,
            mesh_fingerprint.as_str(),
        ),
        // an empty id would label nothing, a line break would break the report's lines
        (
            json!({"op": "add", "constraint": vector("", 9, [0.0, 1.0, 0.0])}),
            400,
            "has the id \"\"",
        ),
        (
            json!({"op": "add", "constraint": vector("a\nb", 9, [0.0, 1.0, 0.0])}),
            400,
            "control characters",
        ),
    ];
    for (op, code, needle) in cases {
        let (status, body) = client.edit(op.clone());
        assert_eq!(status, code, "{op}: {}", String::from_utf8_lossy(&body));
        let message = error_message(&body);
        assert!(message.contains(needle), "{op}: {message}");
    }
    let (status, body) =
        client.edit(json!({"op": "add", "constraint": vector("b", 5, [0.0, 1.0, 0.0])}));
    assert_eq!(status, 409);
    let ids: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(ids["ids"], json!(["b", "a"]));
    let (status, body) = client.post("/api/edit", "{not json");
    assert_eq!(status, 400, "{}", String::from_utf8_lossy(&body));
    assert_eq!(client.get("/nowhere").0, 404);
    assert_eq!(client.post("/api/mesh", "").0, 405);
    assert_eq!(client.get("/api/edit").0, 405);
    assert_eq!(client.get("/api/fur?strands=-3").0, 400);
    assert_eq!(client.get("/api/fur?strands=abc").0, 400);
    assert_eq!(client.get("/api/fur?strands=1.5").0, 400);
    // Nothing of that changed the state.
    let (s, b) = client.get("/api/field");
    let state = frame(s, &b);
    assert_eq!(state.status["constraints"].as_array().unwrap().len(), 1);
    assert!(client.check()["max_relative"].as_f64().unwrap() < 1e-9);
    // The history holds only the one accepted edit.
    frame_ok(client.edit(json!({"op": "undo"})));
    let (status, body) = client.edit(json!({"op": "undo"}));
    assert_eq!(status, 409, "{}", String::from_utf8_lossy(&body));
    server.shutdown();
}

#[test]
fn fur_follows_the_field_and_exports_as_obj() {
    let server = icosphere_server();
    let client = Client::new(&server);
    frame_ok(client.edit(json!({"op": "add", "constraint": vector("a", 5, [1.0, 0.0, 0.0])})));
    let (status, fur) = client.get("/api/fur?strands=500");
    assert_eq!(status, 200);
    let count = u32::from_le_bytes(fur[0..4].try_into().unwrap()) as usize;
    let per = u32::from_le_bytes(fur[4..8].try_into().unwrap()) as usize;
    assert!(count > 100 && count <= 500, "{count}");
    assert_eq!(per, 8);
    assert_eq!(fur.len(), 8 + 12 * count * per);
    // Strands rise off the unit sphere: the tips lie outside it, the roots on it.
    let point = |s: usize, i: usize| {
        let at = 8 + 12 * (s * per + i);
        let x = |k: usize| {
            f32::from_le_bytes(fur[at + 4 * k..at + 4 * k + 4].try_into().unwrap()) as f64
        };
        (x(0) * x(0) + x(1) * x(1) + x(2) * x(2)).sqrt()
    };
    let lifted = (0..count)
        .filter(|&s| point(s, per - 1) > point(s, 0) + 1e-4)
        .count();
    assert!(lifted > count / 2, "{lifted} of {count} strands are lifted");
    let (status, obj) = client.get("/api/fur.obj?strands=300");
    assert_eq!(status, 200);
    let obj = String::from_utf8(obj).unwrap();
    let lines = obj.lines().filter(|l| l.starts_with("l ")).count();
    assert!(lines > 50 && lines <= 300, "{lines}");
    assert_eq!(
        obj.lines().filter(|l| l.starts_with("v ")).count(),
        lines * 8
    );
    server.shutdown();
}

#[test]
fn many_concurrent_requests_are_all_answered() {
    let server = icosphere_server();
    frame_ok(
        Client::new(&server)
            .edit(json!({"op": "add", "constraint": vector("a", 5, [1.0, 0.0, 0.0])})),
    );
    std::thread::scope(|scope| {
        for thread in 0..4 {
            let server = &server;
            scope.spawn(move || {
                let client = Client::new(server);
                for k in 0..40 {
                    let (status, body) = match k % 4 {
                        0 => client.edit(json!({"op": "set", "constraint": vector("a", 5, [1.0, k as f64 * 0.1, thread as f64])})),
                        1 => client.get("/api/field"),
                        2 => client.post("/api/edit", "garbage"),
                        _ => client.get("/api/check"),
                    };
                    let expected = if k % 4 == 2 { 400 } else { 200 };
                    assert_eq!(status, expected, "{}", String::from_utf8_lossy(&body));
                }
            });
        }
    });
    assert!(
        Client::new(&server).check()["max_relative"]
            .as_f64()
            .unwrap()
            < 1e-9
    );
    server.shutdown();
}

/// The words of a mesh payload from `k` on.
fn payload_words(bytes: &[u8], k: usize, n: usize) -> Vec<u32> {
    (k..k + n)
        .map(|i| u32::from_le_bytes(bytes[4 * i..4 * i + 4].try_into().unwrap()))
        .collect()
}

/// On a polygon mesh (the dual of an icosphere: pentagons and hexagons, not planar) the editor
/// starts with polygon-dec, sends the display triangles and the polygons, a field frame of one
/// vector per polygon in its frame, and takes constraints at points of polygons given by one
/// weight per corner; a point with the wrong number of weights is refused naming the face.
#[test]
fn edits_polygons_at_points_given_by_corner_weights() {
    let dual = tvf_core::generate::dual(&icosphere(2)).expect("the dual");
    let mesh = tvf_core::SurfaceMesh::from(dual);
    let (faces, display) = (mesh.face_count(), mesh.display());
    let corners: usize = (0..faces).map(|f| mesh.face_size(f)).sum();
    let server = polygon_server(&mesh);
    let client = Client::new(&server);
    let (status, payload) = client.get("/api/mesh");
    assert_eq!(status, 200);
    let (v, t) = (display.vertex_count(), display.face_count());
    assert_eq!(
        payload_words(&payload, 0, 3),
        [MESH_MAGIC, v as u32, t as u32]
    );
    let at = 3 + 3 * v + 3 * t;
    assert_eq!(payload.len(), 4 * (at + 2 + faces + corners + t));
    assert_eq!(
        payload_words(&payload, at, 2),
        [faces as u32, corners as u32]
    );
    let sizes = payload_words(&payload, at + 2, faces);
    assert!(sizes
        .iter()
        .enumerate()
        .all(|(f, &n)| n as usize == mesh.face_size(f)));
    let listed = payload_words(&payload, at + 2 + faces, corners);
    let expected: Vec<u32> = (0..faces)
        .flat_map(|f| mesh.face(f).iter().map(|&i| i as u32))
        .collect();
    assert_eq!(listed, expected);
    let face_of = payload_words(&payload, at + 2 + faces + corners, t);
    assert!((0..t).all(|k| face_of[k] as usize == mesh.display_face(k)));

    // A vector at a point of a hexagon, a source and a vortex at points of others: the field
    // (one vector per polygon, in its frame) meets them.
    let hexagon = (0..faces).find(|&f| mesh.face_size(f) == 6).unwrap();
    let weights = [0.3, 0.1, 0.1, 0.2, 0.2, 0.1];
    let vector = json!({"id": "a", "kind": "vector", "face": hexagon, "barycentric": weights, "value": [1.0, 0.5, -0.25]});
    let first = frame_ok(client.edit(json!({"op": "add", "constraint": vector})));
    assert_eq!(first.coefficients.len(), 2 * faces);
    assert_eq!(first.status["faces"], faces);
    assert_eq!(first.status["anchors"][0]["face"], hexagon);
    assert_eq!(first.status["anchors"][0]["barycentric"], json!(weights));
    let pentagon = (0..faces).find(|&f| mesh.face_size(f) == 5).unwrap();
    let far = (0..faces).rev().find(|&f| mesh.face_size(f) == 6).unwrap();
    for c in [
        json!({"id": "s", "kind": "divergence", "face": pentagon, "barycentric": [0.2, 0.2, 0.2, 0.2, 0.2], "value": 2.0}),
        json!({"id": "r", "kind": "curl", "face": far, "value": -1.5}),
        json!({"id": "k", "kind": "divergence", "vertex": 3, "value": -1.0}),
    ] {
        frame_ok(client.edit(json!({"op": "add", "constraint": c})));
    }
    let check = client.check();
    assert_eq!(check["constraints"].as_array().unwrap().len(), 4);
    assert!(check["max_relative"].as_f64().unwrap() < 1e-9, "{check}");
    // The field frame carries, in the hexagon's frame (e1 its first side projected onto its
    // plane, normal to its vector area; e2 = n × e1), the constraint's value projected there.
    let (_, body) = client.get("/api/field");
    let last = decode_field_frame(&body).unwrap();
    let (n, p) = (mesh.face_normal(hexagon), mesh.positions());
    let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let corners = mesh.face(hexagon);
    let side = tvf_core::geometry::sub(p[corners[1]], p[corners[0]]);
    let e1 = tvf_core::geometry::normalize(tvf_core::geometry::sub(
        side,
        tvf_core::geometry::scale(n, dot(n, side)),
    ));
    let e2 = tvf_core::geometry::cross(n, e1);
    let value = [1.0, 0.5, -0.25];
    let (a, c) = (
        last.coefficients[2 * hexagon] as f64,
        last.coefficients[2 * hexagon + 1] as f64,
    );
    assert!(
        (a - dot(value, e1)).abs() < 1e-5 && (c - dot(value, e2)).abs() < 1e-5,
        "{a} {c}"
    );
    // The vertex constraint is drawn at its corner of a polygon that has the vertex.
    let anchor = &last.status["anchors"][3];
    let face = anchor["face"].as_u64().unwrap() as usize;
    let corner = mesh
        .face(face)
        .iter()
        .position(|&i| i == 3)
        .expect("a face at vertex 3");
    assert_eq!(anchor["barycentric"][corner], 1.0);

    // Three weights on a hexagon: refused, naming the face and its corner count.
    let (s, b) = client.edit(json!({"op": "add", "constraint":
        {"id": "bad", "kind": "curl", "face": hexagon, "barycentric": [0.2, 0.3, 0.5], "value": 1.0}}));
    assert_eq!(s, 400);
    assert!(
        error_message(&b).contains(&format!(
            "face {hexagon} has 6 corners, but \"barycentric\" gives 3 weights"
        )),
        "{}",
        error_message(&b)
    );
    assert_eq!(client.check()["constraints"].as_array().unwrap().len(), 4);
    server.shutdown();
}
