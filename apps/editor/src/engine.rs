//! [`Editor`]: the editing engine. One thread owns the basis, the operators and the
//! [`SplineSession`]; requests from the HTTP threads reach it over a channel, so edits are
//! applied one at a time, in order.
//!
//! A value change (`set` of a constraint at the same place) only re-solves the session
//! (`SplineSession::modify` keeps the factorisation); adding, removing or moving a constraint
//! borders or downdates the factorisation; ω rebuilds it (the energy changes) and a new basis
//! size rebuilds it on the first `d` fields.

use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::Arc;
use std::time::Instant;

use tvf_core::discretization::{FieldSpace, HodgeComplex};
use tvf_core::SurfaceMesh;
use tvf_design::{
    CompiledConstraint, Constraint, ConstraintAssembler, ConstraintSet, ReducedBasis,
    ReducedBasisF32, SplineSession,
};
use tvf_discretizations::{Conforming, MassLumping};

use crate::edit_op::EditOp;
use crate::error::EditorError;
use crate::payload::encode_field_frame;
use crate::status::{
    constraint_records, reduced_residual, Anchors, CheckReport, CheckedConstraint, Status,
};

type Reply<T> = Sender<Result<T, EditorError>>;

enum Request {
    Edit(EditOp, Reply<Vec<u8>>),
    Frame(Reply<Vec<u8>>),
    ConstraintSet(Reply<String>),
    Check(Reply<CheckReport>),
    FaceVectors(Reply<Vec<[f64; 3]>>),
}

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
    /// The basis `U` (`2F × d`) with its eigenvalues.
    pub basis: ReducedBasis,
    /// Constraints and ω to start with (none and ω = 0.1 if `None`).
    pub constraints: Option<ConstraintSet>,
    /// Number of basis fields to use at first (all if `None`).
    pub basis_size: Option<usize>,
}

#[derive(Debug, Clone, PartialEq)]
struct Snapshot {
    constraints: Vec<Constraint>,
    omega: f64,
    basis_size: usize,
}

