//! Self-contained OBJ reader and P1 (cotan) / Crouzeix–Raviart stiffness–mass assembly for
//! the solver examples and tests (tvf-solvers cannot depend on the mesh crates).
//! Conventions follow `docs/conventions.md`: `S_ij = −(cot α + cot β)/2`, `M_ii = Σ A_t/3`,
//! CR basis `1 − 2φ_c` on the edge opposite corner `c`, `M*_ee = Σ A_t/3`.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A sparse stiffness matrix with its lumped (diagonal) mass.
pub struct StiffnessMass {
    pub stiffness: sprs::CsMat<f64>,
    pub mass: Vec<f64>,
}

/// `../shared/meshes/NAME` relative to the repository root, if it exists.
pub fn shared_mesh(name: &str) -> Option<PathBuf> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/meshes")
        .join(name);
    path.exists().then_some(path)
}

/// Vertex positions and triangles.
pub type Triangles = (Vec<[f64; 3]>, Vec<[usize; 3]>);

/// Vertex positions and triangles of an OBJ file (`v` and `f` lines, 1-based indices).
pub fn read_obj(path: &Path) -> Result<Triangles, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let mut parts = line.split_whitespace();
        match parts.next() {
            Some("v") => {
                let coords: Vec<f64> = parts
                    .take(3)
                    .map(|s| {
                        s.parse()
                            .map_err(|_| format!("{}:{}: bad vertex", path.display(), number + 1))
                    })
                    .collect::<Result<_, _>>()?;
                if coords.len() != 3 {
                    return Err(format!(
                        "{}:{}: vertex needs 3 coordinates",
                        path.display(),
                        number + 1
                    ));
                }
                positions.push([coords[0], coords[1], coords[2]]);
            }
            Some("f") => {
                let ids: Vec<usize> = parts
                    .map(|s| {
                        s.split('/')
                            .next()
                            .unwrap_or("")
                            .parse::<usize>()
                            .map_err(|_| format!("{}:{}: bad face", path.display(), number + 1))
                    })
                    .collect::<Result<_, _>>()?;
                if ids.len() != 3 || ids.contains(&0) {
                    return Err(format!(
                        "{}:{}: only 1-based triangles are supported",
                        path.display(),
                        number + 1
                    ));
                }
                faces.push([ids[0] - 1, ids[1] - 1, ids[2] - 1]);
            }
            _ => {}
        }
    }
    Ok((positions, faces))
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Area and the cotangents of the three corner angles of a triangle.
fn face_geometry(p: [[f64; 3]; 3]) -> (f64, [f64; 3]) {
    let double_area = dot(
        cross(sub(p[1], p[0]), sub(p[2], p[0])),
        cross(sub(p[1], p[0]), sub(p[2], p[0])),
    )
    .sqrt();
    let mut cot = [0.0; 3];
    for c in 0..3 {
        let u = sub(p[(c + 1) % 3], p[c]);
        let v = sub(p[(c + 2) % 3], p[c]);
        cot[c] = dot(u, v) / double_area;
    }
    (0.5 * double_area, cot)
}

/// Cotan stiffness `S_c` (V × V) and barycentric lumped mass.
pub fn cotan(positions: &[[f64; 3]], faces: &[[usize; 3]]) -> StiffnessMass {
    let n = positions.len();
    let mut t = sprs::TriMat::new((n, n));
    let mut mass = vec![0.0; n];
    for f in faces {
        let (area, cot) = face_geometry([positions[f[0]], positions[f[1]], positions[f[2]]]);
        for c in 0..3 {
            let (i, j) = (f[(c + 1) % 3], f[(c + 2) % 3]);
            let w = 0.5 * cot[c];
            t.add_triplet(i, j, -w);
            t.add_triplet(j, i, -w);
            t.add_triplet(i, i, w);
            t.add_triplet(j, j, w);
            mass[f[c]] += area / 3.0;
        }
    }
    StiffnessMass {
        stiffness: t.to_csc(),
        mass,
    }
}

