//! Surfaces with boundary as small descriptions ([`OpenShape`]) and their strategy
//! ([`open_shapes`]), ordered from simple to complex so that shrinking goes towards small disks.

use proptest::prelude::*;
use tvf_core::generate::{disk, hemisphere, holed_torus, open_cylinder, perforated_plate};
use tvf_core::TriangleMesh;

/// A connected surface with boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum OpenShape {
    /// The unit disk of `rings` rings (`6·rings²` faces), one boundary loop.
    Disk {
        /// Rings (≥ 1).
        rings: usize,
    },
    /// The upper unit hemisphere of `rings` rings, one boundary loop.
    Hemisphere {
        /// Rings (≥ 1).
        rings: usize,
    },
    /// An open cylinder (annulus) of height 1, two boundary loops.
    Cylinder {
        /// Vertices per ring (≥ 3).
        around: usize,
        /// Layers (≥ 1).
        layers: usize,
    },
    /// A flat plate with `holes` holes ([`perforated_plate`]): an annulus for one hole, a pair of
    /// pants for two; `holes + 1` boundary loops.
    Pants {
        /// Holes (1 or 2).
        holes: usize,
        /// Segments along each cell side (2 or 4).
        resolution: usize,
    },
    /// A quad torus with one grid cell removed: genus 1, one boundary loop.
    HoledTorus {
        /// Segments along the major circle (≥ 3).
        around: usize,
        /// Segments along the tube (≥ 3).
        tube: usize,
    },
}

impl OpenShape {
    /// Genus of the surface, from the description.
    pub fn genus(&self) -> usize {
        match self {
            OpenShape::HoledTorus { .. } => 1,
            _ => 0,
        }
    }

    /// Number of boundary loops, from the description.
    pub fn boundary_loops(&self) -> usize {
        match self {
            OpenShape::Cylinder { .. } => 2,
            OpenShape::Pants { holes, .. } => holes + 1,
            _ => 1,
        }
    }

    /// Dimension of the harmonic space, `2g + b − 1`.
    pub fn harmonic_dimension(&self) -> usize {
        2 * self.genus() + self.boundary_loops() - 1
    }

    /// The mesh.
    pub fn build(&self) -> TriangleMesh {
        match *self {
            OpenShape::Disk { rings } => disk(rings),
            OpenShape::Hemisphere { rings } => hemisphere(rings),
            OpenShape::Cylinder { around, layers } => open_cylinder(around, layers, 1.0),
            OpenShape::Pants { holes, resolution } => perforated_plate(holes, resolution),
            OpenShape::HoledTorus { around, tube } => {
                holed_torus(1.0, 0.4, around, tube).expect("around, tube ≥ 3")
            }
        }
    }
}

/// Surfaces with boundary: disks, hemispheres, cylinders, pants (annulus or pair of pants) and
/// holed tori.
pub fn open_shapes() -> BoxedStrategy<OpenShape> {
    prop_oneof![
        (1usize..=4).prop_map(|rings| OpenShape::Disk { rings }),
        (2usize..=4).prop_map(|rings| OpenShape::Hemisphere { rings }),
        (4usize..=12, 1usize..=4)
            .prop_map(|(around, layers)| OpenShape::Cylinder { around, layers }),
        (1usize..=2, prop::bool::ANY).prop_map(|(holes, fine)| OpenShape::Pants {
            holes,
            resolution: if fine { 4 } else { 2 },
        }),
        (4usize..=12, 3usize..=6).prop_map(|(around, tube)| OpenShape::HoledTorus { around, tube }),
    ]
    .boxed()
}
