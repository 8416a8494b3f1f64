//! Built-in example meshes, selectable with `--example NAME` wherever a mesh is expected.

use anyhow::{bail, Result};
use tvf_core::generate::{icosphere, torus};
use tvf_core::SurfaceMesh;

/// Names accepted by `--example`.
pub const EXAMPLE_NAMES: &[&str] = &["icosphere", "torus"];

/// Generates the built-in example called `name`.
pub fn example_mesh(name: &str) -> Result<SurfaceMesh> {
    match name {
        "icosphere" => Ok(icosphere(3)),
        "torus" => Ok(torus(1.0, 0.4, 48, 24).expect("fixed torus parameters are valid")),
        _ => bail!(
            "unknown example '{name}': choose one of {}",
            EXAMPLE_NAMES.join(", ")
        ),
    }
}
