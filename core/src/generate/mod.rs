//! Meshes generated in code: no files needed for tests and demos.

mod bumpy_torus;
mod examples;
mod genus_surface;
mod icosphere;
mod jitter;
mod open_surfaces;
mod polygon_meshes;
mod quad_grid;
mod rigid_motion;
mod staggered_rings;
mod torus;

pub use bumpy_torus::bumpy_torus;
pub use examples::{example_mesh, EXAMPLE_NAMES};
pub use genus_surface::genus_surface;
pub use icosphere::icosphere;
pub use jitter::jitter;
pub use open_surfaces::{disk, hemisphere, holed_torus, open_cylinder, perforated_plate};
pub use polygon_meshes::{cube_sphere, dual, quad_torus};
pub use rigid_motion::{rigid_motion, rigidly_moved};
pub use staggered_rings::staggered_ring_faces;
pub use torus::torus;
