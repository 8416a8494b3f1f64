//! What the server tells the page after every edit ([`Status`], sent as JSON in each field
//! frame), where to draw each constraint ([`Anchor`]), and the full-precision check of the held
//! field against the constraints ([`CheckReport`], `GET /api/check`).

use serde::Serialize;
use tvf_core::SurfaceMesh;
use tvf_design::{CompiledConstraint, Constraint, ConstraintSet, Location, ReducedBasis};

/// A point of the surface where a constraint is drawn: a face and the point's weights over its
/// corners (a [`tvf_core::SurfacePoint`]; barycentric coordinates on a triangle).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Anchor {
    /// Face index.
    pub face: usize,
    /// Weights over the face's corners, in its corner order.
    pub barycentric: Vec<f64>,
}

impl Anchor {
    /// The point of `face` (with `corners` corners) whose weight is spread evenly over the
    /// corners `listed`: a corner (`[c]`) or the midpoint of a side (`[c, c + 1]`).
    fn at_corners(face: usize, corners: usize, listed: &[usize]) -> Self {
        let mut barycentric = vec![0.0; corners];
        for &c in listed {
            barycentric[c] = 1.0 / listed.len() as f64;
        }
        Self { face, barycentric }
    }
}

/// Maps constraint locations to anchors (vertices and edges to a face that contains them).
#[derive(Debug, Clone)]
pub struct Anchors {
    /// Corner count of every face.
    face_sizes: Vec<usize>,
    /// A face at every vertex, and the vertex's corner in it.
    vertex_face: Vec<(usize, usize)>,
    /// A face at every edge, and the edge's first corner in it (the side from that corner to
    /// the next).
    edge_face: Vec<(usize, usize)>,
}

impl Anchors {
    /// Precomputes one incident face per vertex and per edge of `mesh`.
    pub fn new(mesh: &SurfaceMesh) -> Self {
        let face_sizes: Vec<usize> = (0..mesh.face_count()).map(|f| mesh.face_size(f)).collect();
        let mut vertex_face = vec![(0, 0); mesh.vertex_count()];
        let mut edge_face = vec![(0, 0); mesh.edge_count()];
        for f in (0..mesh.face_count()).rev() {
            for (c, &i) in mesh.face(f).iter().enumerate() {
                vertex_face[i] = (f, c);
                edge_face[mesh.face_edge(f, c)] = (f, c);
            }
        }
        Self {
            face_sizes,
            vertex_face,
            edge_face,
        }
    }

    /// Where `constraint` is drawn (the face centroid for a face without barycentric point).
    pub fn of(&self, constraint: &Constraint) -> Anchor {
        match &constraint.location {
            Location::Face { face, barycentric } => Anchor {
                face: *face,
                barycentric: barycentric.clone().unwrap_or_else(|| {
                    let n = self.face_sizes[*face];
                    vec![1.0 / n as f64; n]
                }),
            },
            Location::Vertex(v) => {
                let (face, corner) = self.vertex_face[*v];
                Anchor::at_corners(face, self.face_sizes[face], &[corner])
            }
            Location::Edge(e) => {
                let (face, corner) = self.edge_face[*e];
                let n = self.face_sizes[face];
                Anchor::at_corners(face, n, &[corner, (corner + 1) % n])
            }
        }
    }
}

/// The state of the session as the page sees it.
#[derive(Debug, Clone, Serialize)]
pub struct Status {
    /// Increases with every accepted edit.
    pub version: u64,
    /// Weight ω of the Dirichlet term in `E_B + ω E_D`.
    pub omega: f64,
    /// Number `d` of basis fields in use.
    pub basis_size: usize,
    /// Number of fields in the loaded basis (the slider's maximum).
    pub max_basis_size: usize,
    /// Number of faces `F` (the frame carries `2F` values).
    pub faces: usize,
    /// The constraints as records of the constraint-file format.
    pub constraints: serde_json::Value,
    /// Where each constraint is drawn (same order as `constraints`).
    pub anchors: Vec<Anchor>,
    /// Largest relative constraint residual of the held (`f64`) field.
    pub residual: f64,
    /// Time of the reduced solve, milliseconds.
    pub solve_ms: f64,
    /// Time of the map to the full field (`f32`), milliseconds.
    pub map_ms: f64,
    /// How the field was updated: `mapped` (a pass over `U`), `cache built` (a pass over `U`
    /// that also prepared the drag cache) or `cached` (a value change through the cache).
    pub update: &'static str,
    /// Number of edits that can be undone.
    pub undo_depth: usize,
}

/// The constraint records of `constraints` (the `"constraints"` array of the file format).
pub fn constraint_records(constraints: &[Constraint], omega: f64) -> serde_json::Value {
    let set = ConstraintSet {
        omega,
        constraints: constraints.to_vec(),
        mesh_fingerprint: None,
    };
    serde_json::from_str::<serde_json::Value>(&set.to_json())
        .ok()
        .and_then(|mut v| v.get_mut("constraints").map(serde_json::Value::take))
        .unwrap_or(serde_json::Value::Array(Vec::new()))
}

/// Largest relative residual `‖rows · x − values‖ / max(‖values‖, ‖|rows|·|x|‖)` over the
/// constraints, for `x = U v`, evaluating only the coefficients of `x` the rows touch (in `f64`).
pub fn reduced_residual(basis: &ReducedBasis, v: &[f64], compiled: &[CompiledConstraint]) -> f64 {
    let mut worst: f64 = 0.0;
    for c in compiled {
        let (mut r2, mut t2, mut c2) = (0.0, 0.0, 0.0);
        for (row, value) in c.rows.iter().zip(&c.values) {
            let mut sum = 0.0;
            let mut terms = 0.0;
            for &(j, a) in row {
                let x: f64 = basis.row(j).iter().zip(v).map(|(u, w)| u * w).sum();
                sum += a * x;
                terms += (a * x).abs();
            }
            r2 += (sum - value) * (sum - value);
            t2 += terms * terms;
            c2 += value * value;
        }
        let scale = c2.sqrt().max(t2.sqrt()).max(f64::MIN_POSITIVE);
        worst = worst.max(r2.sqrt() / scale);
    }
    worst
}

/// One constraint's residual in a [`CheckReport`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckedConstraint {
    /// Constraint id.
    pub id: String,
    /// `‖rows · x − values‖₂` (units of the values).
    pub absolute: f64,
    /// Relative residual (see `tvf_design::ConstraintResidual`).
    pub relative: f64,
}

/// The held field checked at full precision: `x = U v` mapped in `f64` and every constraint's
/// rows evaluated on it, and how far the `f32` field sent to the page is from it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckReport {
    /// Version of the field checked.
    pub version: u64,
    /// One entry per constraint.
    pub constraints: Vec<CheckedConstraint>,
    /// Largest relative residual (0 without constraints).
    pub max_relative: f64,
    /// `max |x_f32 − x_f64| / max |x_f64|` (0 for a zero field).
    pub f32_deviation: f64,
}
