//! Shared by the Table 1 bench and the ordering example: the paper's 30 constraints, seeded.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::PathBuf;
use tvf_core::SurfaceMesh;
use tvf_design::{Constraint, Location, Target};

/// The meshes of the paper's Table 1 (our closed / ×4 subdivided versions).
pub const MESHES: [&str; 5] = [
    "hand",
    "rocker-arm",
    "bunny-closed",
    "bumpy-torus-x4",
    "armadillo-x4",
];

/// `../shared/meshes` next to the repository root.
pub fn mesh_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/meshes")
}

/// 30 seeded constraints: 24 vectors, 3 divergences at vertices, 3 curls at edges.
pub fn constraints(mesh: &SurfaceMesh, seed: u64) -> Vec<Constraint> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::new();
    for k in 0..30 {
        let face = rng.random_range(0..mesh.face_count());
        let location = Location::Face {
            face,
            barycentric: None,
        };
        let c = match k {
            0..24 => {
                let v = [
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                ];
                Constraint::new(format!("v{k}"), Target::Vector(v), location)
            }
            24..27 => Constraint::new(
                format!("d{k}"),
                Target::Divergence(1.0),
                Location::Vertex(mesh.faces()[face][0]),
            ),
            _ => Constraint::new(
                format!("c{k}"),
                Target::Curl(-1.0),
                Location::Edge(mesh.face_edges()[face][0]),
            ),
        };
        out.push(c);
    }
    out
}
