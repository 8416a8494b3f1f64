//! proptest strategies for meshes, for property-based checks of discretizations: a strategy draws
//! a small *description* of a mesh ([`MeshSpec`]: shape, genus, resolution, jitter, seed, rigid
//! motion) and [`MeshSpec::build`] makes the mesh, so that proptest's shrinking works on the
//! description — towards simpler shapes, lower genus, fewer faces, no jitter and no motion.
//!
//! - [`closed`]: closed surfaces of genus 0–5 (icospheres, tori, sliver tori, plate surfaces);
//! - [`open`]: surfaces with boundary (disk, hemisphere, cylinder, pants, holed torus);
//! - [`perturbation`]: jitter and rigid motions;
//! - [`mesh_spec`]: the whole description, its mesh, several components, the Delaunay-only
//!   variants (edge flips) and [`mesh_specs`], the strategy a property runner draws from;
//! - [`polygon_spec`]: polygon meshes (quad tori and surfaces, cube-spheres, duals, holes,
//!   several components) and [`polygon_mesh_specs`], shrinking within polygon meshes.
//!
//! ```
//! use tvf_conformance::proptest::strategy::{Strategy, ValueTree};
//! use tvf_conformance::proptest::test_runner::TestRunner;
//! use tvf_conformance::strategies::{mesh_specs, MeshNeeds};
//!
//! let mut runner = TestRunner::deterministic();
//! let spec = mesh_specs(MeshNeeds::default()).new_tree(&mut runner).unwrap().current();
//! let mesh = spec.build().unwrap();
//! assert_eq!(mesh.mesh.component_count(), spec.components.len());
//! ```

pub mod closed;
pub mod mesh_spec;
pub mod open;
pub mod perturbation;
pub mod polygon_spec;

pub use closed::{closed_shapes, ClosedShape};
pub use mesh_spec::{mesh_specs, MeshNeeds, MeshSpec, Shape};
pub use open::{open_shapes, OpenShape};
pub use perturbation::{jitters, rigid_motions, Jitter, RigidMotion};
pub use polygon_spec::{polygon_mesh_specs, PolygonMeshSpec, PolygonShape};
