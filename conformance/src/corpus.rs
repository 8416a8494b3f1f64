//! The meshes every discretization is checked on: generated in code (always available) and the
//! real meshes of `../shared/meshes` (used when present, required under `CI=true`), in two
//! corpora — the general one, and the Delaunay one for discretizations that need
//! `cot α + cot β > 0` on every edge (DEC's diagonal `⋆1`).

use crate::lawson_flips::LawsonFlips;
use std::f64::consts::TAU;
use tvf_core::generate::{
    disk, genus_surface, hemisphere, holed_torus, icosphere, jitter, open_cylinder,
    perforated_plate, rigid_motion, staggered_ring_faces, torus,
};
use tvf_core::geometry::{cross, dot, norm, sub};
use tvf_core::mesh::Mesh;
use tvf_core::TriangleMesh;
use tvf_discretizations::{CatalogEntry, DELAUNAY_TOLERANCE};

/// Largest field dimension `n1` for which the suite runs dense eigenvalue checks.
pub const DENSE_LIMIT: usize = 1600;

/// Largest field dimension `n1` for which the suite runs dense eigenvector checks (Lemma 1 and
/// the orthonormality of the assembled basis), which cost several times more.
pub const EIGENVECTOR_LIMIT: usize = 1000;

/// A corpus entry: a mesh and what a correct discretization must find on it. The mesh is a
/// [`TriangleMesh`] in the triangle corpora and a [`tvf_core::SurfaceMesh`] of polygons in the
/// polygon corpus ([`crate::polygon_corpus`]).
#[derive(Debug, Clone)]
pub struct CorpusMesh<M = TriangleMesh> {
    /// Name for failure messages.
    pub name: String,
    /// The mesh.
    pub mesh: M,
    /// Its genus summed over components, stated independently of the mesh's own Euler
    /// characteristic.
    pub genus: usize,
    /// The dimension of the harmonic space, stated independently: `2·genus` on a closed mesh,
    /// `Σ (2g + b − 1)` over the components with `b ≥ 1` boundary loops (plus `2g` over the
    /// closed ones) on a mesh with boundary, for both boundary conditions.
    pub harmonic_dimension: usize,
}

impl<M> CorpusMesh<M> {
    /// A named closed mesh of total genus `genus` (harmonic dimension `2·genus`).
    pub fn new(name: impl Into<String>, mesh: M, genus: usize) -> Self {
        Self {
            name: name.into(),
            mesh,
            genus,
            harmonic_dimension: 2 * genus,
        }
    }

    /// A named mesh with boundary of total genus `genus` and harmonic dimension
    /// `harmonic_dimension`.
    pub fn open(name: impl Into<String>, mesh: M, genus: usize, harmonic_dimension: usize) -> Self {
        Self {
            name: name.into(),
            mesh,
            genus,
            harmonic_dimension,
        }
    }
}

impl<M: Mesh> CorpusMesh<M> {
    /// The genus of every component from the mesh's own Euler characteristics.
    pub fn component_genera(&self) -> Vec<usize> {
        self.mesh
            .topology()
            .component_genera(self.mesh.face_corners())
    }

    /// The harmonic dimension of every component from the mesh's own topology: `2g` on a closed
    /// component, `2g + b − 1` on one with `b ≥ 1` boundary loops.
    pub fn component_harmonic_dimensions(&self) -> Vec<usize> {
        let loops = tvf_discretizations::component_boundary_loops(&self.mesh);
        self.component_genera()
            .iter()
            .zip(&loops)
            .map(|(&g, &b)| if b == 0 { 2 * g } else { 2 * g + b - 1 })
            .collect()
    }
}

/// Which meshes a discretization is checked on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Corpus {
    /// Every generated mesh (genus 0–3, two components, rigidly moved and jittered copies, quad
    /// tori and a torus of slivers that are not Delaunay) and `kitten`, `eight`, `3holes` from
    /// `../shared/meshes`.
    General,
    /// Meshes with `cot α + cot β > 0` on every edge: icospheres, a staggered torus, flipped
    /// genus-2 and genus-3 surfaces, jittered and moved copies, two components, and `eight.obj`
    /// (the only Delaunay shared mesh).
    Delaunay,
    /// Meshes with boundary ([`open_corpus`]): disk, open cylinder, hemisphere, pair of pants,
    /// torus with a hole, two components with different boundary counts, and the raw
    /// `bunny.obj` (5 loops, unreferenced vertices) from `../shared/meshes`.
    Open,
    /// The Delaunay part of the open corpus ([`open_delaunay_corpus`]).
    OpenDelaunay,
}

