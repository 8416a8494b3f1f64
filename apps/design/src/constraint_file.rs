//! The JSON constraint-set format (see README "Constraint files"):
//!
//! ```json
//! {"omega": 0.1,
//!  "mesh_fingerprint": "optional, checked if present",
//!  "constraints": [
//!   {"id": "a", "kind": "vector", "face": 12, "value": [1.0, 0.0, 0.0]},
//!   {"id": "b", "kind": "vector", "face": 30, "barycentric": [0.2, 0.3, 0.5], "value": [0, 1, 0]},
//!   {"id": "c", "kind": "divergence", "vertex": 5, "value": 2.0, "weight": 10.0},
//!   {"id": "d", "kind": "curl", "edge": 7, "value": -1.0},
//!   {"id": "e", "kind": "curl", "face": 3, "barycentric": [0.3, 0.3, 0.4], "value": 1.0,
//!    "family": "other"}]}
//! ```
//!
//! Parsing checks the shape of every record (kind, value shape, exactly one of
//! `face`/`vertex`/`edge`, barycentric only with `face`, finite values, positive weights, unique
//! ids, non-negative indices); [`crate::ConstraintAssembler`] then checks indices against a mesh.

use crate::assembler::check_barycentric;
use crate::constraint::{Constraint, Location, OperatorFamily, Target};
use crate::error::{ConstraintError, ConstraintFileError};
use serde::{Deserialize, Serialize};
use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// Largest constraint file read (64 MiB: hundreds of thousands of constraints).
pub const MAX_CONSTRAINT_FILE_BYTES: u64 = 64 << 20;

/// Default `omega` when a file does not give one.
pub const DEFAULT_OMEGA: f64 = 0.1;

/// A parsed and validated constraint set.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstraintSet {
    /// Weight `ω ≥ 0` of the second energy term (spline: `E_B + ω E_D`; soft design:
    /// `E_D + ω E_B`).
    pub omega: f64,
    /// The constraints, in file order, ids unique.
    pub constraints: Vec<Constraint>,
    /// Fingerprint of the mesh the file was written for, if given.
    pub mesh_fingerprint: Option<String>,
}

/// A scalar or a 3-vector, as written in JSON.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(untagged)]
enum ValueRecord {
    Scalar(f64),
    Vector([f64; 3]),
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ConstraintRecord {
    id: String,
    kind: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    face: Option<i64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    vertex: Option<i64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    edge: Option<i64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    barycentric: Option<Vec<f64>>,
    value: ValueRecord,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    weight: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    family: Option<String>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SetRecord {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    omega: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    mesh_fingerprint: Option<String>,
    constraints: Vec<ConstraintRecord>,
}

impl ConstraintSet {
    /// Reads and validates a constraint file; errors name the file (and the constraint id).
    pub fn load(path: impl AsRef<Path>) -> Result<Self, ConstraintFileError> {
        let path = path.as_ref();
        let io = |source| ConstraintFileError::Io {
            path: path.to_path_buf(),
            source,
        };
        let bytes = tvf_core::io::read_at_most(path, MAX_CONSTRAINT_FILE_BYTES).map_err(io)?;
        let text = String::from_utf8(bytes).map_err(|_| {
            io(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                "not UTF-8 text",
            ))
        })?;
        Self::parse(&text, path)
    }

    /// Parses and validates JSON text (a leading UTF-8 byte-order mark, as some editors write,
    /// is skipped); `origin` names the source in errors.
    pub fn parse(text: &str, origin: &Path) -> Result<Self, ConstraintFileError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let record: SetRecord =
            serde_json::from_str(text).map_err(|source| ConstraintFileError::Json {
                path: origin.to_path_buf(),
                source,
            })?;
        let omega = record.omega.unwrap_or(DEFAULT_OMEGA);
        if !(omega.is_finite() && omega >= 0.0) {
            return Err(ConstraintFileError::BadOmega {
                path: origin.to_path_buf(),
                omega,
            });
        }
        let invalid = |source| ConstraintFileError::Invalid {
            path: origin.to_path_buf(),
            source,
        };
        let mut seen = HashSet::new();
        let mut constraints = Vec::with_capacity(record.constraints.len());
        for (position, c) in record.constraints.iter().enumerate() {
            if c.id.trim().is_empty() || c.id.chars().any(char::is_control) {
                return Err(invalid(ConstraintError::BadId {
                    position,
                    id: c.id.clone(),
                }));
            }
            if !seen.insert(c.id.clone()) {
                return Err(invalid(ConstraintError::DuplicateId { id: c.id.clone() }));
            }
            constraints.push(to_constraint(c).map_err(invalid)?);
        }
        Ok(Self {
            omega,
            constraints,
            mesh_fingerprint: record.mesh_fingerprint,
        })
    }

    /// Checks the file's fingerprint (if any) against the mesh's; `origin` names the file.
    pub fn check_fingerprint(
        &self,
        actual: &str,
        origin: &Path,
    ) -> Result<(), ConstraintFileError> {
        match &self.mesh_fingerprint {
            Some(expected) if expected != actual => Err(ConstraintFileError::FingerprintMismatch {
                path: PathBuf::from(origin),
                expected: expected.clone(),
                actual: actual.to_string(),
            }),
            _ => Ok(()),
        }
    }

