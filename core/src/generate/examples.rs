//! The built-in example meshes, by name (the `tvf` CLI's `--example NAME`).

use super::{
    bumpy_torus, cube_sphere, genus_surface, hemisphere, icosphere, perforated_plate, quad_torus,
    torus,
};
use crate::SurfaceMesh;

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
    "quad-torus",
    "cube-sphere",
];

/// Generates the built-in example called `name` (one of [`EXAMPLE_NAMES`]; `None` otherwise).
pub fn example_mesh(name: &str) -> Option<SurfaceMesh> {
    Some(SurfaceMesh::from(match name {
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
        // Polygon meshes: 1,536 planar quads of genus 1; 1,536 non-planar quads on the sphere.
        "quad-torus" => {
            return quad_torus(1.0, 0.4, 48, 32).map(SurfaceMesh::from);
        }
        "cube-sphere" => return cube_sphere(16).map(SurfaceMesh::from),
        _ => return None,
    }))
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
