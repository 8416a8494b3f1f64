//! Fur: hair strands rooted on the surface that follow a tangent field across faces and
//! rise off the surface along the normal as they grow (the paper's Figure 5).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::geometry::{add, norm, scale, sub};
use tvf_core::{SurfaceMesh, TriangleMesh};

use crate::camera::bounding_box;
use crate::error::{check_face_count, check_finite_vectors, RenderError};
use crate::streamlines::FaceWalker;
use crate::surface::{point_at, tangential};

/// How many strands, how long and how steep.
#[derive(Debug, Clone, PartialEq)]
pub struct FurOptions {
    /// Number of strands; roots are spread over the surface proportionally to face area.
    pub strand_count: usize,
    /// Length of a strand where the field is strongest, as a fraction of the bounding-box
    /// diagonal; elsewhere proportional to the field's tangential magnitude.
    pub length: f64,
    /// Height gained over the whole strand, as a fraction of its length; the lift grows
    /// quadratically along the strand, so strands leave the surface tangentially.
    pub lift: f64,
    /// Points per strand (at least 2), evenly spaced in arc length.
    pub points_per_strand: usize,
    /// Seed of the root positions.
    pub seed: u64,
}

impl Default for FurOptions {
    fn default() -> Self {
        FurOptions {
            strand_count: 20_000,
            length: 0.04,
            lift: 0.35,
            points_per_strand: 8,
            seed: 5,
        }
    }
}

/// Grows fur on `mesh` along `face_vectors` (one vector per face, `F` entries; the tangential
/// part is used): one polyline per strand with a root on the surface, following the field's
/// streamline for a length proportional to the field magnitude at the root, then lifted
/// along the face normals by `lift · L · (s/L)²` at arc length `s`. Strands at faces
/// where the field vanishes are left out. Deterministic for a given seed. A polygon mesh grows
/// on its display triangulation, each triangle with its polygon's vector.
pub fn grow_fur(
    mesh: &SurfaceMesh,
    face_vectors: &[[f64; 3]],
    options: &FurOptions,
) -> Result<Vec<Vec<[f64; 3]>>, RenderError> {
    check_face_count("fur field", mesh.face_count(), face_vectors.len())?;
    let face_vectors = &mesh.on_display(face_vectors);
    let mesh = mesh.display();
    check_finite_vectors("fur field", face_vectors)?;
    if options.points_per_strand < 2
        || options.length.is_nan()
        || options.length <= 0.0
        || !options.lift.is_finite()
    {
        return Err(RenderError::InvalidOption {
            name: "fur points_per_strand / length / lift",
            value: format!(
                "{} / {} / {}",
                options.points_per_strand, options.length, options.lift
            ),
            reason: "need at least 2 points per strand, a positive length and a finite lift",
        });
    }
    let magnitudes: Vec<f64> = face_vectors
        .iter()
        .enumerate()
        .map(|(t, &v)| norm(tangential(v, mesh.face_normal(t))))
        .collect();
    let largest = magnitudes.iter().copied().fold(0.0, f64::max);
    if largest <= 0.0 {
        return Ok(Vec::new());
    }
    let (lo, hi) = bounding_box(mesh.positions());
    let full_length = options.length * norm(sub(hi, lo));
    let walker = FaceWalker::new(mesh, face_vectors);
    let mut cumulative = Vec::with_capacity(mesh.face_count());
    let mut total = 0.0;
    for a in mesh.face_areas() {
        total += a;
        cumulative.push(total);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let mut strands = Vec::with_capacity(options.strand_count);
    for _ in 0..options.strand_count {
        let target = rng.random::<f64>() * total;
        let t = cumulative
            .partition_point(|&c| c < target)
            .min(mesh.face_count() - 1);
        let (a, b): (f64, f64) = (rng.random(), rng.random());
        let (a, b) = if a + b > 1.0 {
            (1.0 - a, 1.0 - b)
        } else {
            (a, b)
        };
        let length = full_length * magnitudes[t] / largest;
        if length <= 1e-9 * full_length {
            continue;
        }
        let root = point_at(mesh, t, [1.0 - a - b, a, b]);
        let path = walker.trace(t, root, 1.0, length, f64::INFINITY, &mut |_| true);
        if path.faces.is_empty() {
            continue;
        }
        strands.push(lift_resampled(mesh, &path.points, &path.faces, options));
    }
    Ok(strands)
}

/// Resamples the surface path evenly in arc length and lifts each sample along the normal
/// of the face it lies in.
fn lift_resampled(
    mesh: &TriangleMesh,
    points: &[[f64; 3]],
    faces: &[usize],
    options: &FurOptions,
) -> Vec<[f64; 3]> {
    let lengths: Vec<f64> = points.windows(2).map(|w| norm(sub(w[1], w[0]))).collect();
    let total: f64 = lengths.iter().sum();
    let n = options.points_per_strand;
    let mut out = Vec::with_capacity(n);
    let mut segment = 0;
    let mut before = 0.0;
    for k in 0..n {
        let s = total * k as f64 / (n - 1) as f64;
        while segment + 1 < lengths.len() && before + lengths[segment] < s {
            before += lengths[segment];
            segment += 1;
        }
        let f = if lengths[segment] > 0.0 {
            ((s - before) / lengths[segment]).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let on_surface = add(
            points[segment],
            scale(sub(points[segment + 1], points[segment]), f),
        );
        let u = if total > 0.0 { s / total } else { 0.0 };
        let height = options.lift * total * u * u;
        out.push(add(
            on_surface,
            scale(mesh.face_normal(faces[segment]), height),
        ));
    }
    out
}
