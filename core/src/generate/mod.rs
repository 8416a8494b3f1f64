//! Meshes generated in code: no files needed for tests and demos.

mod icosphere;
mod torus;

pub use icosphere::icosphere;
pub use torus::torus;
