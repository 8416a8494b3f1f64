//! Checks of the optional capabilities: sampling and point evaluation (core: whatever a complex
//! offers must behave), the rotation `J`, face fields and the explicit divergence and curl
//! (reference: for complexes that opt in).

use crate::algebra_checks::max_abs;
use crate::check_outcome::{assert_outcomes, CheckOutcome};
use crate::corpus::CorpusMesh;
use crate::decomposition_checks::random_field;
use crate::reference_formulas::explicit_divergence_and_curl;
use tvf_core::discretization::sparse::{mul_vec, product, transpose};
use tvf_core::discretization::{
    FieldSampling, HodgeComplex, HodgeOperators, NodeKind, SamplingReproduction,
};
use tvf_core::geometry::{cross, dot, norm, scale, sub};
use tvf_core::{SurfacePoint, TriangleMesh};

/// Barycentric points every sampling check visits: the centroid, near each corner, on an edge.
pub const SAMPLE_POINTS: [[f64; 3]; 5] = [
    [1.0 / 3.0; 3],
    [0.8, 0.1, 0.1],
    [0.1, 0.7, 0.2],
    [0.05, 0.15, 0.8],
    [0.5, 0.5, 0.0],
];

/// The sampled vector `Σ w_i x_i` at a point.
pub fn sample(sampling: &dyn FieldSampling, field: &[f64], face: usize, b: [f64; 3]) -> [f64; 3] {
    let mut v = [0.0; 3];
    for (i, w) in sampling.sample_weights(&SurfacePoint::barycentric(face, b)) {
        for k in 0..3 {
            v[k] += w[k] * field[i];
        }
    }
    v
}

fn assert_vectors_close(what: &str, a: [f64; 3], b: [f64; 3], tolerance: f64) {
    let error = norm(sub(a, b));
    assert!(
        error <= tolerance,
        "{what}: {a:?} vs {b:?} (error {error:e})"
    );
}

/// Core, if the complex samples fields: dimensions agree with the complex, every frame is
/// orthonormal, positively oriented (`e1 × e2 = n`) and tangent, the normal is the mesh's, every
/// sampled vector is tangent, and a constant 3D vector turned into a field by
/// `from_face_vectors` samples back to its projection onto each face at every point of
/// [`SAMPLE_POINTS`] (to 1e-12 of its length), with its normal parts reported — for a sampling
/// that states [`SamplingReproduction::ConstantVectors`]; one that states
/// [`SamplingReproduction::LinearGradients`] is held to [`check_gradient_sampling`] instead. Where the complex
/// fixes field nodes to zero (relative forms: boundary edges), `from_face_vectors` gives 0 there,
/// no sampling weight names them, the constant is reproduced in the faces whose weights name no
/// fixed node, and [`check_relative_sampling`] holds.
pub fn check_sampling<H: HodgeComplex + ?Sized>(complex: &H, mesh: &CorpusMesh) {
    let Some(sampling) = complex.sampling() else {
        return;
    };
    let mesh = &mesh.mesh;
    assert_eq!(sampling.face_count(), mesh.face_count(), "sampling: faces");
    assert_eq!(
        sampling.field_dimension(),
        complex.field_dimension(),
        "sampling: field dimension"
    );
    let reproduces_constants = sampling.reproduction() == SamplingReproduction::ConstantVectors;
    if !reproduces_constants {
        check_gradient_sampling(complex, sampling, mesh);
    }
    let constant = [0.3, -1.1, 0.6];
    let projection = sampling
        .from_face_vectors(&vec![constant; mesh.face_count()])
        .expect("one vector per face");
    assert_eq!(projection.field.len(), complex.field_dimension());
    let fixed = &complex.field_nodes().dirichlet;
    for (i, &x) in projection.field.iter().enumerate() {
        assert!(
            !fixed[i] || x == 0.0,
            "from_face_vectors gives {x} at fixed field node {i}"
        );
    }
    let random = random_field(complex, 5);
    for t in 0..mesh.face_count() {
        let names_fixed = SAMPLE_POINTS.iter().any(|&b| {
            sampling
                .sample_weights(&SurfacePoint::barycentric(t, b))
                .iter()
                .any(|&(i, _)| fixed[i])
        });
        assert!(
            !names_fixed,
            "a sampling weight of face {t} names a fixed field node"
        );
        let touches_fixed = complex.field_nodes().kind == NodeKind::Edges
            && mesh.face_edges()[t].iter().any(|&e| fixed[e]);
        let [e1, e2] = sampling.frame(t);
        let n = sampling.normal(t);
        assert_vectors_close(
            &format!("normal of face {t}"),
            n,
            mesh.face_normal(t),
            1e-12,
        );
        for (value, expected) in frame_conditions(e1, e2, n) {
            assert!(
                (value - expected).abs() < 1e-12,
                "frame of face {t} not orthonormal, tangent and positive"
            );
        }
        let normal_part = dot(constant, n);
        assert!(
            (projection.normal_parts[t] - normal_part).abs() <= 1e-12 * norm(constant),
            "face {t}: reported normal part {} vs {normal_part}",
            projection.normal_parts[t]
        );
        let tangent = sub(constant, scale(n, normal_part));
        for b in SAMPLE_POINTS {
            if reproduces_constants && !touches_fixed {
                let v = sample(sampling, &projection.field, t, b);
                assert_vectors_close(
                    &format!("constant field sampled in face {t} at {b:?}"),
                    v,
                    tangent,
                    1e-12 * norm(constant),
                );
            }
            let w = sample(sampling, &random, t, b);
            assert!(
                dot(w, n).abs() <= 1e-12 * (1.0 + norm(w)),
                "sampled vector not tangent in face {t}"
            );
        }
    }
}

