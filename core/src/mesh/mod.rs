//! Triangle meshes: the [`SurfaceMesh`] type, its topology and its errors.

mod error;
mod fingerprint;
mod geometry_range;
mod quality;
mod surface_mesh;
mod topology;
mod validate;
mod validation_report;

pub use error::MeshError;
pub use geometry_range::GeometryRangeError;
pub use quality::triangle_angles;
pub use surface_mesh::{SurfaceMesh, NO_FACE};
pub use validate::check_faces;
pub use validation_report::{ValidationReport, ValidationWarning, SMALL_ANGLE_DEG};
