//! Seeded constraint sets for the design experiments (Table 1's columns, Figure 9's designed
//! fields): vectors, sources, sinks and vortices spread over a mesh by a seeded generator.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::discretization::{HodgeComplex, NodeKind};
use tvf_core::SurfaceMesh;
use tvf_design::{Constraint, Location, Target};

/// Constraints of the designed fields of Figures 7–9 (soft design, seeded).
pub const DESIGNED_FIELD_CONSTRAINTS: usize = 12;

/// `count` seeded constraints spread over `mesh` for `complex`: 80 % vectors in random faces
/// with random directions, then alternately divergences and curls (for 30: 24 vectors, 3
/// sources/sinks, 3 vortices), each at a node of the complex's own space next to a random face
/// (conforming: divergence at a vertex, curl at an edge; DEC: curl on the face).
pub fn seeded_constraints(
    mesh: &SurfaceMesh,
    complex: &dyn HodgeComplex,
    count: usize,
    seed: u64,
) -> Vec<Constraint> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let vectors = count * 4 / 5;
    let node_next_to = |kind: NodeKind, face: usize| match kind {
        NodeKind::Vertices => Location::Vertex(mesh.face(face)[0]),
        // The side from corner 1 to corner 2: on a triangle, the edge opposite corner 0.
        NodeKind::Edges => Location::Edge(mesh.face_edge(face, 1)),
        NodeKind::Faces | NodeKind::FaceFrames => Location::Face {
            face,
            barycentric: None,
        },
    };
    (0..count)
        .map(|k| {
            let face = rng.random_range(0..mesh.face_count().max(1));
            if k < vectors {
                let v = [(); 3].map(|_| rng.random_range(-1.0..1.0));
                let location = Location::Face {
                    face,
                    barycentric: None,
                };
                Constraint::new(format!("v{k}"), Target::Vector(v), location)
            } else if (k - vectors).is_multiple_of(2) {
                let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
                Constraint::new(
                    format!("d{k}"),
                    Target::Divergence(sign),
                    node_next_to(complex.potential_nodes().kind, face),
                )
            } else {
                Constraint::new(
                    format!("c{k}"),
                    Target::Curl(1.0),
                    node_next_to(complex.co_potential_nodes().kind, face),
                )
            }
        })
        .collect()
}
