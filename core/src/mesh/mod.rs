//! Triangle meshes: the [`SurfaceMesh`] type, its topology and its errors.

mod error;
mod surface_mesh;
mod topology;

pub use error::MeshError;
pub use surface_mesh::{SurfaceMesh, NO_FACE};