impl Corpus {
    /// The corpus of catalog entry `entry` (of any catalog): [`Corpus::Delaunay`] if the entry
    /// needs a Delaunay mesh, else [`Corpus::General`].
    pub fn for_catalog_entry(entry: &CatalogEntry) -> Self {
        if entry.needs_delaunay() {
            Corpus::Delaunay
        } else {
            Corpus::General
        }
    }

    /// The open corpus of catalog entry `entry`: [`Corpus::OpenDelaunay`] if the entry needs a
    /// Delaunay mesh, else [`Corpus::Open`].
    pub fn open_for_catalog_entry(entry: &CatalogEntry) -> Self {
        if entry.needs_delaunay() {
            Corpus::OpenDelaunay
        } else {
            Corpus::Open
        }
    }

    /// The generated meshes and, if `with_shared`, the shared meshes that are present.
    pub fn meshes(self, with_shared: bool) -> Vec<CorpusMesh> {
        let mut meshes = match self {
            Corpus::General => generated_corpus(),
            Corpus::Delaunay => delaunay_corpus(),
            Corpus::Open => open_corpus(),
            Corpus::OpenDelaunay => open_delaunay_corpus(),
        };
        if with_shared {
            meshes.extend(shared_corpus(self));
        }
        meshes
    }

    /// Two small meshes (genus 0 and 1) for the rigid-motion property test.
    pub fn motion_meshes(self) -> Vec<CorpusMesh> {
        match self {
            Corpus::General => vec![
                CorpusMesh::new("icosphere(1)", icosphere(1), 0),
                CorpusMesh::new(
                    "torus 12×6",
                    torus(1.0, 0.4, 12, 6).expect("valid torus"),
                    1,
                ),
            ],
            Corpus::Delaunay => vec![
                CorpusMesh::new("icosphere(1)", icosphere(1), 0),
                CorpusMesh::new("staggered torus 16×8", staggered_torus(1.0, 0.4, 16, 8), 1),
            ],
            Corpus::Open | Corpus::OpenDelaunay => vec![
                CorpusMesh::open("hemisphere(3)", hemisphere(3), 0, 0),
                CorpusMesh::open("open cylinder 12×3", open_cylinder(12, 3, 1.0), 0, 1),
            ],
        }
    }

    /// A randomly perturbed genus-1 mesh for the jitter property test: a quad torus jittered by
    /// 0.2 (general), or a staggered torus jittered by 0.2 and made Delaunay by edge flips.
    pub fn jittered_mesh(self, seed: u64) -> CorpusMesh {
        let name = format!("jittered torus (seed {seed})");
        match self {
            Corpus::General => {
                let base = torus(1.0, 0.4, 12, 6).expect("valid torus");
                CorpusMesh::new(name, jitter(&base, 0.2, seed).expect("finite amplitude"), 1)
            }
            Corpus::Delaunay => {
                let base = staggered_torus(1.0, 0.4, 16, 8);
                let jittered = jitter(&base, 0.2, seed).expect("finite amplitude");
                CorpusMesh::new(name, delaunay_flips(&jittered), 1)
            }
            Corpus::Open | Corpus::OpenDelaunay => {
                let name = format!("jittered open cylinder (seed {seed})");
                let jittered = jitter(&open_cylinder(16, 4, 1.0), 0.1, seed).expect("finite");
                let mesh = if self == Corpus::OpenDelaunay {
                    delaunay_flips(&jittered)
                } else {
                    jittered
                };
                CorpusMesh::open(name, mesh, 0, 1)
            }
        }
    }
}

/// The disjoint union of two meshes (the second's vertex indices shifted).
pub fn disjoint_union(a: &TriangleMesh, b: &TriangleMesh) -> TriangleMesh {
    let offset = a.vertex_count();
    let positions = a.positions().iter().chain(b.positions()).copied().collect();
    let faces = a
        .faces()
        .iter()
        .copied()
        .chain(b.faces().iter().map(|f| f.map(|v| v + offset)))
        .collect();
    TriangleMesh::new(positions, faces).expect("the union of two valid meshes is valid")
}