    /// The set as JSON text in the documented format (round-trips through [`ConstraintSet::parse`]).
    pub fn to_json(&self) -> String {
        let record = SetRecord {
            omega: Some(self.omega),
            mesh_fingerprint: self.mesh_fingerprint.clone(),
            constraints: self.constraints.iter().map(to_record).collect(),
        };
        // Serialising plain records of strings, integers and finite floats cannot fail.
        serde_json::to_string_pretty(&record).unwrap_or_default()
    }
}

fn to_constraint(c: &ConstraintRecord) -> Result<Constraint, ConstraintError> {
    let id = &c.id;
    let bad_value = |kind, expected| ConstraintError::BadValue {
        id: id.clone(),
        kind,
        expected,
    };
    let target = match (c.kind.as_str(), &c.value) {
        ("vector", ValueRecord::Vector(v)) => Target::Vector(*v),
        ("vector", _) => return Err(bad_value("vector", "a value [x, y, z]")),
        ("divergence", ValueRecord::Scalar(s)) => Target::Divergence(*s),
        ("curl", ValueRecord::Scalar(s)) => Target::Curl(*s),
        ("divergence", _) => return Err(bad_value("divergence", "a number as value")),
        ("curl", _) => return Err(bad_value("curl", "a number as value")),
        (other, _) => {
            return Err(ConstraintError::UnknownKind {
                id: id.clone(),
                kind: other.to_string(),
            })
        }
    };
    if !target.is_finite() {
        return Err(ConstraintError::NotFinite {
            id: id.clone(),
            what: "value",
            extra: "",
        });
    }
    let weight = c.weight.unwrap_or(1.0);
    if !(weight.is_finite() && weight > 0.0) {
        return Err(ConstraintError::NotFinite {
            id: id.clone(),
            what: "weight",
            extra: " and positive",
        });
    }
    let family = match c.family.as_deref() {
        None | Some("decomposition") => OperatorFamily::Decomposition,
        Some("other") => OperatorFamily::Other,
        Some(other) => {
            return Err(ConstraintError::UnknownFamily {
                id: id.clone(),
                family: other.to_string(),
            })
        }
    };
    let location = location_of(c)?;
    if matches!(target, Target::Vector(_)) && !matches!(location, Location::Face { .. }) {
        return Err(ConstraintError::BadLocation {
            id: id.clone(),
            problem: "a vector constraint needs a \"face\" (vectors are constant per face)".into(),
        });
    }
    Ok(Constraint {
        id: id.clone(),
        target,
        location,
        family,
        weight,
    })
}

fn location_of(c: &ConstraintRecord) -> Result<Location, ConstraintError> {
    let id = &c.id;
    let index = |what: &'static str, i: i64| {
        usize::try_from(i).map_err(|_| ConstraintError::NegativeIndex {
            id: id.clone(),
            what,
            index: i,
        })
    };
    let bad = |problem: &str| ConstraintError::BadLocation {
        id: id.clone(),
        problem: problem.to_string(),
    };
    if let Some(b) = &c.barycentric {
        if c.face.is_none() {
            return Err(bad("\"barycentric\" needs a \"face\""));
        }
        check_barycentric(id, b)?;
    }
    match (c.face, c.vertex, c.edge) {
        (Some(f), None, None) => Ok(Location::Face {
            face: index("face", f)?,
            barycentric: c.barycentric.clone(),
        }),
        (None, Some(v), None) => Ok(Location::Vertex(index("vertex", v)?)),
        (None, None, Some(e)) => Ok(Location::Edge(index("edge", e)?)),
        (None, None, None) => Err(bad("needs one of \"face\", \"vertex\" or \"edge\"")),
        _ => Err(bad("give exactly one of \"face\", \"vertex\" or \"edge\"")),
    }
}

fn to_record(c: &Constraint) -> ConstraintRecord {
    let as_i64 = |i: usize| i64::try_from(i).unwrap_or(i64::MAX);
    let (face, vertex, edge, barycentric) = match &c.location {
        Location::Face { face, barycentric } => {
            (Some(as_i64(*face)), None, None, barycentric.clone())
        }
        Location::Vertex(v) => (None, Some(as_i64(*v)), None, None),
        Location::Edge(e) => (None, None, Some(as_i64(*e)), None),
    };
    let value = match c.target {
        Target::Vector(v) => ValueRecord::Vector(v),
        Target::Divergence(s) | Target::Curl(s) => ValueRecord::Scalar(s),
    };
    ConstraintRecord {
        id: c.id.clone(),
        kind: c.target.kind_name().to_string(),
        face,
        vertex,
        edge,
        barycentric,
        value,
        weight: (c.weight != 1.0).then_some(c.weight),
        family: (c.family == OperatorFamily::Other).then(|| "other".to_string()),
    }
}
