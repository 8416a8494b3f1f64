//! The demo's inputs, made from the mesh alone (so that `--mesh` works on any mesh): a
//! smooth test field with all three Hodge parts, seeded noise, and constraint positions spread
//! over the surface.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::geometry::{cross, dot, normalize};
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

/// A smooth field with integrable, co-integrable and harmonic content (`n1` coefficients): `grad f + J grad g + P(ω × p)` with `f = sin(2x + z)` on the potential nodes,
/// `g = cos(3y − z)` on the co-potential nodes (normalised coordinates) and the tangential
/// projection `P` of the rotation about the coordinate axis along which the mesh is thinnest
/// (mostly harmonic on a torus around that axis).
pub fn smooth_field<H: HodgeComplex + ?Sized>(complex: &H, mesh: &SurfaceMesh) -> Vec<f64> {
    let f: Vec<f64> = normalised(mesh, &complex.potential_nodes().positions)
        .iter()
        .map(|q| (2.0 * q[0] + q[2]).sin())
        .collect();
    let g: Vec<f64> = normalised(mesh, &complex.co_potential_nodes().positions)
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
        .require_sampling()
        .and_then(|sampling| sampling.from_face_vectors(&rotation))
        .map(|p| p.field)
        .unwrap_or_else(|_| vec![0.0; complex.field_dimension()]);
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

/// Faces seen near the given points of the picture: `targets` are positions in the image plane
/// of a camera looking along `−to_eye` (with world +y up), in units of the half-extent of the
/// faces turned towards the camera (normal · to_eye > 0.5) about their centre. For each target
/// the facing face whose centroid projects closest is chosen (ties go to the face nearer the
/// camera), without repeating faces.
pub fn faces_at_screen_points(
    mesh: &SurfaceMesh,
    to_eye: [f64; 3],
    targets: &[[f64; 2]],
) -> Vec<usize> {
    let p = mesh.positions();
    let right = normalize(cross([0.0, 1.0, 0.0], to_eye));
    let up = cross(to_eye, right);
    let facing: Vec<(usize, [f64; 3])> = mesh
        .faces()
        .iter()
        .enumerate()
        .filter(|&(t, _)| dot(mesh.face_normal(t), to_eye) > 0.5)
        .map(|(t, f)| {
            (
                t,
                [
                    dot(
                        std::array::from_fn(|k| (p[f[0]][k] + p[f[1]][k] + p[f[2]][k]) / 3.0),
                        right,
                    ),
                    dot(
                        std::array::from_fn(|k| (p[f[0]][k] + p[f[1]][k] + p[f[2]][k]) / 3.0),
                        up,
                    ),
                    dot(
                        std::array::from_fn(|k| (p[f[0]][k] + p[f[1]][k] + p[f[2]][k]) / 3.0),
                        to_eye,
                    ),
                ],
            )
        })
        .collect();
    if facing.is_empty() {
        return Vec::new();
    }
    let range = |k: usize| {
        let lo = facing.iter().map(|f| f.1[k]).fold(f64::INFINITY, f64::min);
        let hi = facing
            .iter()
            .map(|f| f.1[k])
            .fold(f64::NEG_INFINITY, f64::max);
        (0.5 * (lo + hi), (0.5 * (hi - lo)).max(1e-300))
    };
    let (x, y, z) = (range(0), range(1), range(2));
    let mut chosen: Vec<usize> = Vec::new();
    for target in targets {
        let best = facing
            .iter()
            .filter(|(t, _)| !chosen.contains(t))
            .map(|&(t, q)| {
                let dx = (q[0] - x.0) / x.1 - target[0];
                let dy = (q[1] - y.0) / y.1 - target[1];
                // Nearer the camera is better (z grows towards the eye).
                let depth = 0.05 * (1.0 - (q[2] - z.0) / z.1);
                (t, (dx * dx + dy * dy).sqrt() + depth)
            })
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((t, _)) = best {
            chosen.push(t);
        }
    }
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::generate::torus;

    #[test]
    fn screen_points_pick_distinct_facing_faces_in_the_right_places() {
        let mesh = torus(1.0, 0.4, 24, 12).unwrap();
        // Looking down the z axis (to_eye = +z): right = y × z = +x and up = z × x = +y.
        let to_eye = [0.0, 0.0, 1.0];
        let targets = [[-0.9, 0.0], [0.9, 0.0], [0.0, 0.9], [0.0, -0.9]];
        let faces = faces_at_screen_points(&mesh, to_eye, &targets);
        assert_eq!(faces.len(), 4);
        let centroid = |t: usize| {
            let f = mesh.faces()[t];
            let p = mesh.positions();
            std::array::from_fn::<f64, 3, _>(|k| (p[f[0]][k] + p[f[1]][k] + p[f[2]][k]) / 3.0)
        };
        for (&t, target) in faces.iter().zip(&targets) {
            assert!(dot(mesh.face_normal(t), to_eye) > 0.5);
            let c = centroid(t);
            assert!(
                c[0] * target[0] >= 0.0 && c[1] * target[1] >= 0.0,
                "face {t} at {c:?}"
            );
            assert!((c[0] * c[0] + c[1] * c[1]).sqrt() > 0.8);
        }
    }

    #[test]
    fn noise_is_seeded_and_bounded() {
        assert_eq!(noise(10, 0.5, 1), noise(10, 0.5, 1));
        assert_ne!(noise(10, 0.5, 1), noise(10, 0.5, 2));
        assert!(noise(100, 0.5, 3).iter().all(|x| x.abs() <= 0.5));
    }
}
