//! Unit properties of the DEC 1-form complex: signed incidences, the cotan Hodge star, the
//! relation to the conforming cotan matrix, Whitney sampling and the Delaunay precondition.

use tvf_core::discretization::{
    BoundaryCondition, DiscretizationError, FieldSampling, HodgeComplex, HodgeOperators,
};
use tvf_core::generate::{bumpy_torus, genus_surface, icosphere, jitter, rigid_motion, torus};
use tvf_core::geometry::{cross, dot, norm, scale, sub};
use tvf_core::{SurfacePoint, TriangleMesh};
use tvf_discretizations::{
    Conforming, DecComplex, DecompositionError, HodgeDecomposer, MassLumping, DELAUNAY_TOLERANCE,
};

/// Cotangent of the angle at corner `c` of face `t`, from 3D positions.
fn corner_cotangent(mesh: &TriangleMesh, t: usize, c: usize) -> f64 {
    let o = mesh.corner(t, c);
    let u = sub(mesh.corner(t, (c + 1) % 3), o);
    let v = sub(mesh.corner(t, (c + 2) % 3), o);
    dot(u, v) / norm(cross(u, v))
}

/// `cot α + cot β` per edge, summed over the faces next to it.
fn cotangent_sums(mesh: &TriangleMesh) -> Vec<f64> {
    let mut sums = vec![0.0; mesh.edge_count()];
    for (t, edges) in mesh.face_edges().iter().enumerate() {
        for (c, &e) in edges.iter().enumerate() {
            sums[e] += corner_cotangent(mesh, t, c);
        }
    }
    sums
}

/// A flat patch of near-equilateral triangles (a Delaunay triangulation of a parallelogram,
/// `n × n` cells), tilted out of the coordinate planes.
fn flat_patch(n: usize) -> TriangleMesh {
    let index = |i: usize, j: usize| j * (n + 1) + i;
    let positions = (0..=n)
        .flat_map(|j| {
            (0..=n).map(move |i| {
                let (x, y) = (i as f64 + 0.5 * j as f64, j as f64 * 3f64.sqrt() / 2.0);
                [x, y, 0.0]
            })
        })
        .collect();
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            faces.push([index(i, j), index(i + 1, j), index(i, j + 1)]);
            faces.push([index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)]);
        }
    }
    let patch = TriangleMesh::new(positions, faces).expect("valid patch");
    rigid_motion(&patch, [0.3, -0.8, 0.5], 0.7, [1.0, 2.0, -0.5]).expect("finite motion")
}

/// Delaunay meshes for the checks: icospheres (curved, closed), a jittered icosphere and the flat
/// patch (with boundary).
fn delaunay_meshes() -> Vec<(&'static str, TriangleMesh)> {
    vec![
        ("icosphere(1)", icosphere(1)),
        ("icosphere(2)", icosphere(2)),
        (
            "jittered icosphere(2)",
            jitter(&icosphere(2), 0.15, 7).expect("finite amplitude"),
        ),
        ("flat patch", flat_patch(6)),
    ]
}

fn build(mesh: &TriangleMesh) -> DecComplex {
    DecComplex::new(mesh, MassLumping::Barycentric).expect("a Delaunay mesh builds")
}

#[test]
fn incidences_are_signed_and_compose_to_zero_exactly() {
    for (name, mesh) in delaunay_meshes() {
        let complex = build(&mesh);
        let d0 = complex.d0().to_csr();
        assert_eq!(d0.shape(), (mesh.edge_count(), mesh.vertex_count()));
        for (e, row) in d0.outer_iterator().enumerate() {
            let [a, b] = mesh.edges()[e];
            let entries: Vec<(usize, f64)> = row.iter().map(|(j, &v)| (j, v)).collect();
            assert_eq!(entries, vec![(a, -1.0), (b, 1.0)], "{name}: d0 row {e}");
        }
        let d1 = complex.d1().to_csr();
        assert_eq!(d1.shape(), (mesh.face_count(), mesh.edge_count()));
        for (t, face) in mesh.faces().iter().enumerate() {
            let mut expected: Vec<(usize, f64)> = (0..3)
                .map(|c| {
                    let (from, to) = (face[c], face[(c + 1) % 3]);
                    let key = [from.min(to), from.max(to)];
                    let e = mesh.edges().iter().position(|&x| x == key).expect("edge");
                    (e, if from < to { 1.0 } else { -1.0 })
                })
                .collect();
            expected.sort_by_key(|&(e, _)| e);
            let row: Vec<(usize, f64)> = d1
                .outer_view(t)
                .expect("row")
                .iter()
                .map(|(j, &v)| (j, v))
                .collect();
            assert_eq!(row, expected, "{name}: d1 row {t}");
        }
        let composed = &d1 * &d0;
        assert!(
            composed.data().iter().all(|&x| x == 0.0),
            "{name}: d1 d0 is not exactly zero"
        );
    }
}