/// Crouzeix–Raviart stiffness `S*_c` (E × E) and lumped mass `M*_ee = Σ A_t/3`.
pub fn crouzeix_raviart(positions: &[[f64; 3]], faces: &[[usize; 3]]) -> StiffnessMass {
    let mut edge_index: HashMap<(usize, usize), usize> = HashMap::new();
    let mut face_edges = Vec::with_capacity(faces.len());
    for f in faces {
        let mut e = [0usize; 3];
        for c in 0..3 {
            let (a, b) = (f[(c + 1) % 3], f[(c + 2) % 3]);
            let key = (a.min(b), a.max(b));
            let next = edge_index.len();
            e[c] = *edge_index.entry(key).or_insert(next);
        }
        face_edges.push(e);
    }
    let m = edge_index.len();
    let mut t = sprs::TriMat::new((m, m));
    let mut mass = vec![0.0; m];
    for (f, e) in faces.iter().zip(&face_edges) {
        let (area, cot) = face_geometry([positions[f[0]], positions[f[1]], positions[f[2]]]);
        for c in 0..3 {
            // 4 A ∇φ_c·∇φ_d = −2 cot(θ_k) for c ≠ d, k the third corner
            let d = (c + 1) % 3;
            let k = (c + 2) % 3;
            let w = 2.0 * cot[k];
            t.add_triplet(e[c], e[d], -w);
            t.add_triplet(e[d], e[c], -w);
            t.add_triplet(e[c], e[c], w);
            t.add_triplet(e[d], e[d], w);
            mass[e[c]] += area / 3.0;
        }
    }
    StiffnessMass {
        stiffness: t.to_csc(),
        mass,
    }
}

/// A `nx × ny` grid of unit squares in the plane, each cut into two triangles along a diagonal
/// whose direction alternates, with vertices displaced by a deterministic jitter of up to
/// `jitter` (so that the spectrum has no symmetric multiplicities): positions and triangles
/// (counter-clockwise).
pub fn grid(nx: usize, ny: usize, jitter: f64) -> Triangles {
    let id = |i: usize, j: usize| i + (nx + 1) * j;
    let wobble = |k: usize, salt: usize| {
        let h = (k.wrapping_mul(2_654_435_761).wrapping_add(salt * 40_503)) % 10_007;
        jitter * (h as f64 / 10_007.0 - 0.5)
    };
    let mut positions = Vec::with_capacity((nx + 1) * (ny + 1));
    for j in 0..=ny {
        for i in 0..=nx {
            let k = id(i, j);
            let inner = i > 0 && i < nx && j > 0 && j < ny;
            let (dx, dy) = if inner {
                (wobble(k, 1), wobble(k, 2))
            } else {
                (0.0, 0.0)
            };
            positions.push([i as f64 + dx, j as f64 + dy, 0.0]);
        }
    }
    let mut faces = Vec::with_capacity(2 * nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                faces.push([a, b, c]);
                faces.push([a, c, d]);
            } else {
                faces.push([a, b, d]);
                faces.push([b, c, d]);
            }
        }
    }
    (positions, faces)
}

/// The consistent P1 mass `M_ij = Σ_T (|T|/12)(1 + δ_ij)` over the triangles `T` holding
/// vertices `i` and `j` (V × V, SPD, full storage).
pub fn consistent_mass(positions: &[[f64; 3]], faces: &[[usize; 3]]) -> sprs::CsMat<f64> {
    let n = positions.len();
    let mut t = sprs::TriMat::new((n, n));
    for f in faces {
        let (area, _) = face_geometry([positions[f[0]], positions[f[1]], positions[f[2]]]);
        for a in 0..3 {
            for b in 0..3 {
                let factor = if a == b { 2.0 } else { 1.0 };
                t.add_triplet(f[a], f[b], factor * area / 12.0);
            }
        }
    }
    t.to_csc()
}

/// The Whitney discretization of 1-forms on the edges of a triangle mesh.
pub struct Whitney {
    /// Edges `(low, high)` (vertex indices, oriented low → high).
    pub edges: Vec<[usize; 2]>,
    /// `M1[e, f] = Σ_T ∫_T ⟨W_e, W_f⟩` with `W_(p,q) = λ_p ∇λ_q − λ_q ∇λ_p` (E × E, SPD).
    pub mass: sprs::CsMat<f64>,
    /// The signed face–edge incidence `d1` (F × E): `+1` where the face's counter-clockwise
    /// boundary runs along the edge's orientation, `−1` against it.
    pub d1: sprs::CsMat<f64>,
    /// Face areas (the diagonal face mass `N`).
    pub face_areas: Vec<f64>,
}

