//! The capability checks on polygon meshes (core: whatever a complex offers must behave), for
//! discretizations whose sampling is one vector per polygon: what they state, measured
//! ([`measure_polygon_capabilities`]: [`measure_polygon_sampling`],
//! [`measure_polygon_point_evaluation`]) and asserted ([`check_polygon_capabilities`]). A
//! polygon's points are [`SurfacePoint`]s: the face and one weight per corner
//! ([`polygon_points`]).

use crate::capability_checks::{frame_conditions, LinearProbe};
use crate::check_outcome::{assert_outcomes, CheckOutcome};
use crate::corpus::CorpusMesh;
use crate::decomposition_checks::random_field;
use tvf_core::discretization::sparse::mul_vec;
use tvf_core::discretization::{
    FieldSampling, HodgeComplex, HodgeOperators, NodeKind, PointEvaluation, SamplingReproduction,
    TangentProjection,
};
use tvf_core::geometry::{dot, norm, scale, sub};
use tvf_core::{SurfaceMesh, SurfacePoint};

/// The constant vector the sampling checks turn into a 1-form.
const CONSTANT: [f64; 3] = [0.3, -1.1, 0.6];

/// Round-off limit of the sampling and evaluation checks, relative (see each check).
pub const POLYGON_TOLERANCE: f64 = 1e-12;

/// The corner weights of the points every polygon check visits on a face of `n` corners: the
/// corner average, each corner (`w = e_c`), the midpoint of each side, and an interior point of
/// unequal weights `w_c ∝ c + 1`.
pub fn polygon_points(n: usize) -> Vec<Vec<f64>> {
    let mut points = vec![vec![1.0 / n as f64; n]];
    for c in 0..n {
        let mut corner = vec![0.0; n];
        corner[c] = 1.0;
        points.push(corner);
        let mut side = vec![0.0; n];
        side[c] = 0.5;
        side[(c + 1) % n] = 0.5;
        points.push(side);
    }
    let total = (n * (n + 1) / 2) as f64;
    points.push((0..n).map(|c| (c + 1) as f64 / total).collect());
    points
}

fn sample(sampling: &dyn FieldSampling, field: &[f64], point: &SurfacePoint) -> [f64; 3] {
    let mut v = [0.0; 3];
    for (i, w) in sampling.sample_weights(point) {
        for k in 0..3 {
            v[k] += w[k] * field[i];
        }
    }
    v
}

/// `κ_f = ℓ²_max / |A_f|`: the longest side of face `f` squared over its (vector) area.
fn side_condition(mesh: &SurfaceMesh, f: usize) -> f64 {
    let corners = mesh.face(f);
    let p = mesh.positions();
    let longest = (0..corners.len())
        .map(|c| {
            let side = sub(p[corners[(c + 1) % corners.len()]], p[corners[c]]);
            dot(side, side)
        })
        .fold(0.0, f64::max);
    longest / mesh.face_area(f)
}

/// Whether the boundary condition fixes an edge or a vertex of face `f` (relative forms).
fn touches_fixed_nodes<H: HodgeComplex + ?Sized>(
    complex: &H,
    mesh: &SurfaceMesh,
    f: usize,
) -> bool {
    let (fields, potentials) = (complex.field_nodes(), complex.potential_nodes());
    let corners = mesh.face(f);
    let fixed_edge = fields.kind == NodeKind::Edges
        && (0..corners.len()).any(|c| fields.dirichlet[mesh.face_edge(f, c)]);
    let fixed_vertex =
        potentials.kind == NodeKind::Vertices && corners.iter().any(|&v| potentials.dirichlet[v]);
    fixed_edge || fixed_vertex
}

