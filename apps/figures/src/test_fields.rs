//! The input fields of the experiments, made from the mesh alone (the paper's "custom" fields
//! are not published): a smooth field with all three Hodge parts, a designed (soft-constrained)
//! field, seeded noise, a field of many
//! small vortices (Figure 10) and a time-dependent field of moving sources and vortices (the
//! bumpy-torus sequence). All are `2F` pointwise face-frame coefficients of the given complex.

use crate::error::FigureError;
use crate::seeded_constraints::seeded_constraints;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::geometry::{dot, norm, sub};
use tvf_core::SurfaceMesh;
use tvf_design::{
    checked_residuals, default_regularization, ConstraintAssembler, FullSoftDesign, SoftOptions,
};
use tvf_render::bounding_box;

/// Centre of the bounding box and its largest half-extent.
fn frame_of(mesh: &SurfaceMesh) -> ([f64; 3], f64) {
    let (lo, hi) = bounding_box(mesh.positions());
    let centre = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
    let half = (0..3).map(|k| 0.5 * (hi[k] - lo[k])).fold(1e-300, f64::max);
    (centre, half)
}

/// Face centroids.
pub fn centroids(mesh: &SurfaceMesh) -> Vec<[f64; 3]> {
    (0..mesh.face_count())
        .map(|t| mesh.face_centroid(t))
        .collect()
}

/// The coordinate axis along which the mesh is thinnest (a torus's axis of revolution).
fn thinnest_axis(mesh: &SurfaceMesh) -> usize {
    let (lo, hi) = bounding_box(mesh.positions());
    (0..3)
        .min_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
        .unwrap_or(2)
}

/// Scales `x` to unit RMS magnitude (`‖x‖_{M_X}² / area = 1`); a zero field stays zero.
fn unit_rms<H: HodgeComplex + ?Sized>(complex: &H, area: f64, x: &mut [f64]) {
    let rms = (complex.field_inner(x, x) / area).sqrt();
    if rms > 0.0 {
        x.iter_mut().for_each(|v| *v /= rms);
    }
}

/// A smooth field `grad f + J grad g + P(swirl)`, each part scaled to unit RMS: `f` and `g` are
/// low-frequency trigonometric functions of the normalised coordinates on the potential and
/// co-potential nodes, `P(swirl)` the tangential projection of the rotation about the thinnest
/// axis (mostly harmonic on a torus around that axis).
pub fn smooth_field<H: HodgeComplex + ?Sized>(complex: &H, mesh: &SurfaceMesh) -> Vec<f64> {
    let (centre, half) = frame_of(mesh);
    let local = |p: [f64; 3]| -> [f64; 3] { std::array::from_fn(|k| (p[k] - centre[k]) / half) };
    let f: Vec<f64> = complex
        .potential_nodes()
        .positions
        .clone()
        .into_iter()
        .map(|p| {
            let q = local(p);
            (1.5 * q[0]).cos() * (q[1] + 0.5 * q[2]).sin()
        })
        .collect();
    let g: Vec<f64> = complex
        .co_potential_nodes()
        .positions
        .clone()
        .into_iter()
        .map(|p| {
            let q = local(p);
            (2.0 * q[1] - q[0]).sin() + 0.5 * (q[2] + 0.3).cos()
        })
        .collect();
    let axis = thinnest_axis(mesh);
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let swirl: Vec<[f64; 3]> = centroids(mesh)
        .into_iter()
        .map(|p| {
            let q = local(p);
            let mut r = [0.0; 3];
            r[i] = -q[j];
            r[j] = q[i];
            r
        })
        .collect();
    let area = mesh.total_area();
    let mut parts = [
        complex.gradient_field(&f),
        complex.co_gradient_field(&g),
        complex
            .require_sampling()
            .and_then(|sampling| sampling.from_face_vectors(&swirl))
            .map(|p| p.field)
            .unwrap_or_else(|_| vec![0.0; complex.field_dimension()]),
    ];
    for part in &mut parts {
        unit_rms(complex, area, part);
    }
    (0..parts[0].len())
        .map(|k| parts[0][k] + parts[1][k] + parts[2][k])
        .collect()
}

/// A designed field, as the paper's "custom" fields were made with its design tools: the full
/// soft design (Fisher et al.) with `constraints` seeded constraints (see
/// [`seeded_constraints`](crate::seeded_constraints::seeded_constraints)) and the biharmonic weight
/// `omega`, so that it is as smooth as the constraints allow; unit RMS. Any complex (diagonal or
/// consistent masses); a field or constraint residual that is not finite is an error.
pub fn designed_field(
    complex: &dyn HodgeComplex,
    mesh: &SurfaceMesh,
    constraints: usize,
    omega: f64,
    seed: u64,
) -> Result<Vec<f64>, FigureError> {
    let compiled = ConstraintAssembler::new(complex, mesh).compile_all(&seeded_constraints(
        mesh,
        complex,
        constraints,
        seed,
    ))?;
    let options = SoftOptions {
        omega,
        regularization: default_regularization(complex),
    };
    let design = FullSoftDesign::new(complex, options, compiled)?;
    let (mut field, _) = design.solve();
    checked_residuals(&field, design.constraints(), omega)?;
    unit_rms(complex, mesh.total_area(), &mut field);
    Ok(field)
}