fn small_torus() -> TriangleMesh {
    torus(1.0, 0.4, 16, 8).expect("valid torus parameters")
}

fn shifted_icosphere() -> TriangleMesh {
    rigid_motion(&icosphere(1), [0.0, 0.0, 1.0], 0.0, [5.0, 0.0, 0.0]).expect("finite")
}

/// Generated meshes: icospheres, tori, genus-2 and genus-3 surfaces, a two-component mesh, a
/// rigidly moved and a jittered copy, and a torus with a strip of cap slivers. All small enough
/// for dense checks except icosphere(3). Most are not Delaunay (the quad tori, the jittered and
/// the sliver meshes), which is what a discretization without a Delaunay precondition must pass.
pub fn generated_corpus() -> Vec<CorpusMesh> {
    let moved_torus = rigid_motion(&small_torus(), [1.0, -2.0, 0.5], 0.83, [3.0, -1.0, 2.0])
        .expect("finite motion");
    let jittered_sphere = jitter(&icosphere(2), 0.15, 7).expect("finite amplitude");
    let jittered_genus2 = jitter(&genus_surface(2, 2), 0.15, 11).expect("finite amplitude");
    vec![
        CorpusMesh::new("icosphere(1)", icosphere(1), 0),
        CorpusMesh::new("icosphere(2)", icosphere(2), 0),
        CorpusMesh::new("icosphere(3)", icosphere(3), 0),
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
            disjoint_union(&small_torus(), &shifted_icosphere()),
            1,
        ),
        CorpusMesh::new("rigidly moved torus", moved_torus, 1),
        CorpusMesh::new("jittered icosphere(2)", jittered_sphere, 0),
        CorpusMesh::new("jittered genus-2 surface", jittered_genus2, 2),
        CorpusMesh::new("sliver torus 12×8", sliver_torus(1.0, 0.4, 12, 8, 0.01), 1),
    ]
}

/// Generated Delaunay meshes (each checked by [`is_delaunay`] in this crate's tests): icospheres
/// (Delaunay as generated, also jittered by 0.15), a staggered torus (acute triangles), genus-2
/// and genus-3 plate surfaces made Delaunay by edge flips, a rigidly moved copy and two
/// components.
pub fn delaunay_corpus() -> Vec<CorpusMesh> {
    let torus = staggered_torus(1.0, 0.4, 24, 10);
    let moved_torus =
        rigid_motion(&torus, [1.0, -2.0, 0.5], 0.83, [3.0, -1.0, 2.0]).expect("finite motion");
    let flipped = |genus| {
        let jittered = jitter(&genus_surface(genus, 2), 0.05, 3).expect("finite amplitude");
        delaunay_flips(&jittered)
    };
    vec![
        CorpusMesh::new("icosphere(1)", icosphere(1), 0),
        CorpusMesh::new("icosphere(2)", icosphere(2), 0),
        CorpusMesh::new("icosphere(3)", icosphere(3), 0),
        CorpusMesh::new("staggered torus 24×10", torus.clone(), 1),
        CorpusMesh::new("flipped genus-2 surface", flipped(2), 2),
        CorpusMesh::new("flipped genus-3 surface", flipped(3), 3),
        CorpusMesh::new(
            "staggered torus + sphere (two components)",
            disjoint_union(&torus, &shifted_icosphere()),
            1,
        ),
        CorpusMesh::new("rigidly moved staggered torus", moved_torus, 1),
        CorpusMesh::new(
            "jittered icosphere(2)",
            jitter(&icosphere(2), 0.15, 7).expect("finite amplitude"),
            0,
        ),
    ]
}

/// Generated meshes with boundary (harmonic dimension `2g + b − 1` per component): disk (b = 1),
/// open cylinder (annulus, b = 2), hemisphere (b = 1), pair of pants (plate with two holes,
/// b = 3), torus with one hole (g = 1, b = 1), and a disk + pair of pants (two components,
/// b = 1 and 3), a jittered pair of pants. All small enough for the dense checks.
pub fn open_corpus() -> Vec<CorpusMesh> {
    let pants = perforated_plate(2, 8);
    let shifted_disk =
        rigid_motion(&disk(3), [0.0, 0.0, 1.0], 0.0, [0.0, 0.0, 3.0]).expect("finite");
    vec![
        CorpusMesh::open("disk(4)", disk(4), 0, 0),
        CorpusMesh::open("open cylinder 16×4", open_cylinder(16, 4, 1.0), 0, 1),
        CorpusMesh::open("hemisphere(5)", hemisphere(5), 0, 0),
        CorpusMesh::open("pair of pants", pants.clone(), 0, 2),
        CorpusMesh::open(
            "torus 16×8 with a hole",
            holed_torus(1.0, 0.4, 16, 8).expect("valid torus"),
            1,
            2,
        ),
        CorpusMesh::open(
            "disk + pair of pants (two components)",
            disjoint_union(&shifted_disk, &pants),
            0,
            2,
        ),
        CorpusMesh::open(
            "jittered pair of pants",
            jitter(&pants, 0.1, 5).expect("finite amplitude"),
            0,
            2,
        ),
    ]
}