/// Core, for a sampling that states [`SamplingReproduction::LinearGradients`]: the gradient
/// `d0 φ` of the linear function `φ(x) = ⟨v, x⟩` at the potential nodes samples back to `v`
/// projected onto each face's plane at every point of [`SAMPLE_POINTS`] in every face none of
/// whose edges or vertices the boundary condition fixes, to `1e-12 · max(1, κ_f / 4)` of `|v|` with
/// `κ_f = ℓ²_max / A_f` (the longest side squared over the area; `κ ≈ 2.3` on an equilateral
/// triangle): the tolerance of the constant-vector check on well-shaped faces, growing on thin
/// ones, where a sharp built from side vectors over the area, as the polygon sharp is, loses
/// accuracy in that proportion.
pub fn check_gradient_sampling<H: HodgeComplex + ?Sized>(
    complex: &H,
    sampling: &dyn FieldSampling,
    mesh: &TriangleMesh,
) {
    let v = [0.3, -1.1, 0.6];
    let phi: Vec<f64> = complex
        .potential_nodes()
        .positions
        .iter()
        .map(|&p| dot(v, p))
        .collect();
    let gradient = mul_vec(complex.d0(), &phi);
    let nodes = complex.field_nodes();
    let potentials = complex.potential_nodes();
    for t in 0..mesh.face_count() {
        let fixed_edge = nodes.kind == NodeKind::Edges
            && mesh.face_edges()[t].iter().any(|&e| nodes.dirichlet[e]);
        let fixed_vertex = potentials.kind == NodeKind::Vertices
            && mesh.faces()[t].iter().any(|&v| potentials.dirichlet[v]);
        if fixed_edge || fixed_vertex {
            continue;
        }
        let n = mesh.face_normal(t);
        let tangent = sub(v, scale(n, dot(v, n)));
        let corners = [0, 1, 2].map(|c| mesh.corner(t, c));
        let longest_squared = (0..3)
            .map(|c| {
                let e = sub(corners[(c + 1) % 3], corners[c]);
                dot(e, e)
            })
            .fold(0.0, f64::max);
        let condition = longest_squared / mesh.face_area(t);
        for b in SAMPLE_POINTS {
            let sampled = sample(sampling, &gradient, t, b);
            assert_vectors_close(
                &format!("gradient of a linear function sampled in face {t} at {b:?}"),
                sampled,
                tangent,
                1e-12 * (condition / 4.0).max(1.0) * norm(v),
            );
        }
    }
}