/// Seeded noise: every face-frame coordinate uniform in `[−amplitude, amplitude]`.
pub fn noise(dimension: usize, amplitude: f64, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..dimension)
        .map(|_| amplitude * rng.random_range(-1.0..1.0))
        .collect()
}

/// Seeded noise as a field of `complex`: on every face a tangent vector whose two frame
/// coordinates are uniform in `[−amplitude, amplitude]`, sampled into the complex's
/// coefficients (for face fields exactly those coordinates).
pub fn tangent_noise(
    complex: &dyn HodgeComplex,
    amplitude: f64,
    seed: u64,
) -> Result<Vec<f64>, FigureError> {
    let sampling = complex.require_sampling()?;
    let coordinates = noise(2 * sampling.face_count(), amplitude, seed);
    let vectors: Vec<[f64; 3]> = coordinates
        .chunks_exact(2)
        .enumerate()
        .map(|(t, ab)| {
            let [e1, e2] = sampling.frame(t);
            std::array::from_fn(|k| ab[0] * e1[k] + ab[1] * e2[k])
        })
        .collect();
    Ok(sampling.from_face_vectors(&vectors)?.field)
}

/// `count` face centroids spread by farthest-point sampling (Euclidean), starting at face 0.
pub fn spread_points(mesh: &SurfaceMesh, count: usize) -> Vec<[f64; 3]> {
    let c = centroids(mesh);
    if c.is_empty() {
        return Vec::new();
    }
    let mut chosen = vec![c[0]];
    let mut distance: Vec<f64> = c.iter().map(|p| norm(sub(*p, c[0]))).collect();
    while chosen.len() < count.min(c.len()) {
        let (far, _) = distance
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(b.1))
            .unwrap_or((0, &0.0));
        let q = c[far];
        chosen.push(q);
        distance
            .par_iter_mut()
            .zip(&c)
            .for_each(|(d, p)| *d = d.min(norm(sub(*p, q))));
    }
    chosen
}

/// A Gaussian bump `Σ s_i exp(−|x − c_i|² / (2σ²))` at the given points (cut off at 5σ).
pub fn gaussian_sum(points: &[[f64; 3]], centres: &[([f64; 3], f64)], sigma: f64) -> Vec<f64> {
    let cutoff = 25.0 * sigma * sigma;
    let scale = -0.5 / (sigma * sigma);
    points
        .par_iter()
        .map(|p| {
            centres
                .iter()
                .map(|(c, s)| {
                    let d = sub(*p, *c);
                    let r2 = dot(d, d);
                    if r2 < cutoff {
                        s * (scale * r2).exp()
                    } else {
                        0.0
                    }
                })
                .sum()
        })
        .collect()
}

/// Figure 10's field: `count` small vortices (rotated gradients of Gaussian bumps of width a
/// quarter of the mean spacing, spread by farthest-point sampling, seeded random strengths
/// `±(0.5..1)`), unit RMS.
pub fn vortex_field<H: HodgeComplex + ?Sized>(
    complex: &H,
    mesh: &SurfaceMesh,
    count: usize,
    seed: u64,
) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let area = mesh.total_area();
    let spacing = (area / count.max(1) as f64).sqrt();
    let centres: Vec<([f64; 3], f64)> = spread_points(mesh, count)
        .into_iter()
        .map(|c| {
            let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
            (c, sign * rng.random_range(0.5..1.0))
        })
        .collect();
    let g = gaussian_sum(
        &complex.co_potential_nodes().positions.clone(),
        &centres,
        0.25 * spacing,
    );
    let mut field = complex.co_gradient_field(&g);
    unit_rms(complex, area, &mut field);
    field
}

/// The time-dependent field of the sequence experiment: sources and vortices whose centres
/// turn about the thinnest axis at different speeds, plus the rotation about that axis with an
/// amplitude oscillating in time.
#[derive(Debug, Clone)]
pub struct MovingFeatures {
    /// `(position at time 0, strength, turns per sequence)` of the sources and sinks.
    sources: Vec<([f64; 3], f64, f64)>,
    /// The same for the vortices.
    vortices: Vec<([f64; 3], f64, f64)>,
    /// Width of the bumps.
    sigma: f64,
    axis: usize,
    centre: [f64; 3],
    potential_nodes: Vec<[f64; 3]>,
    co_potential_nodes: Vec<[f64; 3]>,
    swirl: Vec<f64>,
}

