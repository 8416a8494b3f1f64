//! The meshes every discretization is checked on: generated in code (always available) and the
//! real meshes of `../shared/meshes` (used when present).

use std::path::PathBuf;
use tvf_core::generate::{genus_surface, icosphere, jitter, rigid_motion, torus};
use tvf_core::SurfaceMesh;

/// Largest field dimension `2F` for which the suite runs dense eigenvalue checks.
pub const DENSE_LIMIT: usize = 1600;

/// A corpus entry: a mesh and what a correct discretization must find on it.
#[derive(Debug, Clone)]
pub struct CorpusMesh {
    /// Name for failure messages.
    pub name: String,
    /// The mesh.
    pub mesh: SurfaceMesh,
    /// Its genus summed over components (the harmonic dimension is twice this).
    pub genus: usize,
}

impl CorpusMesh {
    fn new(name: impl Into<String>, mesh: SurfaceMesh, genus: usize) -> Self {
        Self {
            name: name.into(),
            mesh,
            genus,
        }
    }

    /// Whether dense eigenvalue checks are affordable (`2F ≤ DENSE_LIMIT`).
    pub fn dense_ok(&self) -> bool {
        2 * self.mesh.face_count() <= DENSE_LIMIT
    }
}

/// The disjoint union of two meshes (the second's vertex indices shifted).
pub fn disjoint_union(a: &SurfaceMesh, b: &SurfaceMesh) -> SurfaceMesh {
    let offset = a.vertex_count();
    let positions = a.positions().iter().chain(b.positions()).copied().collect();
    let faces = a
        .faces()
        .iter()
        .copied()
        .chain(b.faces().iter().map(|f| f.map(|v| v + offset)))
        .collect();
    SurfaceMesh::new(positions, faces).expect("the union of two valid meshes is valid")
}

fn small_torus() -> SurfaceMesh {
    torus(1.0, 0.4, 16, 8).expect("valid torus parameters")
}

/// Generated meshes: icospheres, tori, genus-2 and genus-3 surfaces, a two-component mesh, a
/// rigidly moved and a jittered copy. All small enough for dense checks except where noted.
pub fn generated_corpus() -> Vec<CorpusMesh> {
    let moved_torus = rigid_motion(&small_torus(), [1.0, -2.0, 0.5], 0.83, [3.0, -1.0, 2.0])
        .expect("finite motion");
    let jittered_sphere = jitter(&icosphere(2), 0.15, 7).expect("finite amplitude");
    let jittered_genus2 = jitter(&genus_surface(2, 2), 0.15, 11).expect("finite amplitude");
    let shifted_sphere =
        rigid_motion(&icosphere(1), [0.0, 0.0, 1.0], 0.0, [5.0, 0.0, 0.0]).expect("finite");
    vec![
        CorpusMesh::new("icosphere(1)", icosphere(1), 0),
        CorpusMesh::new("icosphere(2)", icosphere(2), 0),
        CorpusMesh::new("icosphere(3) (sparse checks only)", icosphere(3), 0),
        CorpusMesh::new("torus 16×8", small_torus(), 1),
        CorpusMesh::new(
            "thin torus 24×6",
            torus(2.0, 0.3, 24, 6).expect("valid torus parameters"),
            1,
        ),
        CorpusMesh::new("genus-2 surface", genus_surface(2, 2), 2),
        CorpusMesh::new("genus-3 surface", genus_surface(3, 2), 3),
        CorpusMesh::new(
            "torus + sphere (two components)",
            disjoint_union(&small_torus(), &shifted_sphere),
            1,
        ),
        CorpusMesh::new("rigidly moved torus", moved_torus, 1),
        CorpusMesh::new("jittered icosphere(2)", jittered_sphere, 0),
        CorpusMesh::new("jittered genus-2 surface", jittered_genus2, 2),
    ]
}

/// `kitten` (genus 1), `eight` (genus 2) and `3holes` (genus 3) from `../shared/meshes`, when
/// present; prints a skip message and returns none otherwise.
pub fn shared_corpus() -> Vec<CorpusMesh> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shared/meshes");
    let mut corpus = Vec::new();
    for (file, genus) in [("kitten.obj", 1), ("eight.obj", 2), ("3holes.obj", 3)] {
        let path = dir.join(file);
        if !path.exists() {
            eprintln!("skipping {}: not present", path.display());
            continue;
        }
        match tvf_core::io::load_mesh(&path) {
            Ok(loaded) => corpus.push(CorpusMesh::new(file, loaded.mesh, genus)),
            Err(error) => panic!("{} exists but does not load: {error}", path.display()),
        }
    }
    corpus
}
