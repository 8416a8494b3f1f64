//! The editing engine behind [`crate::Editor`]: one thread owns the basis, the operators and
//! the [`SplineSession`]; requests from the HTTP threads reach it over a channel, so edits are
//! applied one at a time, in order.
//!
//! A value change (`set` of a constraint at the same place) only re-solves the session
//! (`SplineSession::modify` keeps the factorisation); adding, removing or moving a constraint
//! borders or downdates the factorisation; ω rebuilds it (the energy changes) and a new basis
//! size rebuilds it on the first `d` fields.

use std::sync::mpsc::{Receiver, Sender};
use std::time::Instant;

use sprs::CsMat;
use tvf_core::discretization::sparse::{from_triplets, mul_vec};
use tvf_core::discretization::{HodgeComplex, HodgeOperators, NodeKind};
use tvf_core::SurfaceMesh;
use tvf_design::{
    checked_residuals, CompiledConstraint, Constraint, ConstraintAssembler, ConstraintSet,
    ReducedBasis, SplineSession,
};

use crate::edit_op::EditOp;
use crate::error::EditorError;
use crate::field_mapper::FieldMapper;
use crate::payload::encode_field_frame;
use crate::status::{
    constraint_records, reduced_residual, Anchors, CheckReport, CheckedConstraint, Status,
};

pub(crate) type Reply<T> = Sender<Result<T, EditorError>>;