/// The Delaunay meshes with boundary (edge flips where needed, every mesh checked by
/// [`is_delaunay`] in this crate's tests): disk, open cylinder, hemisphere, pair of pants, two
/// components.
pub fn open_delaunay_corpus() -> Vec<CorpusMesh> {
    let pants = delaunay_flips(&perforated_plate(2, 8));
    let shifted_disk = rigid_motion(
        &delaunay_flips(&disk(3)),
        [0.0, 0.0, 1.0],
        0.0,
        [0.0, 0.0, 3.0],
    )
    .expect("finite");
    vec![
        CorpusMesh::open("flipped disk(4)", delaunay_flips(&disk(4)), 0, 0),
        CorpusMesh::open(
            "open cylinder 16×4",
            delaunay_flips(&open_cylinder(16, 4, 1.0)),
            0,
            1,
        ),
        CorpusMesh::open(
            "flipped hemisphere(5)",
            delaunay_flips(&hemisphere(5)),
            0,
            0,
        ),
        CorpusMesh::open("flipped pair of pants", pants.clone(), 0, 2),
        CorpusMesh::open(
            "flipped disk + pair of pants (two components)",
            disjoint_union(&shifted_disk, &pants),
            0,
            2,
        ),
    ]
}

/// Meshes of `../shared/meshes` when present (a skip message for each missing one; under
/// `CI=true` a missing one panics, [`tvf_test_support::shared_mesh`]): for the general corpus
/// `kitten` (genus 1), `eight` (genus 2) and `3holes` (genus 3); for the Delaunay corpus `eight`
/// alone; for the open corpus the raw `bunny`.
pub fn shared_corpus(corpus: Corpus) -> Vec<CorpusMesh> {
    let files: &[(&str, usize)] = match corpus {
        Corpus::General => &[("kitten.obj", 1), ("eight.obj", 2), ("3holes.obj", 3)],
        Corpus::Delaunay => &[("eight.obj", 2)],
        Corpus::Open => &[("bunny.obj", 0)],
        Corpus::OpenDelaunay => &[],
    };
    let mut meshes = Vec::new();
    for &(file, genus) in files {
        let Some(path) = tvf_test_support::shared_mesh(file) else {
            continue;
        };
        let mesh = match tvf_core::io::load_mesh(&path) {
            Ok(loaded) => match loaded.mesh {
                tvf_core::SurfaceMesh::Triangles(mesh) => mesh,
                tvf_core::SurfaceMesh::Polygons(_) => {
                    panic!("{} is not a triangle mesh", path.display())
                }
            },
            Err(error) => panic!("{} exists but does not load: {error}", path.display()),
        };
        if mesh.is_closed() {
            meshes.push(CorpusMesh::new(file, mesh, genus))
        } else {
            // The raw bunny: genus 0, 5 boundary loops, so 4 harmonic fields.
            meshes.push(CorpusMesh::open(file, mesh, genus, 4))
        }
    }
    meshes
}

/// A torus of revolution around z (`major`, `minor` radii) whose rings of `around` vertices are
/// shifted by half a cell on every other of the `tube` rings (`tube` even), so every cell is two
/// near-isosceles triangles instead of a split rectangle: `2·around·tube` faces, genus 1, outward
/// normals. With `around ≈ 2π·major / (2π·minor / tube)` all triangles are acute, hence Delaunay
/// (a quad torus is not: its diagonals have `cot α + cot β = 0`).
pub fn staggered_torus(major: f64, minor: f64, around: usize, tube: usize) -> TriangleMesh {
    assert!(
        tube & 1 == 0 && tube >= 4 && around >= 3,
        "even tube ≥ 4, around ≥ 3"
    );
    let positions = (0..tube)
        .flat_map(|ring| {
            let v = TAU * ring as f64 / tube as f64;
            let shift = 0.5 * (ring % 2) as f64;
            (0..around).map(move |i| {
                let u = TAU * (i as f64 + shift) / around as f64;
                let radius = major + minor * v.cos();
                [radius * u.cos(), radius * u.sin(), minor * v.sin()]
            })
        })
        .collect();
    let faces = staggered_ring_faces(around, tube, tube);
    TriangleMesh::new(positions, faces).expect("a staggered torus is a valid closed mesh")
}

