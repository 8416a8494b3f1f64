//! [`Editor`]: the handle to the editing engine ([`crate::engine`]) that the HTTP threads use.

use std::path::Path;
use std::sync::mpsc::{channel, Sender};
use std::sync::Arc;

use tvf_core::discretization::HodgeOperators;
use tvf_core::SurfaceMesh;
use tvf_design::{ConstraintSet, ReducedBasis};
use tvf_discretizations::BoxedComplex;

use crate::edit_op::EditOp;
use crate::engine::{run_engine, Reply, Request, Snapshot};
use crate::error::EditorError;
use crate::status::CheckReport;

/// Handle to the editing engine (cheap to clone; the engine stops when every handle is gone).
#[derive(Clone)]
pub struct Editor {
    requests: Sender<Request>,
    mesh: Arc<SurfaceMesh>,
}

/// What the engine starts from.
pub struct EditorSetup {
    /// The mesh.
    pub mesh: SurfaceMesh,
    /// The basis `U` (`n1 × d`) with its eigenvalues.
    pub basis: ReducedBasis,
    /// Constraints and ω to start with (none and ω = 0.1 if `None`).
    pub constraints: Option<ConstraintSet>,
    /// Number of basis fields to use at first (all if `None`).
    pub basis_size: Option<usize>,
    /// The complex of `mesh` the basis belongs to, built from the catalog entry of the caller's
    /// catalog (`Catalog::build_complex`; an entry of one's own as well as a built-in one).
    pub complex: BoxedComplex,
}

impl Editor {
    /// Starts the engine thread: the session and the first field with the complex's operators.
    /// Fails on a complex without field sampling, a basis of another field dimension, a bad basis
    /// size or constraints that do not fit the mesh or are dependent.
    pub fn start(setup: EditorSetup) -> Result<Self, EditorError> {
        let EditorSetup {
            mesh,
            basis,
            constraints,
            basis_size,
            complex,
        } = setup;
        complex
            .require_sampling()
            .map_err(|e| EditorError::Discretization(e.to_string()))?;
        if basis.field_dimension() != complex.field_dimension() {
            return Err(EditorError::BadRequest {
                reason: format!(
                    "the basis has {} rows but the fields of '{}' on this mesh have {}",
                    basis.field_dimension(),
                    complex.id(),
                    complex.field_dimension(),
                ),
            });
        }
        let d = basis_size.unwrap_or(basis.len());
        if d == 0 || d > basis.len() {
            return Err(EditorError::BadBasisSize {
                requested: d,
                available: basis.len(),
            });
        }
        let set = constraints.unwrap_or(ConstraintSet {
            omega: tvf_design::DEFAULT_OMEGA,
            constraints: Vec::new(),
            mesh_fingerprint: None,
        });
        let initial = Snapshot {
            constraints: set.constraints,
            omega: set.omega,
            basis_size: d,
        };
        let mesh = Arc::new(mesh);
        let (requests, inbox) = channel();
        let (started, started_rx) = channel();
        let engine_mesh = Arc::clone(&mesh);
        std::thread::Builder::new()
            .name("tvf-editor-engine".into())
            .spawn(move || {
                run_engine(
                    &engine_mesh,
                    complex.as_ref(),
                    basis,
                    initial,
                    inbox,
                    started,
                )
            })
            .map_err(|source| EditorError::Io {
                what: "starting the editing engine thread".into(),
                source,
            })?;
        started_rx
            .recv()
            .map_err(|_| EditorError::EngineStopped)??;
        Ok(Self { requests, mesh })
    }

    /// The mesh being edited.
    pub fn mesh(&self) -> &SurfaceMesh {
        &self.mesh
    }

    fn ask<T>(&self, make: impl FnOnce(Reply<T>) -> Request) -> Result<T, EditorError> {
        let (tx, rx) = channel();
        self.requests
            .send(make(tx))
            .map_err(|_| EditorError::EngineStopped)?;
        rx.recv().map_err(|_| EditorError::EngineStopped)?
    }

    /// Applies an edit and returns the new field frame (see [`crate::payload`]). A refused
    /// edit leaves the state unchanged; a constraint set made for another mesh (its
    /// `mesh_fingerprint` differs from the mesh's) is refused before it reaches the session.
    pub fn edit(&self, op: EditOp) -> Result<Vec<u8>, EditorError> {
        if let EditOp::Load(set) = &op {
            let fingerprint = format!("{:016x}", self.mesh.fingerprint());
            set.check_fingerprint(&fingerprint, Path::new("loaded constraint set"))?;
        }
        self.ask(|r| Request::Edit(op, r))
    }

    /// The current field frame.
    pub fn field_frame(&self) -> Result<Vec<u8>, EditorError> {
        self.ask(Request::Frame)
    }

    /// The current constraints and ω as constraint-file JSON.
    pub fn constraint_set_json(&self) -> Result<String, EditorError> {
        self.ask(Request::ConstraintSet)
    }

    /// Checks the held field at full precision against every constraint.
    pub fn check(&self) -> Result<CheckReport, EditorError> {
        self.ask(Request::Check)
    }

    /// The held field as one 3D vector per face (`F` entries).
    pub fn face_vectors(&self) -> Result<Vec<[f64; 3]>, EditorError> {
        self.ask(Request::FaceVectors)
    }
}
