//! Shared set-up of the editor's integration tests: an editor on an icosphere, a pair of pants or
//! a polygon mesh with a real spectral basis, served on a free loopback port, and a small HTTP
//! client.

use std::collections::HashMap;
use std::io::Read;
use std::sync::Mutex;

use tvf_core::discretization::BoundaryCondition;
use tvf_core::generate::{icosphere, perforated_plate};
use tvf_core::SurfaceMesh;
use tvf_design::ReducedBasis;
use tvf_discretizations::{catalog_entry, DEFAULT_DISCRETIZATION};
use tvf_editor::server::ServerDeadlines;
use tvf_editor::{Editor, EditorServer, EditorSetup};
use tvf_spectral::{compute_basis, BasisRequest};

/// Faces of `icosphere(3)`.
pub const FACES: usize = 1280;

/// The 100 lowest eigenfields of `icosphere(3)` with the catalog entry `id` (computed once per
/// test binary and id).
pub fn icosphere_basis_for(id: &str) -> ReducedBasis {
    static BASES: Mutex<Option<HashMap<String, ReducedBasis>>> = Mutex::new(None);
    let mut bases = BASES.lock().unwrap_or_else(|e| e.into_inner());
    bases
        .get_or_insert_with(HashMap::new)
        .entry(id.to_string())
        .or_insert_with(|| {
            let mesh = SurfaceMesh::from(icosphere(3));
            let complex = catalog_entry(id)
                .expect("catalog id")
                .build(&mesh)
                .expect("icosphere operators");
            // The 100 lowest eigenfields by the sparse eigensolver, as `tvf edit` computes them
            // (rather than the complete basis by the dense eigensolvers, truncated: the same
            // eigenvalues to round-off, in less time); the first 100 columns in case a cluster
            // of equal eigenvalues brings more.
            let d = 100;
            let spectral =
                compute_basis(complex.as_ref(), &BasisRequest::fields(d)).expect("icosphere basis");
            let full = ReducedBasis::from_spectral(&spectral).expect("reduced basis");
            let n = full.field_dimension();
            let rows = (0..n).flat_map(|r| full.row(r)[..d].to_vec()).collect();
            ReducedBasis::from_row_major(
                rows,
                n,
                full.eigenvalues()[..d].to_vec(),
                full.harmonic()[..d].to_vec(),
            )
            .expect("truncated basis")
        })
        .clone()
}

/// The editor on `icosphere(3)` with the 100 lowest eigenfields, served on 127.0.0.1.
pub fn icosphere_server() -> EditorServer {
    icosphere_server_for(DEFAULT_DISCRETIZATION)
}

/// [`icosphere_server`] with the catalog entry `id`.
pub fn icosphere_server_for(id: &str) -> EditorServer {
    icosphere_server_with(id, ServerDeadlines::default())
}

/// [`icosphere_server`] whose clients have `deadlines` to send their requests.
pub fn icosphere_server_with_deadlines(deadlines: ServerDeadlines) -> EditorServer {
    icosphere_server_with(DEFAULT_DISCRETIZATION, deadlines)
}

fn icosphere_server_with(id: &str, deadlines: ServerDeadlines) -> EditorServer {
    let mesh = SurfaceMesh::from(icosphere(3));
    let complex = catalog_entry(id)
        .expect("catalog id")
        .build(&mesh)
        .expect("icosphere operators");
    let editor = Editor::start(EditorSetup {
        mesh,
        basis: icosphere_basis_for(id),
        constraints: None,
        basis_size: None,
        complex,
    })
    .expect("editor starts");
    EditorServer::start_with_deadlines(editor, 0, deadlines).expect("server starts")
}