impl Editor {
    /// Starts the engine thread: builds the conforming operators of the mesh, the session and
    /// the first field. Fails on a degenerate mesh, a bad basis size or constraints that do not
    /// fit the mesh or are dependent.
    pub fn start(setup: EditorSetup) -> Result<Self, EditorError> {
        let EditorSetup {
            mesh,
            basis,
            constraints,
            basis_size,
        } = setup;
        if basis.field_dimension() != 2 * mesh.face_count() {
            return Err(EditorError::BadRequest {
                reason: format!(
                    "the basis has {} rows but the mesh has {} faces (2F = {})",
                    basis.field_dimension(),
                    mesh.face_count(),
                    2 * mesh.face_count()
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
            .spawn(move || run_engine(&engine_mesh, basis, initial, inbox, started))
            .map_err(|source| EditorError::Io {
                what: "starting the editing engine thread".into(),
                source,
            })?;
        started_rx.recv().map_err(|_| EditorError::EngineStopped)??;
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
    /// edit leaves the state unchanged.
    pub fn edit(&self, op: EditOp) -> Result<Vec<u8>, EditorError> {
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

/// Most undo steps kept.
const HISTORY_LIMIT: usize = 500;

/// The engine's state that outlives a basis size.
struct State<'c> {
    complex: &'c Conforming,
    assembler: ConstraintAssembler<'c, Conforming>,
    anchors: Anchors,
    max_basis_size: usize,
    face_count: usize,
    current: Snapshot,
    compiled: Vec<CompiledConstraint>,
    history: Vec<Snapshot>,
    last_gesture: Option<String>,
    version: u64,
    coefficients: Vec<f64>,
    field32: Vec<f32>,
    solve_ms: f64,
    map_ms: f64,
}

/// A change that needs another basis: the state to reach, and (for an edit) the state to fall
/// back to if that fails, whether to record it for undo, and who waits for the answer.
struct Rebuild {
    target: Snapshot,
    edit: Option<PendingEdit>,
}

struct PendingEdit {
    previous: Snapshot,
    record: bool,
    reply: Reply<Vec<u8>>,
}

fn run_engine(
    mesh: &SurfaceMesh,
    full: ReducedBasis,
    initial: Snapshot,
    inbox: Receiver<Request>,
    started: Sender<Result<(), EditorError>>,
) {
    let complex = match Conforming::new(mesh, MassLumping::Barycentric) {
        Ok(c) => c,
        Err(e) => {
            let _ = started.send(Err(EditorError::Discretization(e.to_string())));
            return;
        }
    };
    let mut state = State {
        complex: &complex,
        assembler: ConstraintAssembler::new(&complex, mesh),
        anchors: Anchors::new(mesh),
        max_basis_size: full.len(),
        face_count: mesh.face_count(),
        current: initial.clone(),
        compiled: Vec::new(),
        history: Vec::new(),
        last_gesture: None,
        version: 0,
        coefficients: vec![0.0; full.len()],
        field32: vec![0.0; 2 * mesh.face_count()],
        solve_ms: 0.0,
        map_ms: 0.0,
    };
    let mut started = Some(started);
    let mut rebuild = Rebuild {
        target: initial,
        edit: None,
    };
    loop {
        let d = rebuild.target.basis_size;
        let truncated = if d < full.len() {
            match truncate(&full, d) {
                Ok(b) => Some(b),
                Err(e) => {
                    if !fail(e, rebuild.edit.take(), &mut started, &mut rebuild) {
                        return;
                    }
                    continue;
                }
            }
        } else {
            None
        };
        let basis = truncated.as_ref().unwrap_or(&full);
        match serve(&mut state, basis, rebuild, &inbox, &mut started) {
            Ok(Some(next)) => rebuild = next,
            Ok(None) => return,
            Err((error, edit)) => {
                rebuild = Rebuild {
                    target: state.current.clone(),
                    edit: None,
                };
                if !fail(error, edit, &mut started, &mut rebuild) {
                    return;
                }
            }
        }
    }
}

/// Reports a failed rebuild: to the waiting edit (and then goes back to its previous state,
/// returning true), or as a start-up error (returning false: the engine stops).
fn fail(
    error: EditorError,
    edit: Option<PendingEdit>,
    started: &mut Option<Sender<Result<(), EditorError>>>,
    rebuild: &mut Rebuild,
) -> bool {
    match edit {
        Some(edit) => {
            let _ = edit.reply.send(Err(error));
            *rebuild = Rebuild {
                target: edit.previous,
                edit: None,
            };
            true
        }
        None => {
            if let Some(s) = started.take() {
                let _ = s.send(Err(error));
            }
            false
        }
    }
}

/// The first `d` fields of `basis` (a copy, row-major).
fn truncate(basis: &ReducedBasis, d: usize) -> Result<ReducedBasis, EditorError> {
    let n = basis.field_dimension();
    let mut rows = Vec::with_capacity(n * d);
    for r in 0..n {
        rows.extend_from_slice(&basis.row(r)[..d]);
    }
    Ok(ReducedBasis::from_row_major(
        rows,
        n,
        basis.eigenvalues()[..d].to_vec(),
        basis.harmonic()[..d].to_vec(),
    )?)
}

fn build_session<'b>(
    basis: &'b ReducedBasis,
    omega: f64,
    compiled: &[CompiledConstraint],
) -> Result<SplineSession<'b>, EditorError> {
    let mut session = SplineSession::new(basis, omega)?;
    for c in compiled {
        session.add(c.clone())?;
    }
    Ok(session)
}

type ServeResult = Result<Option<Rebuild>, (EditorError, Option<PendingEdit>)>;

/// Serves requests with one basis until the basis size changes (returns the rebuild) or every
/// handle is gone (returns `None`).
fn serve(
    state: &mut State,
    basis: &ReducedBasis,
    rebuild: Rebuild,
    inbox: &Receiver<Request>,
    started: &mut Option<Sender<Result<(), EditorError>>>,
) -> ServeResult {
    let Rebuild { target, edit } = rebuild;
    let basis32 = basis.to_f32();
    let compiled = match compile_all(state, &target.constraints) {
        Ok(c) => c,
        Err(e) => return Err((e, edit)),
    };
    let mut session = match build_session(basis, target.omega, &compiled) {
        Ok(s) => s,
        Err(e) => return Err((e, edit)),
    };
    state.current = target;
    state.compiled = compiled;
    refresh(state, &session, &basis32);
    if let Some(edit) = edit {
        if edit.record {
            push_history(state, edit.previous);
        }
        let _ = edit.reply.send(Ok(frame(state, basis)));
    }
    if let Some(s) = started.take() {
        let _ = s.send(Ok(()));
    }
    while let Ok(request) = inbox.recv() {
        match request {
            Request::Edit(op, reply) => {
                let gesture = op.gesture_key();
                let record = gesture.is_none() || gesture != state.last_gesture;
                state.last_gesture = gesture;
                match op {
                    EditOp::BasisSize(d) if d != state.current.basis_size => {
                        if d == 0 || d > state.max_basis_size {
                            let _ = reply.send(Err(EditorError::BadBasisSize {
                                requested: d,
                                available: state.max_basis_size,
                            }));
                            continue;
                        }
                        let target = Snapshot {
                            basis_size: d,
                            ..state.current.clone()
                        };
                        return Ok(Some(rebuild_to(state, target, record, reply)));
                    }
                    EditOp::Undo => match state.history.pop() {
                        None => {
                            let _ = reply.send(Err(EditorError::NothingToUndo));
                        }
                        Some(previous) if previous.basis_size != state.current.basis_size => {
                            return Ok(Some(rebuild_to(state, previous, false, reply)));
                        }
                        Some(previous) => {
                            let outcome = sync(state, &mut session, basis, previous);
                            answer(state, &mut session, basis, &basis32, outcome, None, reply);
                        }
                    },
                    op => {
                        let before = state.current.clone();
                        let outcome = apply(state, &mut session, basis, op);
                        let record = record.then_some(before);
                        answer(state, &mut session, basis, &basis32, outcome, record, reply);
                    }
                }
            }
            Request::Frame(reply) => {
                let _ = reply.send(Ok(frame(state, basis)));
            }
            Request::ConstraintSet(reply) => {
                let set = ConstraintSet {
                    omega: state.current.omega,
                    constraints: state.current.constraints.clone(),
                    mesh_fingerprint: None,
                };
                let _ = reply.send(Ok(set.to_json()));
            }
            Request::Check(reply) => {
                let _ = reply.send(check(state, &session, basis));
            }
            Request::FaceVectors(reply) => {
                let field: Vec<f64> = state.field32.iter().map(|&x| f64::from(x)).collect();
                let vectors = state
                    .complex
                    .fields()
                    .to_vectors(&field)
                    .map_err(|e| EditorError::Discretization(e.to_string()));
                let _ = reply.send(vectors);
            }
        }
    }
    Ok(None)
}

fn rebuild_to(state: &State, target: Snapshot, record: bool, reply: Reply<Vec<u8>>) -> Rebuild {
    Rebuild {
        target,
        edit: Some(PendingEdit {
            previous: state.current.clone(),
            record,
            reply,
        }),
    }
}

fn push_history(state: &mut State, snapshot: Snapshot) {
    if state.history.len() == HISTORY_LIMIT {
        state.history.remove(0);
    }
    state.history.push(snapshot);
}

/// After an in-place edit: on success records the previous state (if asked), re-solves and
/// replies with the new frame; on failure restores the session from the unchanged state and
/// replies with the error.
fn answer<'b>(
    state: &mut State,
    session: &mut SplineSession<'b>,
    basis: &'b ReducedBasis,
    basis32: &ReducedBasisF32,
    outcome: Result<(), EditorError>,
    record: Option<Snapshot>,
    reply: Reply<Vec<u8>>,
) {
    match outcome {
        Ok(()) => {
            if let Some(previous) = record {
                push_history(state, previous);
            }
            refresh(state, session, basis32);
            let _ = reply.send(Ok(frame(state, basis)));
        }
        Err(error) => {
            state.last_gesture = None;
            // A multi-step edit (undo, load) may have failed half-way: rebuild from the
            // unchanged state, which was accepted before, so this succeeds.
            if let Ok(s) = build_session(basis, state.current.omega, &state.compiled) {
                *session = s;
            }
            let _ = reply.send(Err(error));
        }
    }
}

fn compile_all(state: &State, constraints: &[Constraint]) -> Result<Vec<CompiledConstraint>, EditorError> {
    constraints
        .iter()
        .map(|c| state.assembler.compile(c).map_err(EditorError::from))
        .collect()
}

fn index_of(state: &State, id: &str) -> Result<usize, EditorError> {
    state
        .current
        .constraints
        .iter()
        .position(|c| c.id == id)
        .ok_or_else(|| tvf_design::DesignError::UnknownId { id: id.to_string() }.into())
}

/// Applies an edit that keeps the basis. The state changes only if the session accepted it.
fn apply<'b>(
    state: &mut State,
    session: &mut SplineSession<'b>,
    basis: &'b ReducedBasis,
    op: EditOp,
) -> Result<(), EditorError> {
    match op {
        EditOp::Add(c) => {
            let compiled = state.assembler.compile(&c)?;
            session.add(compiled.clone())?;
            state.current.constraints.push(c);
            state.compiled.push(compiled);
        }
        EditOp::Set(c) => {
            let i = index_of(state, &c.id)?;
            let compiled = state.assembler.compile(&c)?;
            session.modify(compiled.clone())?;
            state.current.constraints[i] = c;
            state.compiled[i] = compiled;
        }
        EditOp::Remove(id) => {
            let i = index_of(state, &id)?;
            session.remove(&id)?;
            state.current.constraints.remove(i);
            state.compiled.remove(i);
        }
        EditOp::Clear => {
            *session = SplineSession::new(basis, state.current.omega)?;
            state.current.constraints.clear();
            state.compiled.clear();
        }
        EditOp::Omega(omega) => {
            *session = build_session(basis, omega, &state.compiled)?;
            state.current.omega = omega;
        }
        EditOp::Load(set) => {
            let compiled = compile_all(state, &set.constraints)?;
            *session = build_session(basis, set.omega, &compiled)?;
            state.current.constraints = set.constraints;
            state.current.omega = set.omega;
            state.compiled = compiled;
        }
        EditOp::BasisSize(_) | EditOp::Undo => {}
    }
    Ok(())
}

/// Brings the session to `target` (same basis size) with as little work as possible: value
/// changes re-solve only, other differences add, remove or modify single constraints; a new ω
/// rebuilds.
fn sync<'b>(
    state: &mut State,
    session: &mut SplineSession<'b>,
    basis: &'b ReducedBasis,
    target: Snapshot,
) -> Result<(), EditorError> {
    let compiled = compile_all(state, &target.constraints)?;
    if target.omega != state.current.omega {
        *session = build_session(basis, target.omega, &compiled)?;
    } else {
        for c in &state.current.constraints {
            if !target.constraints.iter().any(|t| t.id == c.id) {
                session.remove(&c.id)?;
            }
        }
        for (c, cc) in target.constraints.iter().zip(&compiled) {
            match state.current.constraints.iter().find(|o| o.id == c.id) {
                Some(old) if old == c => {}
                Some(_) => session.modify(cc.clone())?,
                None => session.add(cc.clone())?,
            }
        }
    }
    state.current = target;
    state.compiled = compiled;
    Ok(())
}

/// Solves the session and maps the coefficients to the `f32` field.
fn refresh(state: &mut State, session: &SplineSession, basis32: &ReducedBasisF32) {
    let start = Instant::now();
    state.coefficients = session.solve();
    let mapped = Instant::now();
    let v32: Vec<f32> = state.coefficients.iter().map(|&x| x as f32).collect();
    // Both lengths come from the same basis and mesh, so the map cannot fail.
    let _ = basis32.map(&v32, &mut state.field32);
    state.solve_ms = (mapped - start).as_secs_f64() * 1e3;
    state.map_ms = mapped.elapsed().as_secs_f64() * 1e3;
    state.version += 1;
}

fn status(state: &State, basis: &ReducedBasis) -> Status {
    Status {
        version: state.version,
        omega: state.current.omega,
        basis_size: state.current.basis_size,
        max_basis_size: state.max_basis_size,
        faces: state.face_count,
        constraints: constraint_records(&state.current.constraints, state.current.omega),
        anchors: state.current.constraints.iter().map(|c| state.anchors.of(c)).collect(),
        residual: reduced_residual(basis, &state.coefficients, &state.compiled),
        solve_ms: state.solve_ms,
        map_ms: state.map_ms,
        undo_depth: state.history.len(),
    }
}

fn frame(state: &State, basis: &ReducedBasis) -> Vec<u8> {
    // Serialising plain numbers, strings and JSON values cannot fail.
    let json = serde_json::to_string(&status(state, basis)).unwrap_or_default();
    encode_field_frame(&json, &state.field32)
}

fn check(state: &State, session: &SplineSession, basis: &ReducedBasis) -> Result<CheckReport, EditorError> {
    let mut field = vec![0.0; basis.field_dimension()];
    basis.map(&state.coefficients, &mut field)?;
    let constraints: Vec<CheckedConstraint> = session
        .residuals(&field)
        .into_iter()
        .map(|r| CheckedConstraint {
            id: r.id,
            absolute: r.absolute,
            relative: r.relative,
        })
        .collect();
    let max_relative = constraints.iter().fold(0.0f64, |m, c| m.max(c.relative));
    let largest = field.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let deviation = field
        .iter()
        .zip(&state.field32)
        .fold(0.0f64, |m, (x, y)| m.max((x - f64::from(*y)).abs()));
    Ok(CheckReport {
        version: state.version,
        constraints,
        max_relative,
        f32_deviation: if largest > 0.0 { deviation / largest } else { 0.0 },
    })
}
