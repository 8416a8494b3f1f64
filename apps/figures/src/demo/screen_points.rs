//! Where the demo puts its constraints: faces seen near given points of the picture, so that
//! `--mesh` works on any mesh.

use tvf_core::geometry::{cross, dot, normalize};
use tvf_core::SurfaceMesh;

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
    let right = normalize(cross([0.0, 1.0, 0.0], to_eye));
    let up = cross(to_eye, right);
    let facing: Vec<(usize, [f64; 3])> = (0..mesh.face_count())
        .filter(|&t| dot(mesh.face_normal(t), to_eye) > 0.5)
        .map(|t| {
            let centroid = mesh.face_centroid(t);
            (
                t,
                [
                    dot(centroid, right),
                    dot(centroid, up),
                    dot(centroid, to_eye),
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
        let mesh = tvf_core::SurfaceMesh::from(torus(1.0, 0.4, 24, 12).unwrap());
        // Looking down the z axis (to_eye = +z): right = y × z = +x and up = z × x = +y.
        let to_eye = [0.0, 0.0, 1.0];
        let targets = [[-0.9, 0.0], [0.9, 0.0], [0.0, 0.9], [0.0, -0.9]];
        let faces = faces_at_screen_points(&mesh, to_eye, &targets);
        assert_eq!(faces.len(), 4);
        for (&t, target) in faces.iter().zip(&targets) {
            assert!(dot(mesh.face_normal(t), to_eye) > 0.5);
            let c = mesh.face_centroid(t);
            assert!(
                c[0] * target[0] >= 0.0 && c[1] * target[1] >= 0.0,
                "face {t} at {c:?}"
            );
            assert!((c[0] * c[0] + c[1] * c[1]).sqrt() > 0.8);
        }
    }
}
