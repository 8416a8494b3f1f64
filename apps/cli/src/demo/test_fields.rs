//! The demo's inputs, made from the mesh alone (so that `--mesh` works on any closed mesh): a
//! smooth test field with all three Hodge parts, seeded noise, and constraint positions spread
//! over the surface.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::discretization::{FieldSpace, FunctionSpace, HodgeComplex, HodgeOperators};
use tvf_core::geometry::{dot, norm, sub};
use tvf_core::SurfaceMesh;
use tvf_render::bounding_box;

/// Positions normalised to the bounding box: centre at 0, largest half-extent 1.
fn normalised(mesh: &SurfaceMesh, points: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let (lo, hi) = bounding_box(mesh.positions());
    let centre: [f64; 3] = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
    let half = (0..3).map(|k| 0.5 * (hi[k] - lo[k])).fold(1e-300, f64::max);
    points
        .iter()
        .map(|p| std::array::from_fn(|k| (p[k] - centre[k]) / half))
        .collect()
}

/// A smooth field with integrable, co-integrable and harmonic content (`2F` coefficients,
/// pointwise): `grad f + J grad g + P(ω × p)` with `f = sin(2x + z)` on the potential nodes,
/// `g = cos(3y − z)` on the co-potential nodes (normalised coordinates) and the tangential
/// projection `P` of the rotation about the coordinate axis along which the mesh is thinnest
/// (mostly harmonic on a torus around that axis).
pub fn smooth_field<H: HodgeComplex>(complex: &H, mesh: &SurfaceMesh) -> Vec<f64> {
    let f: Vec<f64> = normalised(mesh, &complex.potentials().node_positions())
        .iter()
        .map(|q| (2.0 * q[0] + q[2]).sin())
        .collect();
    let g: Vec<f64> = normalised(mesh, &complex.co_potentials().node_positions())
        .iter()
        .map(|q| (3.0 * q[1] - q[2]).cos())
        .collect();
    let centroids: Vec<[f64; 3]> = mesh
        .faces()
        .iter()
        .map(|f| {
            let p = mesh.positions();
            std::array::from_fn(|k| (p[f[0]][k] + p[f[1]][k] + p[f[2]][k]) / 3.0)
        })
        .collect();
    // The axis of the swirl: the direction of least extent (a torus's axis).
    let (lo, hi) = bounding_box(mesh.positions());
    let axis = (0..3)
        .min_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
        .unwrap_or(2);
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let rotation: Vec<[f64; 3]> = normalised(mesh, &centroids)
        .iter()
        .map(|q| {
            let mut r = [0.0; 3];
            r[i] = -q[j];
            r[j] = q[i];
            r
        })
        .collect();
    let swirl = complex
        .fields()
        .from_vectors(&rotation)
        .map(|p| p.field)
        .unwrap_or_else(|_| vec![0.0; complex.fields().dimension()]);
    let a = complex.gradient_field(&f);
    let b = complex.co_gradient_field(&g);
    // Scale the potentials' parts to unit RMS each so that no part dominates the picture.
    let rms = |x: &[f64]| {
        (complex.field_inner(x, x) / mesh.total_area())
            .sqrt()
            .max(1e-300)
    };
    let (ra, rb, rs) = (rms(&a), rms(&b), rms(&swirl));
    a.iter()
        .zip(&b)
        .zip(&swirl)
        .map(|((x, y), z)| x / ra + y / rb + z / rs)
        .collect()
}

/// Seeded noise: an independent random tangent vector per face, each coordinate uniform in
/// `[−amplitude, amplitude]` (`2F` coefficients in the face frames).
pub fn noise(dimension: usize, amplitude: f64, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..dimension)
        .map(|_| amplitude * rng.random_range(-1.0..1.0))
        .collect()
}

/// `count` faces spread over the surface by farthest-point sampling of face centroids, among the
/// faces turned towards `to_eye` (normal · to_eye > 0.5, so that they are seen in pictures; all
/// faces if too few are), starting at the candidate with the largest x coordinate.
pub fn spread_faces(mesh: &SurfaceMesh, count: usize, to_eye: [f64; 3]) -> Vec<usize> {
    let p = mesh.positions();
    let centroids: Vec<[f64; 3]> = mesh
        .faces()
        .iter()
        .map(|f| std::array::from_fn(|k| (p[f[0]][k] + p[f[1]][k] + p[f[2]][k]) / 3.0))
        .collect();
    let mut candidates: Vec<usize> = (0..centroids.len())
        .filter(|&t| dot(mesh.face_normal(t), to_eye) > 0.5)
        .collect();
    if candidates.len() < count {
        candidates = (0..centroids.len()).collect();
    }
    let Some(&first) = candidates
        .iter()
        .max_by(|&&a, &&b| centroids[a][0].total_cmp(&centroids[b][0]))
    else {
        return Vec::new();
    };
    let mut chosen = vec![first];
    let mut distance: Vec<f64> = candidates
        .iter()
        .map(|&t| norm(sub(centroids[t], centroids[first])))
        .collect();
    while chosen.len() < count.min(candidates.len()) {
        let Some(next) = (0..candidates.len()).max_by(|&a, &b| distance[a].total_cmp(&distance[b]))
        else {
            break;
        };
        let face = candidates[next];
        chosen.push(face);
        for (d, &t) in distance.iter_mut().zip(&candidates) {
            *d = d.min(norm(sub(centroids[t], centroids[face])));
        }
    }
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::generate::torus;

    #[test]
    fn spread_faces_are_distinct_and_far_apart() {
        let mesh = torus(1.0, 0.4, 24, 12).unwrap();
        let up = [0.0, 0.0, 1.0];
        let faces = spread_faces(&mesh, 6, up);
        assert_eq!(faces.len(), 6);
        assert!(faces.iter().all(|&t| dot(mesh.face_normal(t), up) > 0.5));
        let mut sorted = faces.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), 6);
        let c = |t: usize| {
            let f = mesh.faces()[t];
            let p = mesh.positions();
            std::array::from_fn::<f64, 3, _>(|k| (p[f[0]][k] + p[f[1]][k] + p[f[2]][k]) / 3.0)
        };
        for (i, &a) in faces.iter().enumerate() {
            for &b in &faces[i + 1..] {
                assert!(norm(sub(c(a), c(b))) > 0.5, "faces {a} and {b} are close");
            }
        }
    }

    #[test]
    fn noise_is_seeded_and_bounded() {
        assert_eq!(noise(10, 0.5, 1), noise(10, 0.5, 1));
        assert_ne!(noise(10, 0.5, 1), noise(10, 0.5, 2));
        assert!(noise(100, 0.5, 3).iter().all(|x| x.abs() <= 0.5));
    }
}