/// Core, if the complex samples 1-forms on edges, states [`SamplingReproduction::ConstantVectors`]
/// (Whitney-like interpolation, whose tangential component along an edge is the edge's value)
/// and fixes some edges (relative forms): a random
/// field of the space sampled at three points of each fixed edge, in its face, has no component
/// along the edge (to 1e-12 of the largest sampled vector): relative 1-forms are normal to the
/// boundary. At least one fixed edge must be a boundary edge of the mesh, and every fixed edge is.
pub fn check_relative_sampling<H: HodgeComplex + ?Sized>(complex: &H, mesh: &CorpusMesh) {
    let Some(sampling) = complex.sampling() else {
        return;
    };
    let nodes = complex.field_nodes();
    if nodes.kind != NodeKind::Edges
        || nodes.dirichlet_count() == 0
        || sampling.reproduction() != SamplingReproduction::ConstantVectors
    {
        return;
    }
    let mesh = &mesh.mesh;
    let field = random_field(complex, 41);
    let mut checked = 0;
    let mut largest = 0.0f64;
    let mut worst = 0.0f64;
    for (t, edges) in mesh.face_edges().iter().enumerate() {
        for (c, &e) in edges.iter().enumerate() {
            if !nodes.dirichlet[e] {
                continue;
            }
            assert!(
                mesh.is_boundary_edge(e),
                "fixed edge {e} is not a boundary edge"
            );
            let [a, b] = mesh.edges()[e];
            let along = sub(mesh.positions()[b], mesh.positions()[a]);
            let along = scale(along, 1.0 / norm(along));
            for s in [0.0, 0.3, 1.0] {
                let mut point = [0.0; 3];
                point[(c + 1) % 3] = s;
                point[(c + 2) % 3] = 1.0 - s;
                let v = sample(sampling, &field, t, point);
                largest = largest.max(norm(v));
                worst = worst.max(dot(v, along).abs());
            }
            checked += 1;
        }
    }
    assert!(checked > 0, "no fixed edge checked");
    assert!(
        worst <= 1e-12 * largest,
        "a relative 1-form has a component {worst:e} along a boundary edge (largest {largest:e})"
    );
}

/// Core, if the complex evaluates (co-)potentials at points: weights of both spaces sum to 1 at
/// every point of [`crate::capability_checks::SAMPLE_POINTS`] and name nodes in range; the
/// potential weights reproduce a linear function sampled at the potential nodes' positions (to
/// 1e-12).
pub fn check_point_evaluation<H: HodgeComplex + ?Sized>(complex: &H, mesh: &CorpusMesh) {
    let Some(evaluation) = complex.point_evaluation() else {
        return;
    };
    let mesh = &mesh.mesh;
    let probe = LinearProbe::on_potential_nodes(complex);
    for t in 0..mesh.face_count() {
        for b in SAMPLE_POINTS {
            for (what, weights, n) in [
                (
                    "potential",
                    evaluation.potential_weights(&SurfacePoint::barycentric(t, b)),
                    complex.potential_dimension(),
                ),
                (
                    "co-potential",
                    evaluation.co_potential_weights(&SurfacePoint::barycentric(t, b)),
                    complex.co_potential_dimension(),
                ),
            ] {
                let total: f64 = weights.iter().map(|&(_, w)| w).sum();
                assert!(
                    (total - 1.0).abs() < 1e-14,
                    "{what} weights in face {t} sum to {total}"
                );
                assert!(
                    weights.iter().all(|&(i, _)| i < n),
                    "{what}: node out of range"
                );
            }
            let point: [f64; 3] =
                std::array::from_fn(|k| (0..3).map(|c| b[c] * mesh.corner(t, c)[k]).sum());
            let value =
                probe.evaluate(&evaluation.potential_weights(&SurfacePoint::barycentric(t, b)));
            assert!(
                (value - LinearProbe::at(point)).abs() <= 1e-12 * probe.scale,
                "potential interpolation in face {t}: {value} vs {}",
                LinearProbe::at(point)
            );
        }
    }
}

/// The six conditions on a face frame `(e1, e2)` with normal `n` as `(value, expected)`:
/// unit `e1` and `e2`, orthogonal to each other and to `n`, and `e1 × e2 = n` (positive).
pub fn frame_conditions(e1: [f64; 3], e2: [f64; 3], n: [f64; 3]) -> [(f64, f64); 6] {
    [
        (dot(e1, e1), 1.0),
        (dot(e2, e2), 1.0),
        (dot(e1, e2), 0.0),
        (dot(e1, n), 0.0),
        (dot(e2, n), 0.0),
        (dot(cross(e1, e2), n), 1.0),
    ]
}

/// The linear function `φ(p) = ⟨a, p⟩ + 2.5`, `a = (0.3, −1.2, 0.7)`, given at the potential
/// nodes of a complex: what the point-evaluation checks on triangle and polygon meshes
/// interpolate.
pub struct LinearProbe {
    /// `φ` at each potential node, `n0` entries.
    pub values: Vec<f64>,
    /// `max(1, max |φ|)` over the nodes: the scale of the interpolation error.
    pub scale: f64,
}