#[test]
fn stars_are_cotan_weights_vertex_areas_and_inverse_face_areas() {
    for (name, mesh) in delaunay_meshes() {
        let complex = build(&mesh);
        for (e, (&star, &sum)) in complex
            .m1()
            .diagonal_values()
            .unwrap()
            .iter()
            .zip(&cotangent_sums(&mesh))
            .enumerate()
        {
            assert!(
                (star - sum / 2.0).abs() <= 1e-12 * sum.abs(),
                "{name}: ⋆1 of edge {e} is {star}, (cot α + cot β)/2 = {}",
                sum / 2.0
            );
        }
        let mut vertex_areas = vec![0.0; mesh.vertex_count()];
        for (t, face) in mesh.faces().iter().enumerate() {
            for &v in face {
                vertex_areas[v] += mesh.face_area(t) / 3.0;
            }
        }
        for (v, (&m, &a)) in complex
            .m0()
            .diagonal_values()
            .unwrap()
            .iter()
            .zip(&vertex_areas)
            .enumerate()
        {
            assert!(
                (m - a).abs() <= 1e-12 * a,
                "{name}: ⋆0 of vertex {v}: {m} vs {a}"
            );
        }
        for (t, &m) in complex.m2().diagonal_values().unwrap().iter().enumerate() {
            let area = mesh.face_area(t);
            assert!((m * area - 1.0).abs() <= 1e-12, "{name}: ⋆2 of face {t}");
        }
    }
}

#[test]
fn exact_stiffness_is_the_conforming_cotan_matrix() {
    for (name, mesh) in delaunay_meshes() {
        for lumping in [MassLumping::Barycentric, MassLumping::Voronoi] {
            let dec = DecComplex::new(&mesh, lumping).expect("Delaunay");
            let conforming = Conforming::new(&mesh, lumping).expect("valid mesh");
            let problem = dec.exact_eigenproblem();
            let a = problem.stiffness.as_sparse().unwrap();
            let b = conforming.potential_stiffness();
            let difference = &a.to_csr() - &b.to_csr();
            let error = difference.data().iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let size = b.data().iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(
                error <= 1e-12 * size,
                "{name}: d0ᵀ ⋆1 d0 differs from Gᵀ M_X G by {error:e} (max {size:e})"
            );
            assert_eq!(
                dec.m0().diagonal_values().unwrap(),
                conforming.m0().diagonal_values().unwrap(),
                "{name}: same ⋆0 and M"
            );
        }
    }
}

/// The sampled vector `Σ w_i x_i` at a point.
fn sample(sampling: &dyn FieldSampling, field: &[f64], face: usize, b: [f64; 3]) -> [f64; 3] {
    let mut v = [0.0; 3];
    for (i, w) in sampling.sample_weights(&SurfacePoint::barycentric(face, b)) {
        for k in 0..3 {
            v[k] += w[k] * field[i];
        }
    }
    v
}

