//! # tvf-core
//!
//! The vocabulary every tvf crate speaks: closed (or bounded) oriented triangle meshes with the
//! topology the discrete operators need, and meshes generated in code for tests and demos.
//!
//! ```
//! use tvf_core::generate::icosphere;
//! let mesh = icosphere(1);
//! assert_eq!(mesh.face_count(), 80);
//! assert_eq!(mesh.genus(), 0);
//! ```
#![warn(missing_docs)]

pub mod discretization;
pub mod generate;
pub mod geometry;
mod hash64;
pub mod intrinsic;
pub mod io;
pub mod mesh;

pub use hash64::Hash64;
pub use mesh::{
    FaceList, MeshError, PolygonMesh, SurfaceMesh, SurfacePoint, TriangleMesh, NO_FACE,
};
pub use mesh::{ValidationReport, ValidationWarning};