/// A [`staggered_torus`] whose ring 1 is pulled towards ring 0: each vertex of ring 1 moves to
/// `thin` of its distance from the midpoint of the two ring-0 vertices it sits between, so the
/// strip between rings 0 and 1 is made of cap slivers (one angle near 180°, two near 0°; for
/// `thin = 0.01` on a 12×8 torus of radii 1 and 0.4 the angles span 0.46°–179.1°). Genus 1, not
/// Delaunay.
pub fn sliver_torus(major: f64, minor: f64, around: usize, tube: usize, thin: f64) -> TriangleMesh {
    let torus = staggered_torus(major, minor, around, tube);
    let p = torus.positions();
    let positions = (0..p.len())
        .map(|v| {
            let (ring, i) = (v / around, v % around);
            if ring != 1 {
                return p[v];
            }
            let (a, b) = (p[i], p[(i + 1) % around]);
            std::array::from_fn(|k| {
                let mid = (a[k] + b[k]) / 2.0;
                mid + thin * (p[v][k] - mid)
            })
        })
        .collect();
    TriangleMesh::new(positions, torus.faces().to_vec()).expect("moving vertices keeps the faces")
}

/// `cot α + cot β` of every edge (`E` entries, one cotangent on a boundary edge), computed from
/// the 3D corner angles.
pub fn cotangent_sums(mesh: &TriangleMesh) -> Vec<f64> {
    let mut sums = vec![0.0; mesh.edge_count()];
    for (t, edges) in mesh.face_edges().iter().enumerate() {
        for (c, &e) in edges.iter().enumerate() {
            sums[e] += corner_cotangent(mesh, t, c);
        }
    }
    sums
}

/// Cotangent of the angle at corner `c` of face `t`, from 3D positions (independent of
/// `tvf-discretizations`).
pub fn corner_cotangent(mesh: &TriangleMesh, t: usize, c: usize) -> f64 {
    let o = mesh.corner(t, c);
    let u = sub(mesh.corner(t, (c + 1) % 3), o);
    let v = sub(mesh.corner(t, (c + 2) % 3), o);
    dot(u, v) / norm(cross(u, v))
}

/// Whether every edge has `cot α + cot β >` [`DELAUNAY_TOLERANCE`] (what DEC needs).
pub fn is_delaunay(mesh: &TriangleMesh) -> bool {
    cotangent_sums(mesh).iter().all(|&s| s > DELAUNAY_TOLERANCE)
}

/// Lawson flips on the surface: while some interior edge has `cot α + cot β ≤`
/// [`DELAUNAY_TOLERANCE`], the worst one
/// is replaced by the other diagonal of its two faces (vertices stay put, so the surface changes
/// slightly where it is not flat). Panics if a flip would break the mesh or if 10·E flips do not
/// make it Delaunay; meant for the small generated meshes of the corpus.
pub fn delaunay_flips(mesh: &TriangleMesh) -> TriangleMesh {
    try_delaunay_flips(mesh).unwrap_or_else(|e| panic!("{e}"))
}

/// [`delaunay_flips`], with an error instead of a panic when a flip would break the mesh (e.g.
/// two faces that would share both vertices of the new diagonal) or when 10·E flips do not make
/// it Delaunay (the mesh strategies reject such draws). The flips are kept up to date edge by
/// edge ([`LawsonFlips`]: the same flips as recomputing every sum after each).
pub fn try_delaunay_flips(mesh: &TriangleMesh) -> Result<TriangleMesh, String> {
    let mut flips = LawsonFlips::new(mesh);
    for _ in 0..10 * mesh.edge_count() {
        let Some(edge) = flips.worst() else {
            return flips.into_mesh();
        };
        flips.flip(edge)?;
    }
    Err("Lawson flips did not converge".to_string())
}
