//! [`EditOp`]: the edits the page sends as JSON in `POST /api/edit`.

use crate::error::EditorError;
use serde::Deserialize;
use std::path::Path;
use tvf_design::{Constraint, ConstraintSet};

/// One edit. JSON: `{"op": "add", "constraint": {...}}`, `{"op": "set", "constraint": {...}}`,
/// `{"op": "remove", "id": "a"}`, `{"op": "omega", "value": 0.1}`,
/// `{"op": "basis_size", "value": 100}`, `{"op": "load", "set": {...}}`, `{"op": "clear"}`,
/// `{"op": "undo"}`. Constraint records and sets use the constraint-file format of tvf-design.
#[derive(Debug, Clone, PartialEq)]
pub enum EditOp {
    /// Adds a constraint with a new id.
    Add(Constraint),
    /// Replaces the constraint with the same id (a value-only change when it stays in place).
    Set(Constraint),
    /// Removes a constraint.
    Remove(String),
    /// Sets `ω ≥ 0` (rebuilds the factorisation: the energy changes).
    Omega(f64),
    /// Uses the first `d` fields of the basis.
    BasisSize(usize),
    /// Replaces all constraints and ω by a constraint set.
    Load(ConstraintSet),
    /// Removes all constraints.
    Clear,
    /// Reverts the last edit.
    Undo,
}

#[derive(Deserialize)]
#[serde(tag = "op", rename_all = "snake_case", deny_unknown_fields)]
enum OpRecord {
    Add { constraint: serde_json::Value },
    Set { constraint: serde_json::Value },
    Remove { id: String },
    Omega { value: f64 },
    BasisSize { value: usize },
    Load { set: serde_json::Value },
    // Braces, not unit variants: serde refuses unknown fields only for struct variants.
    Clear {},
    Undo {},
}

impl EditOp {
    /// Parses an edit from the JSON body of a request.
    pub fn parse(body: &[u8]) -> Result<Self, EditorError> {
        let record: OpRecord =
            serde_json::from_slice(body).map_err(|e| EditorError::BadRequest {
                reason: format!("edit JSON: {e}"),
            })?;
        Ok(match record {
            OpRecord::Add { constraint } => EditOp::Add(parse_constraint(constraint)?),
            OpRecord::Set { constraint } => EditOp::Set(parse_constraint(constraint)?),
            OpRecord::Remove { id } => EditOp::Remove(id),
            OpRecord::Omega { value } => EditOp::Omega(value),
            OpRecord::BasisSize { value } => EditOp::BasisSize(value),
            OpRecord::Load { set } => EditOp::Load(ConstraintSet::parse(
                &set.to_string(),
                Path::new("loaded constraint set"),
            )?),
            OpRecord::Clear {} => EditOp::Clear,
            OpRecord::Undo {} => EditOp::Undo,
        })
    }

    /// A key shared by consecutive edits that belong to one gesture (dragging one constraint,
    /// moving a slider): the undo history keeps only the state before the first of them.
    pub fn gesture_key(&self) -> Option<String> {
        match self {
            EditOp::Set(c) => Some(format!("set:{}", c.id)),
            EditOp::Omega(_) => Some("omega".into()),
            EditOp::BasisSize(_) => Some("basis_size".into()),
            _ => None,
        }
    }
}

/// Parses one constraint record (validated as in a constraint file).
fn parse_constraint(record: serde_json::Value) -> Result<Constraint, EditorError> {
    let text = serde_json::json!({ "constraints": [record] }).to_string();
    let mut set = ConstraintSet::parse(&text, Path::new("edit request"))?;
    set.constraints
        .pop()
        .ok_or_else(|| EditorError::BadRequest {
            reason: "missing constraint".into(),
        })
}
