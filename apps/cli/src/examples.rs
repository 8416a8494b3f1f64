//! Built-in example meshes, selectable with `--example NAME` wherever a mesh is expected.

use anyhow::{bail, Result};
use tvf_core::generate::{
    bumpy_torus, genus_surface, hemisphere, icosphere, perforated_plate, torus,
};
use tvf_core::SurfaceMesh;

/// Names accepted by `--example`.
pub const EXAMPLE_NAMES: &[&str] = &[
    "icosphere",
    "torus",
    "bumpy-torus",
    "genus0",
    "genus1",
    "genus2",
    "genus3",
    "genus4",
    "hemisphere",
    "pants",
];

/// Generates the built-in example called `name`.
pub fn example_mesh(name: &str) -> Result<SurfaceMesh> {
    match name {
        "icosphere" => Ok(icosphere(3)),
        "torus" => Ok(torus(1.0, 0.4, 48, 24).expect("fixed torus parameters are valid")),
        "bumpy-torus" => Ok(bumpy_torus(1.0, 0.3, 96, 48, 24, 0.35)
            .expect("fixed bumpy torus parameters are valid")),
        "genus0" => Ok(genus_surface(0, 8)),
        "genus1" => Ok(genus_surface(1, 8)),
        "genus2" => Ok(genus_surface(2, 8)),
        "genus3" => Ok(genus_surface(3, 8)),
        "genus4" => Ok(genus_surface(4, 8)),
        // Meshes with boundary: one loop (2400 faces), three loops (a plate with two holes).
        "hemisphere" => Ok(hemisphere(20)),
        "pants" => Ok(perforated_plate(2, 12)),
        _ => bail!(
            "unknown example '{name}': choose one of {}",
            EXAMPLE_NAMES.join(", ")
        ),
    }
}