#[test]
fn whitney_sampling_of_the_de_rham_map_reproduces_constant_vectors() {
    let points = [
        [1.0 / 3.0; 3],
        [0.8, 0.1, 0.1],
        [0.1, 0.7, 0.2],
        [0.05, 0.15, 0.8],
        [0.5, 0.5, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let constant = [0.7, -0.4, 1.3];
    for (name, mesh) in delaunay_meshes() {
        let complex = build(&mesh);
        let sampling = complex.sampling().expect("Whitney sampling");
        let projection = sampling
            .from_face_vectors(&vec![constant; mesh.face_count()])
            .expect("one vector per face");
        for t in 0..mesh.face_count() {
            let n = mesh.face_normal(t);
            let tangent = sub(constant, scale(n, dot(constant, n)));
            assert!((projection.normal_parts[t] - dot(constant, n)).abs() <= 1e-12);
            for b in points {
                let v = sample(sampling, &projection.field, t, b);
                let error = norm(sub(v, tangent));
                assert!(
                    error <= 1e-12 * norm(constant),
                    "{name}: face {t} at {b:?}: {v:?} vs {tangent:?}"
                );
            }
        }
    }
}

#[test]
fn whitney_forms_integrate_to_one_along_their_own_edge() {
    // Two-point Gauss–Legendre on [0, 1]: exact for the linear integrand ⟨W(s), p_b − p_a⟩.
    let gauss = [0.5 - 0.5 / 3f64.sqrt(), 0.5 + 0.5 / 3f64.sqrt()];
    for (name, mesh) in delaunay_meshes() {
        let complex = build(&mesh);
        let sampling = complex.sampling().expect("Whitney sampling");
        let mut unit = vec![0.0; mesh.edge_count()];
        for (t, face) in mesh.faces().iter().enumerate() {
            for &e in &mesh.face_edges()[t] {
                unit[e] = 1.0;
                for (c, &along) in mesh.face_edges()[t].iter().enumerate() {
                    // Edge `along` is opposite corner c; walk it from its a to its b.
                    let [a, b] = mesh.edges()[along];
                    let tangent = sub(mesh.positions()[b], mesh.positions()[a]);
                    let corner_of = |v: usize| face.iter().position(|&x| x == v).expect("corner");
                    let (ca, cb) = (corner_of(a), corner_of(b));
                    assert_ne!(ca, c);
                    let integral: f64 = gauss
                        .iter()
                        .map(|&s| {
                            let mut bary = [0.0; 3];
                            bary[ca] = 1.0 - s;
                            bary[cb] = s;
                            dot(sample(sampling, &unit, t, bary), tangent) / 2.0
                        })
                        .sum();
                    let expected = if along == e { 1.0 } else { 0.0 };
                    assert!(
                        (integral - expected).abs() <= 1e-12,
                        "{name}: face {t}, form of edge {e} along edge {along}: {integral}"
                    );
                }
                unit[e] = 0.0;
            }
        }
    }
}

/// A quad torus has `cot α + cot β = 0` (up to round-off) on all `16·8` diagonals of its cyclic
/// cells, a jittered plate surface clearly negative values; both are refused, with the count of
/// edges at or below [`DELAUNAY_TOLERANCE`] computed here independently.
#[test]
fn non_delaunay_meshes_are_refused_with_the_count_of_bad_edges() {
    for (name, mesh, expected_count) in [
        (
            "quad torus 16×8",
            torus(1.0, 0.4, 16, 8).expect("valid torus"),
            Some(128),
        ),
        ("genus_surface(1, 4)", genus_surface(1, 4), None),
        (
            "jittered genus-2 plate surface",
            jitter(&genus_surface(2, 2), 0.05, 3).expect("finite amplitude"),
            None,
        ),
    ] {
        let sums = cotangent_sums(&mesh);
        assert!(
            sums.iter().all(|s| (s - DELAUNAY_TOLERANCE).abs() > 1e-14),
            "{name}: a sum within round-off of the tolerance makes the count ambiguous"
        );
        let bad: Vec<usize> = (0..sums.len())
            .filter(|&e| sums[e] <= DELAUNAY_TOLERANCE)
            .collect();
        assert!(!bad.is_empty(), "{name} should not be Delaunay");
        if let Some(count) = expected_count {
            assert_eq!(bad.len(), count, "{name}: independent count");
        }
        for lumping in [MassLumping::Barycentric, MassLumping::Voronoi] {
            match DecComplex::new(&mesh, lumping) {
                Err(DiscretizationError::NotDelaunay {
                    count,
                    first,
                    value,
                    ..
                }) => {
                    assert_eq!(count, bad.len(), "{name}: number of non-Delaunay edges");
                    assert_eq!(first, bad[0], "{name}: first non-Delaunay edge");
                    assert!(
                        (value - sums[first]).abs() <= 1e-12,
                        "{name}: reported cot α + cot β = {value}, computed {}",
                        sums[first]
                    );
                }
                other => panic!(
                    "{name}: expected NotDelaunay, got {:?}",
                    other.map(|c| c.id().to_string())
                ),
            }
        }
    }
}

/// Which generated meshes are Delaunay (and so get a DEC complex): icospheres as generated and
/// jittered; the genus-0 plate at resolution 2; no quad torus, no plate with holes (at
/// resolution 4 the genus-1 plate's flat rectangles have `cot α + cot β` of ±1e-17), no bumpy
/// torus.
#[test]
fn generated_meshes_that_are_delaunay() {
    let mut delaunay = vec![
        ("icosphere(1)", icosphere(1)),
        ("icosphere(2)", icosphere(2)),
        ("icosphere(3)", icosphere(3)),
        ("genus_surface(0, 2)", genus_surface(0, 2)),
    ];
    for seed in 0..5 {
        delaunay.push((
            "jittered icosphere(2)",
            jitter(&icosphere(2), 0.15, seed).expect("finite amplitude"),
        ));
    }
    for (name, mesh) in &delaunay {
        assert!(
            cotangent_sums(mesh).iter().all(|&s| s > DELAUNAY_TOLERANCE),
            "{name}"
        );
        assert!(
            DecComplex::new(mesh, MassLumping::Voronoi).is_ok(),
            "{name}"
        );
    }
    let refused = [
        ("torus 24×6", torus(2.0, 0.3, 24, 6).expect("valid torus")),
        ("genus_surface(1, 2)", genus_surface(1, 2)),
        ("genus_surface(3, 2)", genus_surface(3, 2)),
        ("genus_surface(1, 4)", genus_surface(1, 4)),
        ("genus_surface(2, 4)", genus_surface(2, 4)),
        (
            "bumpy torus",
            bumpy_torus(1.0, 0.3, 32, 16, 6, 0.5).expect("valid parameters"),
        ),
    ];
    for (name, mesh) in &refused {
        assert!(
            matches!(
                DecComplex::new(mesh, MassLumping::Barycentric),
                Err(DiscretizationError::NotDelaunay { .. })
            ),
            "{name} should be refused"
        );
    }
}

#[test]
fn relative_forms_fix_boundary_vertices_and_edges_to_zero() {
    let mesh = flat_patch(6);
    let absolute =
        DecComplex::with_boundary(&mesh, MassLumping::Voronoi, BoundaryCondition::Tangential)
            .expect("absolute forms");
    let relative =
        DecComplex::with_boundary(&mesh, MassLumping::Voronoi, BoundaryCondition::Normal)
            .expect("relative forms");
    assert_eq!(relative.id(), "dec-circumcentric+normal");
    let boundary_edge: Vec<bool> = (0..mesh.edge_count())
        .map(|e| mesh.is_boundary_edge(e))
        .collect();
    let mut boundary_vertex = vec![false; mesh.vertex_count()];
    for e in mesh.boundary_edges() {
        for v in mesh.edges()[e] {
            boundary_vertex[v] = true;
        }
    }
    assert_eq!(relative.potential_nodes().dirichlet, boundary_vertex);
    assert_eq!(relative.field_nodes().dirichlet, boundary_edge);
    assert_eq!(relative.co_potential_nodes().dirichlet_count(), 0);
    assert_eq!(relative.co_potential_nodes().constant_kernel, vec![true]);
    assert_eq!(absolute.co_potential_nodes().constant_kernel, vec![false]);
    // d0 and d1 are those of absolute forms with the fixed columns and rows emptied.
    for (&value, (e, v)) in absolute.d0().iter() {
        let kept = !boundary_vertex[v] && !boundary_edge[e];
        assert_eq!(
            relative.d0().get(e, v).copied(),
            kept.then_some(value),
            "d0[{e}, {v}]"
        );
    }
    for (&value, (t, e)) in absolute.d1().iter() {
        let kept = !boundary_edge[e];
        assert_eq!(
            relative.d1().get(t, e).copied(),
            kept.then_some(value),
            "d1[{t}, {e}]"
        );
    }
    let composed = tvf_core::discretization::sparse::product(relative.d1(), relative.d0());
    assert!(composed.iter().all(|(&x, _)| x == 0.0), "d1 d0 = 0 exactly");
    // Fields of the space are zero on boundary edges; others are refused naming the edge.
    let sampling = relative.sampling().expect("Whitney sampling");
    let projection = sampling
        .from_face_vectors(&vec![[0.3, -1.1, 0.6]; mesh.face_count()])
        .expect("one vector per face");
    let first = boundary_edge
        .iter()
        .position(|&b| b)
        .expect("a boundary edge");
    assert!((0..mesh.edge_count()).all(|e| !boundary_edge[e] || projection.field[e] == 0.0));
    let decomposer = HodgeDecomposer::new(&relative).expect("factors");
    let parts = decomposer
        .decompose(&projection.field)
        .expect("a relative 1-form");
    assert!(
        parts.harmonic.iter().all(|x| x.abs() < 1e-10),
        "a disk has no harmonic field"
    );
    let mut outside = projection.field.clone();
    outside[first] = 0.5;
    match decomposer.decompose(&outside) {
        Err(DecompositionError::Discretization(DiscretizationError::NonzeroOnDirichletNode {
            index,
            value,
            ..
        })) => assert_eq!((index, value), (first, 0.5)),
        other => panic!("expected a refusal, got {other:?}"),
    }
    // On a closed mesh both conditions give the same complex.
    let sphere = icosphere(2);
    let a = DecComplex::with_boundary(&sphere, MassLumping::Voronoi, BoundaryCondition::Tangential)
        .unwrap();
    let b = DecComplex::with_boundary(&sphere, MassLumping::Voronoi, BoundaryCondition::Normal)
        .unwrap();
    assert_eq!(a.id(), b.id());
    assert_eq!(a.d0(), b.d0());
    assert_eq!(a.d1(), b.d1());
    assert_eq!(a.field_nodes(), b.field_nodes());
}