/// Measures `sampling`, `complex`'s, which states [`SamplingReproduction::LinearGradients`], on a
/// polygon mesh, one outcome each:
///
/// - `polygon_sampling:sizes`: one frame per face, the field dimension the complex's;
/// - `polygon_sampling:frames`: every frame orthonormal, tangent, positive (`e1 × e2 = n`) and
///   its normal the unit vector area `A_f / |A_f|` (largest deviation, limit 1e-12);
/// - `polygon_sampling:sharp_of_flat`: the 1-form of a constant vector `v` (its flat, `x = d0 φ`
///   for `φ(p) = ⟨v, p⟩` at the potential nodes, `x_(a,b) = ⟨v, p_b − p_a⟩`) samples to
///   `v − ⟨v, n_f⟩ n_f`, `v` projected onto the polygon's plane (normal to its vector area; de
///   Goes, Butts, Desbrun 2020, §4), at every point of [`polygon_points`] of every face the
///   boundary condition leaves free: the largest error over `|v| · max(1, κ_f / 4)`, `κ_f` the
///   longest side squared over the area, limit 1e-12 (as on triangles,
///   [`crate::capability_checks::check_gradient_sampling`]);
/// - `polygon_sampling:one_vector_per_polygon`: a random field samples to the same vector at
///   every point of a polygon (largest difference from the corner average's, relative to the
///   largest sampled vector, limit 1e-12);
/// - `polygon_sampling:tangent`: every sampled vector of a random field is tangent
///   (`|⟨w, n_f⟩| ≤ 1e-12 (1 + |w|)`);
/// - `polygon_sampling:normal_parts`: `from_face_vectors` of the constant reports `⟨v, n_f⟩` as
///   the normal part of every face (limit `1e-12 |v|`);
/// - `polygon_sampling:fixed_nodes`: no sampling weight names a node the boundary condition
///   fixes, and `from_face_vectors` is 0 there (count of violations, expected 0).
pub fn measure_polygon_sampling<H: HodgeComplex + ?Sized>(
    complex: &H,
    sampling: &dyn FieldSampling,
    mesh: &SurfaceMesh,
) -> Vec<CheckOutcome> {
    const NAME: &str = "polygon_sampling";
    let sizes_agree = sampling.face_count() == mesh.face_count()
        && sampling.field_dimension() == complex.field_dimension();
    let mut outcomes = vec![CheckOutcome::count(
        format!("{NAME}:sizes"),
        usize::from(!sizes_agree),
        0,
        format!(
            "{} frames for {} faces, sampled dimension {} for n1 = {}",
            sampling.face_count(),
            mesh.face_count(),
            sampling.field_dimension(),
            complex.field_dimension()
        ),
    )];
    if !sizes_agree {
        return outcomes;
    }
    if sampling.reproduction() != SamplingReproduction::LinearGradients {
        outcomes.push(CheckOutcome::failed(
            format!("{NAME}:reproduction"),
            "a sampling on polygons must state LinearGradients (one sharp per polygon)".into(),
        ));
        return outcomes;
    }
    let phi: Vec<f64> = complex
        .potential_nodes()
        .positions
        .iter()
        .map(|&p| dot(CONSTANT, p))
        .collect();
    let flat = mul_vec(complex.d0(), &phi);
    let random = random_field(complex, 5);
    let projection = sampling
        .from_face_vectors(&vec![CONSTANT; mesh.face_count()])
        .expect("one vector per face");
    let fixed = &complex.field_nodes().dirichlet;
    let mut fixed_violations = projection
        .field
        .iter()
        .zip(fixed)
        .filter(|(&x, &f)| f && x != 0.0)
        .count();
    let faces = measure_faces(complex, sampling, mesh, &flat, &random, &projection);
    fixed_violations += faces.fixed_violations;
    let spread = if faces.largest > 0.0 {
        faces.spread / faces.largest
    } else {
        faces.spread
    };
    let measured = [
        ("frames", faces.frames, "largest deviation of a frame from orthonormal, tangent, positive, normal along the vector area"),
        ("sharp_of_flat", faces.sharp, "largest error of the sharp of a constant vector's 1-form against the vector projected onto the polygon's plane, over |v| max(1, κ/4)"),
        ("one_vector_per_polygon", spread, "largest difference between the vectors sampled at two points of one polygon, over the largest sampled vector"),
        ("tangent", faces.tangent, "largest normal component of a sampled vector, over 1 + its length"),
        ("normal_parts", faces.normal_parts, "largest error of a reported normal part, over |v|"),
    ];
    for (what, value, detail) in measured {
        outcomes.push(CheckOutcome::at_most(
            format!("{NAME}:{what}"),
            value,
            POLYGON_TOLERANCE,
            detail.to_string(),
        ));
    }
    outcomes.push(CheckOutcome::count(
        format!("{NAME}:fixed_nodes"),
        fixed_violations,
        0,
        "sampling weights or flat values on nodes the boundary condition fixes".to_string(),
    ));
    outcomes
}

/// The largest deviations [`measure_polygon_sampling`] reports, over every face.
struct FaceMeasures {
    frames: f64,
    sharp: f64,
    spread: f64,
    tangent: f64,
    normal_parts: f64,
    /// The largest sampled vector of the random field.
    largest: f64,
    /// Sampling weights that name a fixed node.
    fixed_violations: usize,
}