pub(crate) enum Request {
    Edit(EditOp, Reply<Vec<u8>>),
    Frame(Reply<Vec<u8>>),
    ConstraintSet(Reply<String>),
    Check(Reply<CheckReport>),
    FaceVectors(Reply<Vec<[f64; 3]>>),
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Snapshot {
    pub(crate) constraints: Vec<Constraint>,
    pub(crate) omega: f64,
    pub(crate) basis_size: usize,
}

/// Most undo steps kept.
const HISTORY_LIMIT: usize = 500;

/// The engine's state that outlives a basis size.
struct State<'c> {
    complex: &'c dyn HodgeComplex,
    assembler: ConstraintAssembler<'c, dyn HodgeComplex + 'c>,
    /// Face-frame coefficients (`2F × n1`) of the field sampled at the face centroids, for
    /// discretizations whose coefficients are not already that (the page draws `2F` values).
    display: Option<CsMat<f64>>,
    display32: Vec<f32>,
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
    update: &'static str,
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

pub(crate) fn run_engine(
    mesh: &SurfaceMesh,
    complex: &dyn HodgeComplex,
    full: ReducedBasis,
    initial: Snapshot,
    inbox: Receiver<Request>,
    started: Sender<Result<(), EditorError>>,
) {
    let mut state = State {
        complex,
        assembler: ConstraintAssembler::new(complex, mesh),
        display: display_map(complex),
        display32: vec![0.0; 2 * mesh.face_count()],
        anchors: Anchors::new(mesh),
        max_basis_size: full.len(),
        face_count: mesh.face_count(),
        current: initial.clone(),
        compiled: Vec::new(),
        history: Vec::new(),
        last_gesture: None,
        version: 0,
        coefficients: vec![0.0; full.len()],
        field32: vec![0.0; complex.field_dimension()],
        solve_ms: 0.0,
        map_ms: 0.0,
        update: "mapped",
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
            Served::Rebuild(next) => rebuild = next,
            Served::Closed => return,
            Served::Failed(error, edit) => {
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

/// The first `d` fields of `basis` ([`ReducedBasis::first_fields`]).
fn truncate(basis: &ReducedBasis, d: usize) -> Result<ReducedBasis, EditorError> {
    Ok(basis.first_fields(d)?)
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

/// How [`serve`] ended: every handle is gone, the basis size changes, or building the session
/// for the new state failed (with the edit waiting for the answer, if any).
enum Served {
    Closed,
    Rebuild(Rebuild),
    Failed(EditorError, Option<PendingEdit>),
}

/// Serves requests with one basis until the basis size changes (returns the rebuild), every
/// handle is gone, or the session for the new state cannot be built.
fn serve(
    state: &mut State,
    basis: &ReducedBasis,
    rebuild: Rebuild,
    inbox: &Receiver<Request>,
    started: &mut Option<Sender<Result<(), EditorError>>>,
) -> Served {
    let mut mapper = match FieldMapper::new(basis) {
        Ok(mapper) => mapper,
        Err(error) => return Served::Failed(error.into(), rebuild.edit),
    };
    let mut session = match open_session(state, basis, &mut mapper, rebuild, started) {
        Ok(session) => session,
        Err(failed) => return *failed,
    };
    while let Ok(request) = inbox.recv() {
        match request {
            Request::Edit(op, reply) => {
                let mut editing = Editing {
                    session: &mut session,
                    basis,
                    mapper: &mut mapper,
                };
                if let Some(rebuild) = editing.edit(state, op, reply) {
                    return Served::Rebuild(rebuild);
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
                let _ = reply.send(check(state, basis));
            }
            Request::FaceVectors(reply) => {
                let field: Vec<f64> = state.field32.iter().map(|&x| f64::from(x)).collect();
                let vectors = state
                    .complex
                    .require_sampling()
                    .and_then(|sampling| sampling.to_face_vectors(&field))
                    .map_err(|e| EditorError::Discretization(e.to_string()));
                let _ = reply.send(vectors);
            }
        }
    }
    Served::Closed
}

/// The session of `basis` for the state `rebuild` leads to, made current and solved; answers
/// the edit that asked for the rebuild (if any) and tells a starting engine that it runs. On
/// failure, what [`serve`] returns (boxed: an error and a waiting edit are large).
fn open_session<'b>(
    state: &mut State,
    basis: &'b ReducedBasis,
    mapper: &mut FieldMapper,
    rebuild: Rebuild,
    started: &mut Option<Sender<Result<(), EditorError>>>,
) -> Result<SplineSession<'b>, Box<Served>> {
    let Rebuild { target, edit } = rebuild;
    let compiled = match compile_all(state, &target.constraints) {
        Ok(c) => c,
        Err(e) => return Err(Box::new(Served::Failed(e, edit))),
    };
    let mut session = match build_session(basis, target.omega, &compiled) {
        Ok(s) => s,
        Err(e) => return Err(Box::new(Served::Failed(e, edit))),
    };
    // Going back to the state before a refused basis-size change (no edit waits, and the
    // engine has started) shows the same field again: it keeps its version.
    let restoring = edit.is_none() && started.is_none();
    let version = state.version;
    state.current = target;
    state.compiled = compiled;
    refresh(state, &mut session, mapper, None);
    if restoring {
        state.version = version;
    }
    if let Some(edit) = edit {
        if edit.record {
            push_history(state, edit.previous);
        }
        let _ = edit.reply.send(Ok(frame(state, basis)));
    }
    if let Some(s) = started.take() {
        let _ = s.send(Ok(()));
    }
    Ok(session)
}

/// What an edit works on besides the state: the session of the current basis, the basis and
/// the field mapper.
struct Editing<'s, 'b> {
    session: &'s mut SplineSession<'b>,
    basis: &'b ReducedBasis,
    mapper: &'s mut FieldMapper,
}

impl Editing<'_, '_> {
    /// Applies `op` and replies; returns the rebuild when the edit changes the basis size (the
    /// reply then waits for it).
    fn edit(&mut self, state: &mut State, op: EditOp, reply: Reply<Vec<u8>>) -> Option<Rebuild> {
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
                    return None;
                }
                let target = Snapshot {
                    basis_size: d,
                    ..state.current.clone()
                };
                Some(rebuild_to(state, target, record, reply))
            }
            EditOp::Undo => match state.history.pop() {
                None => {
                    let _ = reply.send(Err(EditorError::NothingToUndo));
                    None
                }
                Some(previous) if previous.basis_size != state.current.basis_size => {
                    Some(rebuild_to(state, previous, false, reply))
                }
                Some(previous) => {
                    let outcome = self.sync(state, previous);
                    self.answer(state, outcome, None, reply);
                    None
                }
            },
            op => {
                let before = state.current.clone();
                let outcome = self
                    .apply(state, op)
                    .and_then(|v| self.refuse_non_finite(state, before.clone()).map(|()| v));
                let record = record.then_some(before);
                self.answer(state, outcome, record, reply);
                None
            }
        }
    }

    /// After an in-place edit: on success records the previous state (if asked), re-solves and
    /// replies with the new frame; on failure restores the session from the unchanged state and
    /// replies with the error.
    fn answer(
        &mut self,
        state: &mut State,
        outcome: Result<Option<usize>, EditorError>,
        record: Option<Snapshot>,
        reply: Reply<Vec<u8>>,
    ) {
        match outcome {
            Ok(values_of) => {
                if let Some(previous) = record {
                    push_history(state, previous);
                }
                refresh(state, self.session, self.mapper, values_of);
                let _ = reply.send(Ok(frame(state, self.basis)));
            }
            Err(error) => {
                state.last_gesture = None;
                // A multi-step edit (undo, load) may have failed half-way: rebuild from the
                // unchanged state, which was accepted before, so this succeeds.
                if let Ok(s) = build_session(self.basis, state.current.omega, &state.compiled) {
                    *self.session = s;
                }
                let _ = reply.send(Err(error));
            }
        }
    }

    /// Applies an edit that keeps the basis. The state changes only if the session accepted it.
    /// Returns the index of the constraint if only its values changed.
    fn apply(&mut self, state: &mut State, op: EditOp) -> Result<Option<usize>, EditorError> {
        match op {
            EditOp::Add(c) => {
                let compiled = state.assembler.compile(&c)?;
                self.session.add(compiled.clone())?;
                state.current.constraints.push(c);
                state.compiled.push(compiled);
            }
            EditOp::Set(c) => {
                let i = index_of(state, &c.id)?;
                let compiled = state.assembler.compile(&c)?;
                let values_only = state.compiled[i].rows == compiled.rows;
                self.session.modify(compiled.clone())?;
                state.current.constraints[i] = c;
                state.compiled[i] = compiled;
                return Ok(values_only.then_some(i));
            }
            EditOp::Remove(id) => {
                let i = index_of(state, &id)?;
                self.session.remove(&id)?;
                state.current.constraints.remove(i);
                state.compiled.remove(i);
            }
            EditOp::Clear => {
                *self.session = SplineSession::new(self.basis, state.current.omega)?;
                state.current.constraints.clear();
                state.compiled.clear();
            }
            EditOp::Omega(omega) => {
                *self.session = build_session(self.basis, omega, &state.compiled)?;
                state.current.omega = omega;
            }
            EditOp::Load(set) => {
                let compiled = compile_all(state, &set.constraints)?;
                *self.session = build_session(self.basis, set.omega, &compiled)?;
                state.current.constraints = set.constraints;
                state.current.omega = set.omega;
                state.compiled = compiled;
            }
            EditOp::BasisSize(_) | EditOp::Undo => {}
        }
        Ok(None)
    }

    /// Brings the session to `target` (same basis size) with as little work as possible: value
    /// changes re-solve only, other differences add, remove or modify single constraints; a new ω
    /// rebuilds.
    fn sync(&mut self, state: &mut State, target: Snapshot) -> Result<Option<usize>, EditorError> {
        let compiled = compile_all(state, &target.constraints)?;
        if target.omega != state.current.omega {
            *self.session = build_session(self.basis, target.omega, &compiled)?;
        } else {
            for c in &state.current.constraints {
                if !target.constraints.iter().any(|t| t.id == c.id) {
                    self.session.remove(&c.id)?;
                }
            }
            for (c, cc) in target.constraints.iter().zip(&compiled) {
                match state.current.constraints.iter().find(|o| o.id == c.id) {
                    Some(old) if old == c => {}
                    Some(_) => self.session.modify(cc.clone())?,
                    None => self.session.add(cc.clone())?,
                }
            }
        }
        state.current = target;
        state.compiled = compiled;
        Ok(None)
    }

    /// After an edit was applied: if the session's solution is NaN or infinite (values or ω so
    /// large that `f64` arithmetic overflows), goes back to `before` and returns the error naming
    /// the constraint, so the editor never holds or shows a non-finite field.
    fn refuse_non_finite(
        &mut self,
        state: &mut State,
        before: Snapshot,
    ) -> Result<(), EditorError> {
        let coefficients = self.session.solve();
        if coefficients.iter().all(|x| x.is_finite()) {
            return Ok(());
        }
        let mut field = vec![0.0; self.basis.field_dimension()];
        self.basis.map(&coefficients, &mut field)?;
        let error = match checked_residuals(&field, &state.compiled, state.current.omega) {
            Err(error) => EditorError::from(error),
            Ok(_) => EditorError::Design(tvf_design::DesignError::NotFinite {
                id: String::new(),
                problem: "the solved field is not finite".into(),
                cause: format!("omega is {:e}", state.current.omega),
            }),
        };
        self.sync(state, before)?;
        Err(error)
    }
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

fn compile_all(
    state: &State,
    constraints: &[Constraint],
) -> Result<Vec<CompiledConstraint>, EditorError> {
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

/// Solves the session and maps the coefficients to the `f32` field: through the drag cache
/// when only the values of constraint `values_of` changed, otherwise by a full pass over `U`.
fn refresh(
    state: &mut State,
    session: &mut SplineSession,
    mapper: &mut FieldMapper,
    values_of: Option<usize>,
) {
    let start = Instant::now();
    state.coefficients = session.solve();
    let solved = Instant::now();
    state.update = match values_of {
        Some(i) => {
            let c = &state.compiled[i];
            match mapper.update_values(
                session,
                &c.id,
                &c.values,
                &state.coefficients,
                &mut state.field32,
            ) {
                Ok(true) => "cached",
                Ok(false) => "cache built",
                Err(_) => {
                    mapper.map(&state.coefficients, &mut state.field32);
                    "mapped"
                }
            }
        }
        None => {
            mapper.map(&state.coefficients, &mut state.field32);
            "mapped"
        }
    };
    if let Some(display) = &state.display {
        let field: Vec<f64> = state.field32.iter().map(|&x| f64::from(x)).collect();
        let sampled = mul_vec(display, &field);
        state.display32 = sampled.iter().map(|&x| x as f32).collect();
    }
    state.solve_ms = (solved - start).as_secs_f64() * 1e3;
    state.map_ms = solved.elapsed().as_secs_f64() * 1e3;
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
        anchors: state
            .current
            .constraints
            .iter()
            .map(|c| state.anchors.of(c))
            .collect(),
        residual: reduced_residual(basis, &state.coefficients, &state.compiled),
        solve_ms: state.solve_ms,
        map_ms: state.map_ms,
        update: state.update,
        undo_depth: state.history.len(),
    }
}

fn frame(state: &State, basis: &ReducedBasis) -> Vec<u8> {
    // Serialising plain numbers, strings and JSON values cannot fail.
    let json = serde_json::to_string(&status(state, basis)).unwrap_or_default();
    match state.display {
        Some(_) => encode_field_frame(&json, &state.display32),
        None => encode_field_frame(&json, &state.field32),
    }
}

/// The held field mapped in `f64` and checked against every constraint; a NaN or infinite
/// field or residual is an error naming the constraint.
fn check(state: &State, basis: &ReducedBasis) -> Result<CheckReport, EditorError> {
    let mut field = vec![0.0; basis.field_dimension()];
    basis.map(&state.coefficients, &mut field)?;
    let constraints: Vec<CheckedConstraint> =
        checked_residuals(&field, &state.compiled, state.current.omega)?
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
        f32_deviation: if largest > 0.0 {
            deviation / largest
        } else {
            0.0
        },
    })
}

/// The map from a discretization's field coefficients to face-frame coefficients at the face
/// centroids (`2F × n1`), or `None` when the coefficients already are that.
fn display_map(complex: &dyn HodgeComplex) -> Option<CsMat<f64>> {
    if complex.field_nodes().kind == NodeKind::FaceFrames {
        return None;
    }
    let sampling = complex.sampling()?;
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for t in 0..sampling.face_count() {
        for (i, w) in sampling.sample_frame_weights(&sampling.centroid(t)) {
            for (k, &wk) in w.iter().enumerate() {
                rows.push(2 * t + k);
                cols.push(i);
                values.push(wk);
            }
        }
    }
    Some(from_triplets(
        2 * sampling.face_count(),
        complex.field_dimension(),
        rows,
        cols,
        values,
    ))
}