impl LinearProbe {
    /// `φ` at the potential nodes' positions of `complex`.
    pub fn on_potential_nodes<H: HodgeComplex + ?Sized>(complex: &H) -> Self {
        let values: Vec<f64> = complex
            .potential_nodes()
            .positions
            .iter()
            .map(|&p| Self::at(p))
            .collect();
        let scale = values.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        Self { values, scale }
    }

    /// `φ(p)`.
    pub fn at(p: [f64; 3]) -> f64 {
        dot([0.3, -1.2, 0.7], p) + 2.5
    }

    /// `Σ w φ_i` over the node weights `(i, w)` of a point.
    pub fn evaluate(&self, weights: &[(usize, f64)]) -> f64 {
        weights.iter().map(|&(i, w)| w * self.values[i]).sum()
    }
}

/// Reference `rotation`: the complex has a rotation `J` with `J² = −I` (exactly) and
/// `Jᵀ M1 J = M1` (relative 1e-14); with sampling, `J` rotates every sampled vector by +π/2:
/// `sample(J x) = n × sample(x)` (to 1e-12).
pub fn check_rotation<H: HodgeComplex + ?Sized>(complex: &H, mesh: &CorpusMesh) {
    let j = complex
        .rotation()
        .expect("the complex opted into the rotation checks but has no rotation")
        .rotation();
    let n = complex.field_dimension();
    assert_eq!(j.shape(), (n, n), "J shape");
    let j2 = product(j, j);
    for (value, (r, c)) in j2.iter() {
        let expected = if r == c { -1.0 } else { 0.0 };
        assert!(value == &expected, "J² ≠ −I at ({r},{c}): {value}");
    }
    assert_eq!(j2.nnz(), n, "J² has one entry per row");
    let m1 = complex
        .m1()
        .sparse_matrix()
        .expect("the field mass M1 is stored directly");
    let jt_m1_j = product(&transpose(j), &product(&m1, j));
    let difference = &jt_m1_j - &m1.to_csr();
    let error = max_abs(&difference);
    assert!(
        error <= 1e-14 * max_abs(&m1),
        "Jᵀ M1 J ≠ M1: differs by {error:e} (max entry {:e})",
        max_abs(&m1)
    );
    if let Some(sampling) = complex.sampling() {
        let x = random_field(complex, 3);
        let jx = mul_vec(j, &x);
        for t in 0..mesh.mesh.face_count() {
            for b in SAMPLE_POINTS {
                let v = sample(sampling, &x, t, b);
                let expected = cross(sampling.normal(t), v);
                assert_vectors_close(
                    &format!("J in face {t}"),
                    sample(sampling, &jx, t, b),
                    expected,
                    1e-12 * (1.0 + norm(v)),
                );
            }
        }
    }
}

/// Reference `face_fields`: the fields are one tangent vector per face (`n1 = 2F`, nodes
/// [`NodeKind::FaceFrames`]), `M1 = (A_t, A_t)` per face, zero off the diagonal (relative 1e-12,
/// so `1ᵀ M1 1 = 2·area`),
/// sampling is constant on each face, and `from_face_vectors ∘ to_face_vectors` is the identity
/// on fields (to 1e-12), while a vector lifted off the face plane is reported by its normal part.
pub fn check_face_fields<H: HodgeComplex + ?Sized>(complex: &H, mesh: &CorpusMesh) {
    let mesh = &mesh.mesh;
    assert_eq!(complex.field_nodes().kind, NodeKind::FaceFrames);
    assert_eq!(complex.field_dimension(), 2 * mesh.face_count());
    let m1 = complex
        .m1()
        .sparse_matrix()
        .expect("the field mass M1 is stored directly");
    let mut diagonal = vec![0.0; m1.rows()];
    for (&value, (i, j)) in m1.iter() {
        let area = mesh.face_area(i / 2);
        if i == j {
            diagonal[i] += value;
        } else {
            assert!(
                value.abs() <= 1e-12 * area,
                "M1[{i}, {j}] = {value}: face fields have a diagonal M1"
            );
        }
    }
    for (i, &value) in diagonal.iter().enumerate() {
        let area = mesh.face_area(i / 2);
        assert!(
            (value - area).abs() <= 1e-12 * area,
            "M1 of face {}: {value} vs area {area}",
            i / 2
        );
    }
    let sampling = complex
        .sampling()
        .expect("face fields are sampled per face");
    let field = random_field(complex, 9);
    let vectors = sampling.to_face_vectors(&field).expect("right length");
    for (t, &v) in vectors.iter().enumerate() {
        for b in SAMPLE_POINTS {
            assert_vectors_close(
                &format!("face field sampled in face {t}"),
                sample(sampling, &field, t, b),
                v,
                1e-12 * (1.0 + norm(v)),
            );
        }
    }
    let lifted: Vec<[f64; 3]> = vectors
        .iter()
        .enumerate()
        .map(|(t, &v)| {
            let n = sampling.normal(t);
            std::array::from_fn(|k| v[k] + 0.25 * n[k])
        })
        .collect();
    let projection = sampling.from_face_vectors(&lifted).expect("right length");
    for (i, (x, y)) in projection.field.iter().zip(&field).enumerate() {
        assert!((x - y).abs() < 1e-12, "round trip changed coefficient {i}");
    }
    assert!(
        (projection.max_normal_part() - 0.25).abs() < 1e-12,
        "normal parts: {}",
        projection.max_normal_part()
    );
}

