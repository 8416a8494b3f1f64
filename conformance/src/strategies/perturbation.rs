//! Perturbations of a generated mesh as small descriptions: seeded vertex jitter ([`Jitter`],
//! [`jitters`]) and rigid motions ([`RigidMotion`], [`rigid_motions`]). Both shrink towards the
//! identity (no jitter, no motion).

use proptest::prelude::*;
use tvf_core::generate::{jitter, rigid_motion};
use tvf_core::TriangleMesh;

/// Largest jitter amplitude the strategies draw (a fraction of the shortest edge at a vertex;
/// 0.2 keeps meshes with angles above ~20° valid, see [`tvf_core::generate::jitter`]).
pub const MAX_JITTER: f64 = 0.2;

/// Every vertex moved by a random vector of at most `amplitude` times its shortest edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jitter {
    /// Fraction of the shortest edge at each vertex (0 = none).
    pub amplitude: f64,
    /// Seed of the random moves.
    pub seed: u64,
}

impl Jitter {
    /// The jittered mesh (the mesh itself for amplitude 0).
    pub fn apply(&self, mesh: &TriangleMesh) -> Result<TriangleMesh, String> {
        if self.amplitude == 0.0 {
            return Ok(mesh.clone());
        }
        jitter(mesh, self.amplitude, self.seed).map_err(|e| format!("jitter: {e}"))
    }
}

/// Jitter of amplitude `0..max_amplitude` (half of the draws none at all), any seed.
pub fn jitters(max_amplitude: f64) -> BoxedStrategy<Jitter> {
    let amplitude = prop_oneof![Just(0.0), 0.0..max_amplitude];
    (amplitude, 0u64..1_000_000)
        .prop_map(|(amplitude, seed)| Jitter { amplitude, seed })
        .boxed()
}

/// A rotation by `angle` radians about `axis` (through the origin; a zero axis is no rotation),
/// then a translation by `translation`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidMotion {
    /// Rotation axis (need not be unit length).
    pub axis: [f64; 3],
    /// Rotation angle in radians.
    pub angle: f64,
    /// Translation, applied after the rotation.
    pub translation: [f64; 3],
}

impl RigidMotion {
    /// The moved mesh.
    pub fn apply(&self, mesh: &TriangleMesh) -> Result<TriangleMesh, String> {
        rigid_motion(mesh, self.axis, self.angle, self.translation)
            .map_err(|e| format!("rigid motion: {e}"))
    }
}

/// No motion (shrinks to this) or a random rotation and a translation of up to 10 per axis.
pub fn rigid_motions() -> BoxedStrategy<Option<RigidMotion>> {
    let motion = (
        prop::array::uniform3(-1.0f64..1.0),
        -3.0f64..3.0,
        prop::array::uniform3(-10.0f64..10.0),
    )
        .prop_map(|(axis, angle, translation)| RigidMotion {
            axis,
            angle,
            translation,
        });
    prop::option::of(motion).boxed()
}
