//! End-to-end: `tvf edit` prints a URL with the session token; the server it started answers
//! the page and the API only with that token and its own Host. On the raw `bunny.obj` of
//! `../shared/meshes` (skipped where it does not exist, a failure under `CI=true`): the dropped
//! unreferenced vertices are reported and an edit over HTTP gives a field that meets its
//! constraint. With `--intrinsic-delaunay` on a mesh that is not Delaunay, the editor serves the
//! basis of the complex built on the flipped triangulation and edits fields on the input faces.

use crate::common::tvf;
use tvf_core::generate::{jitter, torus};
use tvf_core::io::write_obj;
use tvf_editor::decode_field_frame;
use tvf_test_support::{request, shared_mesh, status, EditorProcess};

/// Starts `tvf edit` with `args` and a cache folder.
fn start_editor(args: &[&str], cache: &std::path::Path) -> EditorProcess {
    let mut command = tvf();
    command
        .args(["-q", "edit"])
        .args(args)
        .arg("--cache-dir")
        .arg(cache);
    EditorProcess::start(command)
}

#[test]
fn the_raw_bunny_is_edited_over_http() {
    // Uses ../shared/meshes/bunny.obj (five boundary loops, unreferenced vertices).
    let Some(path) = shared_mesh("bunny.obj") else {
        return;
    };
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
    let server = start_editor(&[path.to_str().unwrap(), "-k", "20"], cache.path());
    let (address, token) = (&server.address, &server.token);
    let printed = server.printed.join("\n");
    assert!(
        printed.contains(&format!("{dropped} unreferenced vertices dropped")),
        "{printed}"
    );
    assert!(
        printed.contains("conforming-barycentric+tangential"),
        "{printed}"
    );
    let (code, frame) = request(
        address,
        "POST",
        "/api/edit",
        token,
        r#"{"op": "add", "constraint": {"id": "v", "kind": "vector", "face": 100, "value": [0.3, 1.0, -0.2]}}"#,
    );
    assert_eq!(code, 200, "{}", String::from_utf8_lossy(&frame));
    assert!(!frame.is_empty(), "the edit answers with the new field");
    let (code, check) = request(address, "GET", "/api/check", token, "");
    assert_eq!(code, 200);
    let check: serde_json::Value = serde_json::from_slice(&check).expect("JSON check");
    assert_eq!(check["constraints"].as_array().unwrap().len(), 1, "{check}");
    assert!(
        check["max_relative"].as_f64().unwrap() < 1e-9,
        "the field misses the constraint: {check}"
    );
    // A constraint the mesh cannot hold is refused with a message naming it.
    let (code, answer) = request(
        address,
        "POST",
        "/api/edit",
        token,
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
    let server = start_editor(&["--example", "icosphere", "-k", "20"], cache.path());
    let (address, token) = (server.address.as_str(), server.token.as_str());
    assert!(token.len() >= 32, "{token}");
    assert_eq!(status(address, address, &server.page(), None), 200);
    assert_eq!(status(address, address, "/", None), 403);
    assert_eq!(status(address, address, "/api/ping", Some(token)), 200);
    assert_eq!(status(address, address, "/api/ping", None), 403);
    assert_eq!(
        status(address, "evil.example.com", "/api/ping", Some(token)),
        403
    );
    drop(server);
}

#[test]
fn an_intrinsic_complex_is_edited_over_http() {
    // A jittered torus: many edges are not Delaunay, so the flag flips them and the complex is
    // built from the intrinsic triangulation's lengths.
    let temp = tempfile::tempdir().unwrap();
    let mesh = jitter(&torus(1.0, 0.4, 18, 9).unwrap(), 0.3, 11).unwrap();
    let path = temp.path().join("torus.obj");
    write_obj(&path, &mesh).unwrap();
    let cache = tempfile::tempdir().unwrap();
    let server = start_editor(
        &[path.to_str().unwrap(), "-k", "20", "--intrinsic-delaunay"],
        cache.path(),
    );
    let (address, token) = (&server.address, &server.token);
    let printed = server.printed.join("\n");
    assert!(
        printed.contains("conforming-barycentric+intrinsic-delaunay"),
        "{printed}"
    );
    let (code, answer) = request(
        address,
        "POST",
        "/api/edit",
        token,
        r#"{"op": "add", "constraint": {"id": "v", "kind": "vector", "face": 40, "value": [0.3, 1.0, -0.2]}}"#,
    );
    assert_eq!(code, 200, "{}", String::from_utf8_lossy(&answer));
    let (code, bytes) = request(address, "GET", "/api/field", token, "");
    assert_eq!(code, 200);
    let frame = decode_field_frame(&bytes).expect("a field frame");
    assert_eq!(
        frame.coefficients.len(),
        2 * mesh.face_count(),
        "one vector per input face"
    );
    assert!(frame.coefficients.iter().all(|x| x.is_finite()));
    assert!(
        frame.coefficients.iter().any(|&x| x != 0.0),
        "the edit moved the field"
    );
    let (code, check) = request(address, "GET", "/api/check", token, "");
    assert_eq!(code, 200);
    let check: serde_json::Value = serde_json::from_slice(&check).expect("JSON check");
    assert!(
        check["max_relative"].as_f64().unwrap() < 1e-9,
        "the field misses the constraint: {check}"
    );
    drop(server);
}
