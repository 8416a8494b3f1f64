//! Triangle meshes: the [`TriangleMesh`] type, its topology and its errors.

mod error;
mod fingerprint;
mod geometry_range;
mod quality;
mod topology;
mod triangle_mesh;
mod validate;
mod validation_report;

pub use error::MeshError;
pub use geometry_range::GeometryRangeError;
pub use quality::triangle_angles;
pub use triangle_mesh::{TriangleMesh, NO_FACE};
pub use validate::check_faces;
pub use validation_report::{ValidationReport, ValidationWarning, SMALL_ANGLE_DEG};
