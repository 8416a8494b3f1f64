//! Closed surfaces of genus 0–5 as small descriptions ([`ClosedShape`]) and their strategy
//! ([`closed_shapes`]), ordered from simple to complex so that shrinking goes towards icospheres,
//! low genus and low resolution.

use crate::corpus::{sliver_torus, staggered_torus};
use proptest::prelude::*;
use tvf_core::generate::{genus_surface, icosphere, torus};
use tvf_core::TriangleMesh;

/// Largest genus the strategies draw.
pub const MAX_GENUS: usize = 5;

/// A closed, connected surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ClosedShape {
    /// The unit icosphere of subdivision `level` (0–2: 20, 80, 320 faces), genus 0, Delaunay.
    Sphere {
        /// Subdivision level.
        level: u32,
    },
    /// A quad torus of radii 1 and 0.4, `2·around·tube` faces, genus 1 (not Delaunay: the quad
    /// diagonals have `cot α + cot β = 0`).
    Torus {
        /// Segments along the major circle (≥ 3).
        around: usize,
        /// Segments along the tube (≥ 3).
        tube: usize,
    },
    /// A staggered torus of radii 1 and 0.4 ([`staggered_torus`]) with `around = ⌈2.5·tube⌉`,
    /// so all triangles are acute (Delaunay), genus 1.
    StaggeredTorus {
        /// Rings along the tube (even, ≥ 4).
        tube: usize,
    },
    /// A staggered torus whose second ring is pulled towards the first ([`sliver_torus`]): a
    /// strip of cap slivers, `thin` of the original distance (smaller is thinner). Genus 1, not
    /// Delaunay.
    SliverTorus {
        /// Rings along the tube (even, ≥ 4).
        tube: usize,
        /// How much of the distance to the opposite edge a sliver keeps (0 < thin ≤ 1).
        thin: f64,
    },
    /// The boundary of a thickened plate with `genus` holes ([`genus_surface`]); `resolution`
    /// 2 (coarse: angles 15.6°–112.5°) or 4 segments per cell side.
    Plate {
        /// Genus (0–[`MAX_GENUS`]).
        genus: usize,
        /// Segments along each cell side.
        resolution: usize,
    },
}

impl ClosedShape {
    /// The genus of the surface, from the description (independent of the mesh).
    pub fn genus(&self) -> usize {
        match self {
            ClosedShape::Sphere { .. } => 0,
            ClosedShape::Torus { .. }
            | ClosedShape::StaggeredTorus { .. }
            | ClosedShape::SliverTorus { .. } => 1,
            ClosedShape::Plate { genus, .. } => *genus,
        }
    }

    /// Whether the generated mesh is Delaunay as it is (no flips needed).
    pub fn is_delaunay(&self) -> bool {
        matches!(
            self,
            ClosedShape::Sphere { .. } | ClosedShape::StaggeredTorus { .. }
        )
    }

    /// The mesh.
    pub fn build(&self) -> TriangleMesh {
        match *self {
            ClosedShape::Sphere { level } => icosphere(level),
            ClosedShape::Torus { around, tube } => {
                torus(1.0, 0.4, around, tube).expect("around, tube ≥ 3")
            }
            ClosedShape::StaggeredTorus { tube } => staggered_torus(1.0, 0.4, around(tube), tube),
            ClosedShape::SliverTorus { tube, thin } => {
                sliver_torus(1.0, 0.4, around(tube), tube, thin)
            }
            ClosedShape::Plate { genus, resolution } => genus_surface(genus, resolution),
        }
    }
}

/// Segments along the major circle of a staggered torus with `tube` rings whose triangles are
/// acute (radii 1 and 0.4).
fn around(tube: usize) -> usize {
    (2.5 * tube as f64).ceil() as usize
}

/// Closed surfaces: with `delaunay`, only the Delaunay-as-generated ones (icospheres, staggered
/// tori) and plates (which [`crate::strategies::MeshSpec::build`] makes Delaunay by flips);
/// otherwise also quad tori and sliver tori.
pub fn closed_shapes(delaunay: bool) -> BoxedStrategy<ClosedShape> {
    let sphere = (0u32..=2).prop_map(|level| ClosedShape::Sphere { level });
    let staggered = (2usize..=4).prop_map(|half| ClosedShape::StaggeredTorus { tube: 2 * half });
    let plate = (0..=MAX_GENUS, prop::bool::ANY).prop_map(|(genus, fine)| ClosedShape::Plate {
        genus,
        resolution: if fine { 4 } else { 2 },
    });
    if delaunay {
        return prop_oneof![sphere, staggered, plate].boxed();
    }
    let quad_torus =
        (3usize..=12, 3usize..=6).prop_map(|(around, tube)| ClosedShape::Torus { around, tube });
    let sliver = (2usize..=4, 0.01f64..1.0).prop_map(|(half, thin)| ClosedShape::SliverTorus {
        tube: 2 * half,
        thin: 1.0 - thin,
    });
    prop_oneof![sphere, quad_torus, staggered, sliver, plate].boxed()
}
