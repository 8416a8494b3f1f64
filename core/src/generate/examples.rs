//! The built-in example meshes, by name (the `tvf` CLI's `--example NAME`).

use super::{bumpy_torus, genus_surface, hemisphere, icosphere, perforated_plate, torus};
use crate::TriangleMesh;

/// Names accepted by [`example_mesh`].
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

/// Generates the built-in example called `name` (one of [`EXAMPLE_NAMES`]; `None` otherwise).
pub fn example_mesh(name: &str) -> Option<TriangleMesh> {
    Some(match name {
        "icosphere" => icosphere(3),
        "torus" => torus(1.0, 0.4, 48, 24).expect("fixed torus parameters are valid"),
        "bumpy-torus" => {
            bumpy_torus(1.0, 0.3, 96, 48, 24, 0.35).expect("fixed bumpy torus parameters are valid")
        }
        "genus0" => genus_surface(0, 8),
        "genus1" => genus_surface(1, 8),
        "genus2" => genus_surface(2, 8),
        "genus3" => genus_surface(3, 8),
        "genus4" => genus_surface(4, 8),
        // Meshes with boundary: one loop (2400 faces), three loops (a plate with two holes).
        "hemisphere" => hemisphere(20),
        "pants" => perforated_plate(2, 12),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_is_an_example_and_others_are_not() {
        for name in EXAMPLE_NAMES {
            assert!(
                example_mesh(name).is_some_and(|m| m.face_count() > 0),
                "{name}"
            );
        }
        assert!(example_mesh("teapot").is_none());
    }
}
