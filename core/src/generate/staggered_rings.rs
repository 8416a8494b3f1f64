//! [`staggered_ring_faces`]: the triangles between rings of vertices where every other ring is
//! shifted by half a cell (near-isosceles triangles instead of split rectangles).

/// The faces between `strips` consecutive pairs of rings of `around` vertices each, vertex `i` of
/// ring `r` being `(r % ring_count) · around + i % around`, odd rings shifted by +1/2 cell:
/// `2 · around · strips` faces, counter-clockwise when ring `r + 1` lies to the left of the
/// direction of increasing `i` on ring `r`. `ring_count = strips` closes the rings into a torus,
/// `ring_count = strips + 1` leaves a strip with two boundary rings.
pub fn staggered_ring_faces(around: usize, strips: usize, ring_count: usize) -> Vec<[usize; 3]> {
    let index = |ring: usize, i: usize| (ring % ring_count) * around + i % around;
    let mut faces = Vec::with_capacity(2 * around * strips);
    for ring in 0..strips {
        for i in 0..around {
            let (a, a_next) = (index(ring, i), index(ring, i + 1));
            let (b, b_next) = (index(ring + 1, i), index(ring + 1, i + 1));
            if ring % 2 == 0 {
                // The upper ring is shifted by +1/2: b sits between a and a_next.
                faces.push([a, a_next, b]);
                faces.push([b, a_next, b_next]);
            } else {
                // The lower ring is shifted: a sits between b and b_next.
                faces.push([a, b_next, b]);
                faces.push([a, a_next, b_next]);
            }
        }
    }
    faces
}
