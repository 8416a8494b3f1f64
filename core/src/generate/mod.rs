//! Meshes generated in code: no files needed for tests and demos.

mod bumpy_torus;
mod genus_surface;
mod icosphere;
mod jitter;
mod rigid_motion;
mod torus;

pub use bumpy_torus::bumpy_torus;
pub use genus_surface::genus_surface;
pub use icosphere::icosphere;
pub use jitter::jitter;
pub use rigid_motion::rigid_motion;
pub use torus::torus;