/// Reference `div_curl_formulas`: for random face fields, the complex's divergence and curl of
/// both families equal the explicit sums over faces of `A_t ⟨∇ψ_i, v_t⟩` and
/// `A_t ⟨∇ψ_i, n × v_t⟩` ([`explicit_divergence_and_curl`]) turned pointwise by the space's mass,
/// with the potential basis (mass `M0`: `potential_divergence`, `other_curl`) and the
/// co-potential basis (mass `M2⁻¹`: `other_divergence`, `co_potential_curl`), relative 1e-10. Needs face fields, a rotation and
/// P1 or Crouzeix–Raviart spaces.
pub fn check_div_curl_formulas<H: HodgeComplex + ?Sized>(complex: &H, mesh: &CorpusMesh) {
    assert_outcomes(&measure_div_curl_formulas(complex, &mesh.mesh));
}

/// [`check_div_curl_formulas`] measured: one outcome per operator
/// (`div_curl_formulas:potential_divergence`, `:other_curl`, `:other_divergence`,
/// `:co_potential_curl`), the largest deviation over two random fields relative to the largest
/// explicit value, against `1e-10`; a complex without sampling or a rotation fails naming it.
pub fn measure_div_curl_formulas<H: HodgeComplex + ?Sized>(
    complex: &H,
    mesh: &TriangleMesh,
) -> Vec<CheckOutcome> {
    const NAME: &str = "div_curl_formulas";
    let capabilities = (
        complex.sampling(),
        complex.other_divergence(),
        complex.other_curl(),
    );
    let (Some(sampling), Some(other_divergence), Some(other_curl)) = capabilities else {
        return vec![CheckOutcome::failed(
            NAME,
            "needs sampling and a rotation".to_string(),
        )];
    };
    let co_mass = complex.m2().inverse();
    let names = [
        "potential_divergence",
        "other_curl",
        "other_divergence",
        "co_potential_curl",
    ];
    let mut worst = [(0.0f64, 0.0f64, 0.0f64); 4];
    for seed in [1, 2] {
        let field = random_field(complex, seed);
        let vectors = sampling.to_face_vectors(&field).expect("right length");
        let potential_kind = complex.potential_nodes().kind;
        let (p_div, p_curl) =
            explicit_divergence_and_curl(potential_kind, mesh, complex.m0(), &vectors);
        let co_potential_kind = complex.co_potential_nodes().kind;
        let (q_div, q_curl) =
            explicit_divergence_and_curl(co_potential_kind, mesh, &co_mass, &vectors);
        let operators = [
            (complex.potential_divergence(), &p_div),
            (other_curl, &p_curl),
            (other_divergence, &q_div),
            (complex.co_potential_curl(), &q_curl),
        ];
        for (k, (operator, expected)) in operators.into_iter().enumerate() {
            let deviation = vector_deviation(&operator.apply(&field), expected);
            if deviation.0.is_nan() || deviation.0 > worst[k].0 {
                worst[k] = deviation;
            }
        }
    }
    names
        .iter()
        .zip(worst)
        .map(|(what, (relative, error, scale))| {
            CheckOutcome::at_most(
                format!("{NAME}:{what}"),
                relative,
                1e-10,
                format!("{what} differs from its explicit formula by {error:e} (max {scale:e})"),
            )
        })
        .collect()
}

/// `(max |got − expected| / max |expected|, max |got − expected|, max |expected|)`; NaN when
/// the lengths differ.
fn vector_deviation(got: &[f64], expected: &[f64]) -> (f64, f64, f64) {
    if got.len() != expected.len() {
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    let scale = expected.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let error = got
        .iter()
        .zip(expected)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let relative = if scale > 0.0 { error / scale } else { error };
    (relative, error, scale)
}