/// Visits every face of `mesh` at the points of [`polygon_points`]: frames, the sharp of the
/// flat `flat` of [`CONSTANT`], the random field `random` (one vector per polygon, tangent) and
/// the normal parts `projection` reports.
fn measure_faces<H: HodgeComplex + ?Sized>(
    complex: &H,
    sampling: &dyn FieldSampling,
    mesh: &SurfaceMesh,
    flat: &[f64],
    random: &[f64],
    projection: &TangentProjection,
) -> FaceMeasures {
    let fixed = &complex.field_nodes().dirichlet;
    let (mut frames, mut sharp, mut spread, mut tangent, mut normal_parts) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (mut largest, mut fixed_violations) = (0.0f64, 0usize);
    for f in 0..mesh.face_count() {
        let [e1, e2] = sampling.frame(f);
        let n = sampling.normal(f);
        frames = frames.max(norm(sub(n, mesh.face_normal(f))));
        for (value, expected) in frame_conditions(e1, e2, n) {
            frames = frames.max((value - expected).abs());
        }
        normal_parts = normal_parts
            .max((projection.normal_parts[f] - dot(CONSTANT, n)).abs() / norm(CONSTANT));
        // The polygon's plane is the mesh's: normal to the vector area of its corners.
        let plane_normal = mesh.face_normal(f);
        let expected = sub(CONSTANT, scale(plane_normal, dot(CONSTANT, plane_normal)));
        let free = !touches_fixed_nodes(complex, mesh, f);
        let condition = (side_condition(mesh, f) / 4.0).max(1.0);
        let points = polygon_points(mesh.face_size(f));
        let first = sample(
            sampling,
            random,
            &SurfacePoint::centroid(f, points[0].len()),
        );
        for weights in points {
            let point = SurfacePoint { face: f, weights };
            fixed_violations += sampling
                .sample_weights(&point)
                .iter()
                .filter(|&&(i, _)| fixed[i])
                .count();
            if free {
                let error = norm(sub(sample(sampling, flat, &point), expected));
                sharp = sharp.max(error / (norm(CONSTANT) * condition));
            }
            let w = sample(sampling, random, &point);
            largest = largest.max(norm(w));
            spread = spread.max(norm(sub(w, first)));
            tangent = tangent.max(dot(w, n).abs() / (1.0 + norm(w)));
        }
    }
    FaceMeasures {
        frames,
        sharp,
        spread,
        tangent,
        normal_parts,
        largest,
        fixed_violations,
    }
}

/// Measures `evaluation`, `complex`'s point evaluation, on a polygon mesh at every point of
/// [`polygon_points`] of every face:
///
/// - `polygon_point_evaluation:weights`: the potential and co-potential weights sum to 1 (to
///   1e-14) and name nodes in range (violations, expected 0);
/// - `polygon_point_evaluation:linear`: the potential weights reproduce a linear function
///   `φ(p) = ⟨a, p⟩ + 2.5` given at the potential nodes at the point's position `Σ_c w_c p_c`
///   (at a corner, `φ` of the corner): the largest error over `max(1, max |φ|)`, limit 1e-12.
pub fn measure_polygon_point_evaluation<H: HodgeComplex + ?Sized>(
    complex: &H,
    evaluation: &dyn PointEvaluation,
    mesh: &SurfaceMesh,
) -> Vec<CheckOutcome> {
    const NAME: &str = "polygon_point_evaluation";
    let probe = LinearProbe::on_potential_nodes(complex);
    let (mut bad_weights, mut error) = (0usize, 0.0f64);
    for f in 0..mesh.face_count() {
        for weights in polygon_points(mesh.face_size(f)) {
            let point = SurfacePoint { face: f, weights };
            let potential = evaluation.potential_weights(&point);
            let co_potential = evaluation.co_potential_weights(&point);
            for (weights, n) in [
                (&potential, complex.potential_dimension()),
                (&co_potential, complex.co_potential_dimension()),
            ] {
                let total: f64 = weights.iter().map(|&(_, w)| w).sum();
                if (total - 1.0).abs() >= 1e-14 || weights.iter().any(|&(i, _)| i >= n) {
                    bad_weights += 1;
                }
            }
            let value = probe.evaluate(&potential);
            let expected = LinearProbe::at(mesh.point_position(&point));
            error = error.max((value - expected).abs() / probe.scale);
        }
    }
    vec![
        CheckOutcome::count(
            format!("{NAME}:weights"),
            bad_weights,
            0,
            "points whose weights do not sum to 1 or name a node out of range".to_string(),
        ),
        CheckOutcome::at_most(
            format!("{NAME}:linear"),
            error,
            POLYGON_TOLERANCE,
            "largest error of a linear function evaluated at a point, over max(1, max |φ|)"
                .to_string(),
        ),
    ]
}

/// The capability checks a complex's capabilities get on a polygon mesh: its sampling
/// ([`measure_polygon_sampling`]) and its point evaluation ([`measure_polygon_point_evaluation`]);
/// a capability the complex lacks gives no outcome.
pub fn measure_polygon_capabilities<H: HodgeComplex + ?Sized>(
    complex: &H,
    mesh: &SurfaceMesh,
) -> Vec<CheckOutcome> {
    let mut outcomes = Vec::new();
    if let Some(sampling) = complex.sampling() {
        outcomes.extend(measure_polygon_sampling(complex, sampling, mesh));
    }
    if let Some(evaluation) = complex.point_evaluation() {
        outcomes.extend(measure_polygon_point_evaluation(complex, evaluation, mesh));
    }
    outcomes
}

/// Asserts [`measure_polygon_capabilities`] on a polygon corpus mesh.
pub fn check_polygon_capabilities<H: HodgeComplex + ?Sized>(
    complex: &H,
    mesh: &CorpusMesh<SurfaceMesh>,
) {
    assert_outcomes(&measure_polygon_capabilities(complex, &mesh.mesh));
}