/// The editor on a generated pair of pants (`perforated_plate(2, 8)`: flat, genus 0, three
/// boundary loops; Delaunay-flipped for entries that need it) with catalog entry `id`, boundary
/// condition `boundary` and its 60 lowest eigenfields, served on 127.0.0.1; also returns the
/// mesh.
pub fn pants_server_for(id: &str, boundary: BoundaryCondition) -> (EditorServer, SurfaceMesh) {
    let entry = catalog_entry(id).expect("catalog id");
    let mesh = SurfaceMesh::from(if entry.needs_delaunay() {
        tvf_conformance::corpus::delaunay_flips(&perforated_plate(2, 8))
    } else {
        perforated_plate(2, 8)
    });
    let complex = entry.build_with(&mesh, boundary).expect("pants operators");
    let spectral = compute_basis(complex.as_ref(), &BasisRequest::fields(60)).expect("pants basis");
    let editor = Editor::start(EditorSetup {
        mesh: mesh.clone(),
        basis: ReducedBasis::from_spectral(&spectral).expect("reduced basis"),
        constraints: None,
        basis_size: None,
        complex,
    })
    .expect("editor starts");
    (EditorServer::start(editor, 0).expect("server starts"), mesh)
}

/// The editor on the polygon mesh `mesh` with `polygon-dec` (its default there) and the 60
/// lowest eigenfields, served on 127.0.0.1.
pub fn polygon_server(mesh: &SurfaceMesh) -> EditorServer {
    assert!(!mesh.is_triangle_mesh());
    let complex = catalog_entry("polygon-dec")
        .expect("catalog id")
        .build(mesh)
        .expect("polygon-dec operators");
    let spectral =
        compute_basis(complex.as_ref(), &BasisRequest::fields(60)).expect("polygon basis");
    let editor = Editor::start(EditorSetup {
        mesh: mesh.clone(),
        basis: ReducedBasis::from_spectral(&spectral).expect("reduced basis"),
        constraints: None,
        basis_size: None,
        complex,
    })
    .expect("editor starts on a polygon mesh");
    EditorServer::start(editor, 0).expect("server starts")
}

/// A blocking HTTP client for one server that returns every status (no error on 4xx) and sends
/// the session token, as the page does.
pub struct Client {
    agent: ureq::Agent,
    base: String,
    token: String,
}

impl Client {
    pub fn new(server: &EditorServer) -> Self {
        let agent = ureq::Agent::config_builder()
            .http_status_as_error(false)
            .build()
            .into();
        Self {
            agent,
            base: format!("http://{}", server.address()),
            token: server.token().to_string(),
        }
    }

    fn read(response: ureq::http::Response<ureq::Body>) -> (u16, Vec<u8>) {
        let status = response.status().as_u16();
        let mut body = Vec::new();
        response
            .into_body()
            .into_reader()
            .read_to_end(&mut body)
            .expect("response body");
        (status, body)
    }

    /// `GET path` → (status, body).
    pub fn get(&self, path: &str) -> (u16, Vec<u8>) {
        Self::read(
            self.agent
                .get(format!("{}{path}", self.base))
                .header("X-TVF-Token", &self.token)
                .call()
                .expect("GET"),
        )
    }

    /// `POST path` with a body → (status, body).
    pub fn post(&self, path: &str, body: &str) -> (u16, Vec<u8>) {
        let response = self
            .agent
            .post(format!("{}{path}", self.base))
            .header("Content-Type", "application/json")
            .header("X-TVF-Token", &self.token)
            .send(body.as_bytes())
            .expect("POST");
        Self::read(response)
    }

    /// `POST /api/edit` with an edit as JSON.
    pub fn edit(&self, op: serde_json::Value) -> (u16, Vec<u8>) {
        self.post("/api/edit", &op.to_string())
    }

    /// `GET /api/check`, parsed.
    pub fn check(&self) -> serde_json::Value {
        let (status, body) = self.get("/api/check");
        assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
        serde_json::from_slice(&body).expect("check JSON")
    }
}

/// The error message of a JSON error body.
pub fn error_message(body: &[u8]) -> String {
    let v: serde_json::Value = serde_json::from_slice(body).expect("error body is JSON");
    v["error"].as_str().expect("error field").to_string()
}
