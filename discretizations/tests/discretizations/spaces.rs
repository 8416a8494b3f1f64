//! Unit-level properties of the spaces and the error paths of tvf-discretizations.

use tvf_core::discretization::sparse::mul_vec;
use tvf_core::discretization::{
    BoundaryCondition, DiscretizationError, FieldRotation, FieldSampling, HodgeComplex,
    HodgeOperators,
};
use tvf_core::generate::{icosphere, torus};
use tvf_core::TriangleMesh;
use tvf_discretizations::{
    Conforming, CrouzeixRaviart, DecompositionError, FaceFields, FunctionSpace, HodgeDecomposer,
    LagrangeP1, MassLumping, Nonconforming, PaperSpace,
};

/// A linear function `f(p) = a·p + c` sampled at the nodes of a space.
fn sample(nodes: &[[f64; 3]], a: [f64; 3], c: f64) -> Vec<f64> {
    nodes
        .iter()
        .map(|p| a[0] * p[0] + a[1] * p[1] + a[2] * p[2] + c)
        .collect()
}

#[test]
fn gradients_and_interpolation_reproduce_linear_functions() {
    let mesh = torus(1.0, 0.4, 12, 6).expect("valid torus");
    let fields = FaceFields::new(&mesh).expect("valid mesh");
    let a = [0.3, -1.2, 0.7];
    let p1 = LagrangeP1::new(&mesh, MassLumping::Barycentric).expect("valid mesh");
    let cr = CrouzeixRaviart::new(&mesh, MassLumping::Voronoi).expect("valid mesh");
    let spaces: [&dyn FunctionSpace; 2] = [&p1, &cr];
    for space in spaces {
        let f = sample(&space.node_positions(), a, 2.5);
        // The gradient of a linear function is its tangential projection, per face.
        let gradient = fields
            .to_face_vectors(&mul_vec(space.gradient(), &f))
            .expect("right length");
        for (t, g) in gradient.iter().enumerate() {
            let n = fields.normal(t);
            let an = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
            for k in 0..3 {
                assert!(
                    (g[k] - (a[k] - an * n[k])).abs() < 1e-12,
                    "{}: face {t}",
                    space.name()
                );
            }
        }
        // Interpolation at a barycentric point reproduces the function there.
        let b = [0.2, 0.5, 0.3];
        for t in [0, 17, mesh.face_count() - 1] {
            let p: [f64; 3] =
                std::array::from_fn(|k| (0..3).map(|c| b[c] * mesh.corner(t, c)[k]).sum::<f64>());
            let weights = space.interpolation_weights(t, b);
            let value: f64 = weights.iter().map(|&(node, w)| w * f[node]).sum();
            let expected = sample(&[p], a, 2.5)[0];
            assert!(
                (value - expected).abs() < 1e-12,
                "{}: interpolation",
                space.name()
            );
            let total: f64 = weights.iter().map(|&(_, w)| w).sum();
            assert!((total - 1.0).abs() < 1e-15);
        }
    }
}

#[test]
fn vectors_round_trip_and_normal_parts_are_reported() {
    let mesh = icosphere(1);
    let fields = FaceFields::new(&mesh).expect("valid mesh");
    let field: Vec<f64> = (0..fields.field_dimension())
        .map(|i| (i as f64).cos())
        .collect();
    let vectors = fields.to_face_vectors(&field).expect("right length");
    let lifted: Vec<[f64; 3]> = vectors
        .iter()
        .enumerate()
        .map(|(t, v)| {
            let n = fields.normal(t);
            std::array::from_fn(|k| v[k] + 0.25 * n[k])
        })
        .collect();
    let projection = fields.from_face_vectors(&lifted).expect("right length");
    for (x, y) in projection.field.iter().zip(&field) {
        assert!((x - y).abs() < 1e-12);
    }
    assert!(projection
        .normal_parts
        .iter()
        .all(|p| (p - 0.25).abs() < 1e-12));
    assert!((projection.max_normal_part() - 0.25).abs() < 1e-12);
    assert_eq!(
        fields.from_face_vectors(&lifted[1..]),
        Err(DiscretizationError::DimensionMismatch {
            what: "per-face vectors",
            expected: 80,
            found: 79
        })
    );
    let mut bad = lifted.clone();
    bad[3][1] = f64::NAN;
    assert!(matches!(
        fields.from_face_vectors(&bad),
        Err(DiscretizationError::NonFinite { index: 3, .. })
    ));
    assert!(fields.to_face_vectors(&field[1..]).is_err());
    // J is a rotation by +π/2 about the normal: J v = n × v.
    let rotated = fields
        .to_face_vectors(&mul_vec(fields.rotation(), &field))
        .expect("right length");
    for (t, (r, v)) in rotated.iter().zip(&vectors).enumerate() {
        let n = fields.normal(t);
        let cross = [
            n[1] * v[2] - n[2] * v[1],
            n[2] * v[0] - n[0] * v[2],
            n[0] * v[1] - n[1] * v[0],
        ];
        for k in 0..3 {
            assert!((r[k] - cross[k]).abs() < 1e-12);
        }
    }
}

#[test]
fn degenerate_face_is_an_error() {
    let mesh = TriangleMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 3, 1]],
    )
    .expect("topologically valid");
    assert!(matches!(
        Conforming::new(&mesh, MassLumping::Barycentric),
        Err(DiscretizationError::DegenerateFace { face: 0, .. })
    ));
}

#[test]
fn open_mesh_decomposes_with_either_boundary_condition() {
    // A single square made of two triangles: every vertex and four edges on the boundary.
    let mesh = TriangleMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .expect("valid");
    for boundary in BoundaryCondition::ALL {
        let complex = Nonconforming::with_boundary(&mesh, MassLumping::Voronoi, boundary)
            .expect("valid geometry");
        assert!(complex.topology().has_boundary);
        assert_eq!(complex.topology().harmonic_dimension, 0, "a disk");
        assert_eq!(
            complex.id(),
            format!("nonconforming-voronoi+{}", boundary.name())
        );
        assert_eq!(complex.dirichlet_energy().shape(), (4, 4));
        let field = [0.3, -1.0, 2.0, 0.5];
        let parts = HodgeDecomposer::new(&complex)
            .expect("factors")
            .decompose(&field)
            .expect("decomposes");
        for (i, &v) in field.iter().enumerate() {
            let sum = parts.integrable[i] + parts.cointegrable[i] + parts.harmonic[i];
            assert!((sum - v).abs() < 1e-12);
            assert!(
                parts.harmonic[i].abs() < 1e-12,
                "no harmonic fields on a disk"
            );
        }
    }
}

#[test]
fn decomposition_rejects_wrong_input() {
    let mesh = icosphere(1);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).expect("valid mesh");
    let decomposer = HodgeDecomposer::new(&complex).expect("closed mesh");
    assert!(matches!(
        decomposer.decompose(&[0.0; 3]),
        Err(DecompositionError::Discretization(
            DiscretizationError::DimensionMismatch { .. }
        ))
    ));
    let mut field = vec![1.0; complex.field_dimension()];
    field[5] = f64::INFINITY;
    assert!(matches!(
        decomposer.decompose(&field),
        Err(DecompositionError::Discretization(
            DiscretizationError::NonFinite { index: 5, .. }
        ))
    ));
    // On a sphere there is no harmonic field.
    assert!(decomposer.harmonic_basis(1).expect("ok").is_empty());
}
