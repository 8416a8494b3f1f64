//! # tvf-editor
//!
//! The interactive spline editor (the paper's Section 7 application): a local HTTP server on
//! 127.0.0.1 that serves a WebGL2 page (embedded in the binary, works offline) and answers every
//! edit of a constraint with the new field, computed by a [`tvf_design::SplineSession`] that is
//! updated incrementally.
//!
//! - [`Editor`]: the editing engine (a thread owning the basis and the session).
//! - [`EditorServer`]: the HTTP server; its endpoints are listed in the [`server`] module, who
//!   may call them in [`access`] (own Host and Origin, session token), the wire format in
//!   [`http`].
//! - [`EditOp`]: the edits, as JSON; [`payload`]: the binary mesh, field and fur payloads.
//!
//! ```
//! use tvf_core::generate::icosphere;
//! use tvf_design::ReducedBasis;
//! use tvf_editor::{decode_field_frame, EditOp, Editor, EditorSetup};
//!
//! let mesh = tvf_core::SurfaceMesh::from(icosphere(1));
//! let complex = tvf_discretizations::build_complex("conforming-barycentric", None, &mesh)?;
//! // A toy basis for the example: the first 12 coordinate fields of the face frames
//! // (a real one comes from tvf_spectral::compute_basis).
//! let n = 2 * mesh.face_count();
//! let d = 12;
//! let rows: Vec<f64> = (0..n * d).map(|k| if k / d == k % d { 1.0 } else { 0.0 }).collect();
//! let eigenvalues: Vec<f64> = (1..=d).map(|i| i as f64).collect();
//! let basis = ReducedBasis::from_row_major(rows, n, eigenvalues, vec![false; d]).unwrap();
//! let editor = Editor::start(EditorSetup {
//!     mesh,
//!     basis,
//!     constraints: None,
//!     basis_size: None,
//!     complex,
//! })?;
//! let op = EditOp::parse(br#"{"op": "add", "constraint":
//!     {"id": "a", "kind": "vector", "face": 2, "value": [1.0, 0.0, 0.0]}}"#).unwrap();
//! let frame = decode_field_frame(&editor.edit(op).unwrap()).unwrap();
//! assert_eq!(frame.status["constraints"].as_array().unwrap().len(), 1);
//! assert!(editor.check().unwrap().max_relative < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

pub mod access;
pub mod assets;
mod edit_op;
mod editor;
mod engine;
mod error;
mod field_mapper;
pub mod http;
pub mod payload;
pub mod server;
mod status;
mod waiting_room;

pub use edit_op::EditOp;
pub use editor::{Editor, EditorSetup};
pub use error::EditorError;
pub use payload::{decode_field_frame, FieldFrame};
pub use server::EditorServer;
pub use status::{Anchor, CheckReport, CheckedConstraint, Status};
