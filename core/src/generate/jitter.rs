//! Seeded random vertex displacement, for property tests on perturbed meshes.

use crate::geometry::{add, norm, scale, sub};
use crate::{MeshError, TriangleMesh};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Moves every vertex by a random vector, uniform in the ball of radius
/// `amplitude × (shortest edge at that vertex)`; the same `seed` gives the same mesh on every
/// machine (ChaCha8). Faces are unchanged.
///
/// Each move is a fraction of the local edge length, so small amplitudes keep a mesh valid:
/// `amplitude = 0.2` keeps every face of a mesh with angles above ~20° from collapsing or
/// flipping (checked by the tests on icosphere, torus and genus surfaces). Larger amplitudes
/// may produce degenerate or flipped faces; the result is not re-validated. Fails only if
/// `amplitude` is not finite.
pub fn jitter(mesh: &TriangleMesh, amplitude: f64, seed: u64) -> Result<TriangleMesh, MeshError> {
    let positions = mesh.positions();
    let mut shortest = vec![f64::INFINITY; positions.len()];
    for &[a, b] in mesh.edges() {
        let length = norm(sub(positions[a], positions[b]));
        shortest[a] = shortest[a].min(length);
        shortest[b] = shortest[b].min(length);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let moved = positions
        .iter()
        .zip(&shortest)
        .map(|(&p, &local)| {
            // Rejection sampling of the unit ball.
            let offset = loop {
                let d: [f64; 3] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
                if norm(d) <= 1.0 {
                    break d;
                }
            };
            let radius = if local.is_finite() {
                amplitude * local
            } else {
                0.0
            };
            add(p, scale(offset, radius))
        })
        .collect();
    TriangleMesh::new(moved, mesh.faces().to_vec())
}