impl MovingFeatures {
    /// `count` sources and `count` vortices at seeded random faces of `mesh`, bumps of width
    /// `width_fraction` times the largest half-extent.
    pub fn new<H: HodgeComplex + ?Sized>(
        complex: &H,
        mesh: &SurfaceMesh,
        count: usize,
        width_fraction: f64,
        seed: u64,
    ) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let c = centroids(mesh);
        let pick = |rng: &mut ChaCha8Rng| {
            let p = c[rng.random_range(0..c.len().max(1))];
            let strength = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
            let turns = [-2.0, -1.0, 1.0, 2.0][rng.random_range(0..4)];
            (p, strength, turns)
        };
        let sources = (0..count).map(|_| pick(&mut rng)).collect();
        let vortices = (0..count).map(|_| pick(&mut rng)).collect();
        let (centre, half) = frame_of(mesh);
        let axis = thinnest_axis(mesh);
        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
        let rotation: Vec<[f64; 3]> = c
            .iter()
            .map(|p| {
                let mut r = [0.0; 3];
                r[i] = -(p[j] - centre[j]) / half;
                r[j] = (p[i] - centre[i]) / half;
                r
            })
            .collect();
        let mut swirl = complex
            .require_sampling()
            .and_then(|sampling| sampling.from_face_vectors(&rotation))
            .map(|p| p.field)
            .unwrap_or_else(|_| vec![0.0; complex.field_dimension()]);
        unit_rms(complex, mesh.total_area(), &mut swirl);
        Self {
            sources,
            vortices,
            sigma: width_fraction * half,
            axis,
            centre,
            potential_nodes: complex.potential_nodes().positions.clone(),
            co_potential_nodes: complex.co_potential_nodes().positions.clone(),
            swirl,
        }
    }

    /// `p` turned by `angle` about the thinnest axis through the bounding-box centre.
    fn turned(&self, p: [f64; 3], angle: f64) -> [f64; 3] {
        let (i, j) = ((self.axis + 1) % 3, (self.axis + 2) % 3);
        let (s, c) = angle.sin_cos();
        let (x, y) = (p[i] - self.centre[i], p[j] - self.centre[j]);
        let mut q = p;
        q[i] = self.centre[i] + c * x - s * y;
        q[j] = self.centre[j] + s * x + c * y;
        q
    }

    /// The field at time `t ∈ [0, 1]` (the whole sequence).
    pub fn frame<H: HodgeComplex + ?Sized>(&self, complex: &H, t: f64) -> Vec<f64> {
        let at = |features: &[([f64; 3], f64, f64)]| -> Vec<([f64; 3], f64)> {
            features
                .iter()
                .map(|&(p, s, turns)| (self.turned(p, std::f64::consts::TAU * turns * t), s))
                .collect()
        };
        let f = gaussian_sum(&self.potential_nodes, &at(&self.sources), self.sigma);
        let g = gaussian_sum(&self.co_potential_nodes, &at(&self.vortices), self.sigma);
        let a = complex.gradient_field(&f);
        let b = complex.co_gradient_field(&g);
        let amplitude = (std::f64::consts::TAU * t).cos();
        (0..a.len())
            .map(|k| (a[k] + b[k]) * self.sigma + amplitude * self.swirl[k])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_is_seeded_and_bounded() {
        assert_eq!(noise(10, 0.5, 1), noise(10, 0.5, 1));
        assert_ne!(noise(10, 0.5, 1), noise(10, 0.5, 2));
        assert!(noise(100, 0.5, 3).iter().all(|x| x.abs() <= 0.5));
    }
    use tvf_core::generate::torus;
    use tvf_discretizations::{catalog_entry, DEFAULT_DISCRETIZATION};

    #[test]
    fn fields_are_seeded_finite_and_unit_rms() {
        let mesh = SurfaceMesh::from(torus(1.0, 0.4, 24, 12).unwrap());
        let boxed = catalog_entry(DEFAULT_DISCRETIZATION)
            .unwrap()
            .build(&mesh)
            .unwrap();
        let complex = boxed.as_ref();
        let area = mesh.total_area();
        let v = vortex_field(complex, &mesh, 12, 3);
        assert_eq!(v, vortex_field(complex, &mesh, 12, 3));
        let rms = (complex.field_inner(&v, &v) / area).sqrt();
        assert!((rms - 1.0).abs() < 1e-12);
        let s = smooth_field(complex, &mesh);
        assert!(s.iter().all(|x| x.is_finite()));
        let moving = MovingFeatures::new(complex, &mesh, 3, 0.2, 5);
        let (a, b) = (moving.frame(complex, 0.0), moving.frame(complex, 0.1));
        assert_eq!(a.len(), 2 * mesh.face_count());
        assert!(a.iter().zip(&b).any(|(x, y)| (x - y).abs() > 1e-6));
        let d = designed_field(complex, &mesh, 6, 1.0, 2).unwrap();
        assert!((complex.field_inner(&d, &d) / area - 1.0).abs() < 1e-9);
        assert_eq!(noise(5, 0.5, 1), noise(5, 0.5, 1));
        assert!(noise(100, 0.5, 2).iter().all(|x| x.abs() <= 0.5));
    }

    #[test]
    fn spread_points_are_distinct() {
        let mesh = SurfaceMesh::from(torus(1.0, 0.4, 24, 12).unwrap());
        let points = spread_points(&mesh, 10);
        assert_eq!(points.len(), 10);
        for (k, p) in points.iter().enumerate() {
            for q in &points[..k] {
                assert!(norm(sub(*p, *q)) > 0.1);
            }
        }
    }
}