/// The Whitney 1-form mass, the face–edge incidence and the face areas of a triangle mesh
/// (`∫_T λ_a λ_b = |T|(1 + δ_ab)/12`, `⟨∇λ_a, ∇λ_b⟩ = (e_a · e_b)/(4|T|²)` with `e_a` the
/// edge vector opposite corner `a`, taken cyclically).
pub fn whitney(positions: &[[f64; 3]], faces: &[[usize; 3]]) -> Whitney {
    let mut edge_index: HashMap<(usize, usize), usize> = HashMap::new();
    let mut edges = Vec::new();
    let mut face_edges = Vec::with_capacity(faces.len());
    for f in faces {
        // Edge c runs from corner c to corner c + 1.
        let e: [(usize, f64); 3] = std::array::from_fn(|c| {
            let (a, b) = (f[c], f[(c + 1) % 3]);
            let key = (a.min(b), a.max(b));
            let index = *edge_index.entry(key).or_insert_with(|| {
                edges.push([key.0, key.1]);
                edges.len() - 1
            });
            (index, if a < b { 1.0 } else { -1.0 })
        });
        face_edges.push(e);
    }
    let (ne, nf) = (edges.len(), faces.len());
    let mut mass = sprs::TriMat::new((ne, ne));
    let mut d1 = sprs::TriMat::new((nf, ne));
    let mut face_areas = Vec::with_capacity(nf);
    for (face, (f, e)) in faces.iter().zip(&face_edges).enumerate() {
        let p = [positions[f[0]], positions[f[1]], positions[f[2]]];
        let (area, _) = face_geometry(p);
        face_areas.push(area);
        let opposite: [[f64; 3]; 3] = std::array::from_fn(|a| sub(p[(a + 2) % 3], p[(a + 1) % 3]));
        let grad = |a: usize, b: usize| dot(opposite[a], opposite[b]) / (4.0 * area * area);
        let lambda = |a: usize, b: usize| area * if a == b { 2.0 } else { 1.0 } / 12.0;
        // ∫ ⟨λ_p ∇λ_q − λ_q ∇λ_p, λ_r ∇λ_s − λ_s ∇λ_r⟩ for local edges (p, q), (r, s).
        let inner = |(p, q): (usize, usize), (r, s): (usize, usize)| {
            lambda(p, r) * grad(q, s) - lambda(p, s) * grad(q, r) - lambda(q, r) * grad(p, s)
                + lambda(q, s) * grad(p, r)
        };
        for (c, &(ec, sc)) in e.iter().enumerate() {
            d1.add_triplet(face, ec, sc);
            for (d, &(ed, sd)) in e.iter().enumerate() {
                let value = inner((c, (c + 1) % 3), (d, (d + 1) % 3));
                mass.add_triplet(ec, ed, sc * sd * value);
            }
        }
    }
    Whitney {
        edges,
        mass: mass.to_csc(),
        d1: d1.to_csr(),
        face_areas,
    }
}

/// A closed "pillow": two copies of the jittered `nx × ny` grid glued along their boundary,
/// the top one bulging to `+height`, the bottom one (faces reversed) to `−height`: a closed
/// orientable surface (one constant in the kernels of the vertex Laplacian and of `d1ᵀ`).
/// `nx` and `ny` must be even: then the diagonal of each corner square runs through the
/// corner, and no triangle has all its vertices on the seam (such a triangle would be glued to
/// its mirror image along all three edges, a closed surface of its own).
pub fn pillow(nx: usize, ny: usize, jitter: f64, height: f64) -> Triangles {
    assert!(nx & 1 == 0 && ny & 1 == 0, "pillow: nx and ny must be even");
    let (mut positions, top_faces) = grid(nx, ny, jitter);
    let id = |i: usize, j: usize| i + (nx + 1) * j;
    let bulge = |p: [f64; 3]| {
        let (u, v) = (p[0] / nx as f64, p[1] / ny as f64);
        height * (std::f64::consts::PI * u).sin() * (std::f64::consts::PI * v).sin()
    };
    let top = positions.len();
    let mut bottom = vec![usize::MAX; top];
    for j in 0..=ny {
        for i in 0..=nx {
            let k = id(i, j);
            if i == 0 || i == nx || j == 0 || j == ny {
                bottom[k] = k;
            } else {
                let p = positions[k];
                bottom[k] = positions.len();
                positions.push([p[0], p[1], -bulge(p)]);
            }
        }
    }
    for p in positions.iter_mut().take(top) {
        p[2] = bulge(*p);
    }
    let mut faces = top_faces.clone();
    faces.extend(
        top_faces
            .iter()
            .map(|f| [bottom[f[0]], bottom[f[2]], bottom[f[1]]]),
    );
    (positions, faces)
}
