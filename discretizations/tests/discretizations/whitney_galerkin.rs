//! The Whitney–Galerkin complex: its Whitney mass against quadrature, `d0ᵀ M1 d0` against the
//! cotan formula, `M1` positive definite on meshes that are not Delaunay, the exact family P1
//! with the consistent mass and the co-exact family the mixed RT0–P0 Laplacian.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use sprs::CsMat;
use std::f64::consts::TAU;
use tvf_core::discretization::{
    BoundaryCondition, DiscretizationError, EigenStiffness, HodgeComplex, HodgeOperators,
};
use tvf_core::generate::{
    disk, genus_surface, icosphere, jitter, perforated_plate, rigid_motion, staggered_ring_faces,
    torus,
};
use tvf_core::geometry::{cross, dot, norm, scale, sub};
use tvf_core::{SurfacePoint, TriangleMesh};
use tvf_discretizations::{
    catalog_entry, consistent_p1_mass, face_geometry::FaceGeometry, whitney_mass, DecComplex,
    HodgeDecomposer, MassLumping, WhitneyGalerkin,
};

/// A torus of revolution (radii 1 and 0.4) whose rings of `around` vertices are staggered by half
/// a cell, with every vertex of ring 1 pulled to `thin` of its distance from the midpoint of
/// the two ring-0 vertices it sits between: the strip between rings 0 and 1 is made of cap
/// slivers (an angle near 180°, two near 0°), so the mesh is far from Delaunay.
fn sliver_torus(around: usize, tube: usize, thin: f64) -> TriangleMesh {
    let point = |ring: usize, i: usize| {
        let v = TAU * ring as f64 / tube as f64;
        let u = TAU * (i as f64 + 0.5 * (ring % 2) as f64) / around as f64;
        let radius = 1.0 + 0.4 * v.cos();
        [radius * u.cos(), radius * u.sin(), 0.4 * v.sin()]
    };
    let positions = (0..tube)
        .flat_map(|ring| {
            (0..around).map(move |i| {
                let p = point(ring, i);
                if ring != 1 {
                    return p;
                }
                let (a, b) = (point(0, i), point(0, i + 1));
                std::array::from_fn(|k| {
                    let mid = (a[k] + b[k]) / 2.0;
                    mid + thin * (p[k] - mid)
                })
            })
        })
        .collect();
    TriangleMesh::new(positions, staggered_ring_faces(around, tube, tube)).expect("valid torus")
}

/// Meshes that are not Delaunay (DEC refuses each): jittered, slivers, quad tori, with boundary.
fn non_delaunay_meshes() -> Vec<(&'static str, TriangleMesh)> {
    vec![
        (
            "jittered torus 16×8",
            jitter(&torus(1.0, 0.4, 16, 8).expect("valid torus"), 0.2, 3).expect("finite"),
        ),
        ("sliver torus", sliver_torus(12, 8, 0.01)),
        (
            "quad torus 16×8",
            torus(1.0, 0.4, 16, 8).expect("valid torus"),
        ),
        (
            "jittered genus-2 surface",
            jitter(&genus_surface(2, 2), 0.2, 5).expect("finite"),
        ),
        (
            "jittered pair of pants",
            jitter(&perforated_plate(2, 8), 0.2, 9).expect("finite"),
        ),
    ]
}

/// Every mesh of the checks: the non-Delaunay ones, a plain and a jittered icosphere and a disk
/// (with boundary).
fn meshes() -> Vec<(&'static str, TriangleMesh)> {
    let mut meshes = non_delaunay_meshes();
    meshes.push(("icosphere(2)", icosphere(2)));
    meshes.push((
        "jittered icosphere(2)",
        jitter(&icosphere(2), 0.2, 3).expect("finite"),
    ));
    meshes.push(("disk(4)", disk(4)));
    meshes
}

fn dense(a: &CsMat<f64>) -> Mat<f64> {
    let mut m = Mat::zeros(a.rows(), a.cols());
    for (&v, (i, j)) in a.iter() {
        m[(i, j)] += v;
    }
    m
}

fn max_abs(m: &Mat<f64>) -> f64 {
    let mut largest = 0.0f64;
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            largest = largest.max(m[(i, j)].abs());
        }
    }
    largest
}

/// Cotangent of the angle at corner `c` of face `t`, from the 3D positions.
fn corner_cotangent(mesh: &TriangleMesh, t: usize, c: usize) -> f64 {
    let o = mesh.corner(t, c);
    let u = sub(mesh.corner(t, (c + 1) % 3), o);
    let v = sub(mesh.corner(t, (c + 2) % 3), o);
    dot(u, v) / norm(cross(u, v))
}

/// The cotan matrix `−(cot α + cot β)/2` off the diagonal, rows summing to zero (dense).
fn cotan_matrix(mesh: &TriangleMesh) -> Mat<f64> {
    let n = mesh.vertex_count();
    let mut s = Mat::zeros(n, n);
    for (t, face) in mesh.faces().iter().enumerate() {
        for c in 0..3 {
            let w = corner_cotangent(mesh, t, c) / 2.0;
            let (i, j) = (face[(c + 1) % 3], face[(c + 2) % 3]);
            s[(i, j)] -= w;
            s[(j, i)] -= w;
            s[(i, i)] += w;
            s[(j, j)] += w;
        }
    }
    s
}

/// The three edge midpoints of a triangle in barycentric coordinates: the quadrature rule
/// `∫_T g ≈ |T|/3 Σ g(m)`, exact for polynomials of degree 2.
const MIDPOINTS: [[f64; 3]; 3] = [[0.0, 0.5, 0.5], [0.5, 0.0, 0.5], [0.5, 0.5, 0.0]];

/// The Whitney form `λ_p ∇λ_q − λ_q ∇λ_p` of the edge from corner `p` to corner `q` of face `t`
/// at barycentric point `b`, with `∇λ_c = n × (p_{c+2} − p_{c+1}) / 2A` (3D).
fn whitney_form(mesh: &TriangleMesh, t: usize, p: usize, q: usize, b: [f64; 3]) -> [f64; 3] {
    let corner: [[f64; 3]; 3] = std::array::from_fn(|c| mesh.corner(t, c));
    let scaled_normal = cross(sub(corner[1], corner[0]), sub(corner[2], corner[0]));
    let gradient = |c: usize| {
        scale(
            cross(scaled_normal, sub(corner[(c + 2) % 3], corner[(c + 1) % 3])),
            1.0 / dot(scaled_normal, scaled_normal),
        )
    };
    let (gp, gq) = (gradient(p), gradient(q));
    std::array::from_fn(|k| b[p] * gq[k] - b[q] * gp[k])
}

#[test]
fn element_masses_match_quadrature_of_the_whitney_forms() {
    let triangles: [(&str, [[f64; 3]; 3]); 5] = [
        (
            "equilateral",
            [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 0.75f64.sqrt(), 0.0]],
        ),
        (
            "obtuse",
            [[0.0, 0.0, 0.0], [3.0, 0.0, 0.0], [2.6, 0.4, 0.0]],
        ),
        (
            "cap sliver",
            [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.01, 0.0]],
        ),
        (
            "needle",
            [[0.0, 0.0, 0.0], [5.0, 0.0, 0.0], [5.0, 0.02, 0.0]],
        ),
        (
            "scalene",
            [[0.1, 0.2, 0.0], [1.3, -0.4, 0.0], [0.7, 0.9, 0.0]],
        ),
    ];
    let mut worst = 0.0f64;
    for (name, corners) in triangles {
        // Vertex numbers out of corner order, so that the edges run against the corners too.
        let flat = TriangleMesh::new(vec![corners[2], corners[0], corners[1]], vec![[1, 2, 0]])
            .expect("one triangle");
        let mesh = rigid_motion(&flat, [0.3, -0.7, 0.2], 1.1, [0.5, 2.0, -1.0]).expect("finite");
        let geometry = FaceGeometry::new(&mesh).expect("not degenerate");
        let assembled = dense(&whitney_mass(&mesh, &geometry));
        let complex = WhitneyGalerkin::new(&mesh).expect("builds");
        let sampling = complex.sampling().expect("Whitney sampling");
        let area = mesh.face_area(0);
        let mut quadrature = Mat::<f64>::zeros(3, 3);
        let mut sampled = Mat::<f64>::zeros(3, 3);
        for b in MIDPOINTS {
            // The form of mesh edge e = (a, b), a < b, from its lower to its higher vertex.
            let forms: Vec<[f64; 3]> = mesh
                .edges()
                .iter()
                .map(|&[a, v]| {
                    let corner = |x: usize| mesh.faces()[0].iter().position(|&y| y == x).unwrap();
                    whitney_form(&mesh, 0, corner(a), corner(v), b)
                })
                .collect();
            let mut from_sampling = [[0.0; 3]; 3];
            for (e, w) in sampling.sample_weights(&SurfacePoint::barycentric(0, b)) {
                from_sampling[e] = w;
            }
            for e in 0..3 {
                for f in 0..3 {
                    quadrature[(e, f)] += area / 3.0 * dot(forms[e], forms[f]);
                    sampled[(e, f)] += area / 3.0 * dot(from_sampling[e], from_sampling[f]);
                }
            }
        }
        let error = max_abs(&(&assembled - &quadrature)) / max_abs(&quadrature);
        let sampling_error = max_abs(&(&sampled - &quadrature)) / max_abs(&quadrature);
        eprintln!(
            "{name}: element mass vs quadrature {error:.1e}, sampled forms {sampling_error:.1e}"
        );
        assert!(error <= 1e-13, "{name}: element mass differs by {error:e}");
        assert!(
            sampling_error <= 1e-13,
            "{name}: sampled forms differ by {sampling_error:e}"
        );
        worst = worst.max(error);
    }
    eprintln!("worst element mass error (relative): {worst:.1e}");
}

#[test]
fn potential_stiffness_is_the_cotan_matrix() {
    for (name, mesh) in meshes() {
        let complex = WhitneyGalerkin::new(&mesh).expect("builds on every mesh");
        let stiffness = dense(complex.potential_stiffness());
        let cotan = cotan_matrix(&mesh);
        let error = max_abs(&(&stiffness - &cotan)) / max_abs(&cotan);
        eprintln!("{name}: |d0ᵀ M1 d0 − cotan| / |cotan| = {error:.1e}");
        assert!(
            error <= 1e-12,
            "{name}: d0ᵀ M1 d0 differs from cotan by {error:e}"
        );
    }
}

#[test]
fn whitney_mass_is_positive_definite_where_dec_refuses_the_mesh() {
    for (name, mesh) in non_delaunay_meshes() {
        assert!(
            matches!(
                DecComplex::new(&mesh, MassLumping::Barycentric),
                Err(DiscretizationError::NotDelaunay { .. })
            ),
            "{name} should not be Delaunay"
        );
        let complex = WhitneyGalerkin::new(&mesh).expect("builds on every mesh");
        let m1 = complex.m1().sparse_matrix().expect("M1 is stored directly");
        let transpose = m1.transpose_view().to_csr();
        assert_eq!(m1, transpose, "{name}: M1 is not exactly symmetric");
        let eigenvalues = dense(&m1)
            .self_adjoint_eigenvalues(Side::Lower)
            .expect("dense eigenvalues");
        let (low, high) = (eigenvalues[0], eigenvalues[eigenvalues.len() - 1]);
        let (min_angle, max_angle) = mesh.angle_range_deg();
        eprintln!(
            "{name}: angles {min_angle:.2}°–{max_angle:.2}°, eig(M1) in [{low:.2e}, {high:.2e}]"
        );
        assert!(
            low > 1e-6 * high,
            "{name}: M1 is not positive definite ({low:e})"
        );
    }
}

#[test]
fn exact_family_is_p1_with_the_consistent_mass() {
    let conforming = catalog_entry("conforming-consistent").expect("in the catalog");
    for (name, mesh) in meshes() {
        let whitney = WhitneyGalerkin::new(&mesh).expect("builds");
        let p1 = conforming.build(&mesh).expect("builds");
        let (a, b) = (whitney.exact_eigenproblem(), p1.exact_eigenproblem());
        let (EigenStiffness::Sparse(sa), EigenStiffness::Sparse(sb)) = (&a.stiffness, &b.stiffness)
        else {
            panic!("{name}: the exact stiffness is sparse");
        };
        let (sa, sb) = (dense(sa), dense(sb));
        let stiffness_error = max_abs(&(&sa - &sb)) / max_abs(&sb);
        let geometry = FaceGeometry::new(&mesh).expect("not degenerate");
        let consistent = dense(&consistent_p1_mass(&mesh, &geometry));
        let (ma, mb) = (
            dense(&a.mass.sparse_matrix().expect("M0 is sparse")),
            dense(&b.mass.sparse_matrix().expect("M0 is sparse")),
        );
        assert_eq!(max_abs(&(&ma - &consistent)), 0.0, "{name}: Whitney M0");
        assert_eq!(max_abs(&(&mb - &consistent)), 0.0, "{name}: conforming M0");
        eprintln!("{name}: exact stiffness, Whitney vs P1: {stiffness_error:.1e}");
        assert!(stiffness_error <= 1e-12, "{name}: {stiffness_error:e}");
    }
}

/// The lowest-order Raviart–Thomas mass, assembled from its own basis: in face `t` the function
/// of the edge opposite corner `c` is `σ (x − p_c) / 2|T|`, with unit flux through that edge,
/// outward for `σ = +1`; `σ` is `+1` where the face's counter-clockwise boundary runs along the
/// edge's orientation `a → b` (so the outward normal of one face is the global normal of the
/// edge) and `−1` in the other face. Integrated by the edge-midpoint rule (exact).
fn raviart_thomas_mass(mesh: &TriangleMesh) -> (Mat<f64>, Mat<f64>) {
    let (e, f) = (mesh.edge_count(), mesh.face_count());
    let mut mass = Mat::zeros(e, e);
    let mut divergence = Mat::zeros(f, e);
    for (t, (face, edges)) in mesh.faces().iter().zip(mesh.face_edges()).enumerate() {
        let area = mesh.face_area(t);
        let sign = |c: usize| {
            if face[(c + 1) % 3] < face[(c + 2) % 3] {
                1.0
            } else {
                -1.0
            }
        };
        for b in MIDPOINTS {
            let x: [f64; 3] =
                std::array::from_fn(|k| (0..3).map(|c| b[c] * mesh.corner(t, c)[k]).sum());
            let value = |c: usize| scale(sub(x, mesh.corner(t, c)), sign(c) / (2.0 * area));
            for c in 0..3 {
                for d in 0..3 {
                    mass[(edges[c], edges[d])] += area / 3.0 * dot(value(c), value(d));
                }
            }
        }
        // ∫_T div φ = σ · (2 / 2|T|) · |T| = σ: the flux out of the face.
        for c in 0..3 {
            divergence[(t, edges[c])] += sign(c);
        }
    }
    (mass, divergence)
}

/// Ascending eigenvalues of `(A, diag(m))`.
fn eigenvalues_with_diagonal_mass(a: &Mat<f64>, m: &[f64]) -> Vec<f64> {
    let scaled = Mat::from_fn(a.nrows(), a.ncols(), |i, j| {
        a[(i, j)] / (m[i] * m[j]).sqrt()
    });
    scaled
        .self_adjoint_eigenvalues(Side::Lower)
        .expect("dense eigenvalues")
}

#[test]
fn co_exact_family_is_the_mixed_rt0_p0_laplacian() {
    for (name, mesh) in meshes() {
        let complex = WhitneyGalerkin::new(&mesh).expect("builds");
        let (rt_mass, rt_divergence) = raviart_thomas_mass(&mesh);
        let m1 = dense(&complex.m1().sparse_matrix().expect("stored directly"));
        let mass_error = max_abs(&(&m1 - &rt_mass)) / max_abs(&rt_mass);
        assert!(mass_error <= 1e-12, "{name}: M1 vs RT0 mass {mass_error:e}");
        assert_eq!(
            max_abs(&(&dense(complex.d1()) - &rt_divergence)),
            0.0,
            "{name}: d1 is the RT0 divergence"
        );
        let areas: Vec<f64> = (0..mesh.face_count()).map(|t| mesh.face_area(t)).collect();
        let co_exact = complex.co_exact_eigenproblem();
        let co_mass = co_exact.mass.diagonal_values().expect("M2⁻¹ is diagonal");
        for (t, (&m, &area)) in co_mass.iter().zip(&areas).enumerate() {
            assert!((m - area).abs() <= 1e-14 * area, "{name}: M2⁻¹ of face {t}");
        }
        // Mixed RT0–P0: B M_RT⁻¹ Bᵀ with B the divergence, P0 mass the areas.
        let llt = rt_mass.llt(Side::Lower).expect("the RT0 mass is SPD");
        let schur = &rt_divergence * llt.solve(rt_divergence.transpose());
        let expected = eigenvalues_with_diagonal_mass(&schur, &areas);
        let EigenStiffness::Mixed { field_mass, d1 } = &co_exact.stiffness else {
            panic!("{name}: the co-exact stiffness of a Whitney mass is kept in mixed form");
        };
        let d1t = dense(d1).transpose().to_owned();
        let stiffness = dense(d1) * field_mass.solve_block(d1t.as_ref());
        let found = eigenvalues_with_diagonal_mass(&stiffness, &areas);
        let top = expected[expected.len() - 1];
        let error = found
            .iter()
            .zip(&expected)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
            / top;
        eprintln!("{name}: M1 vs RT0 mass {mass_error:.1e}, co-exact spectrum vs mixed RT0–P0 {error:.1e}");
        assert!(
            error <= 1e-10,
            "{name}: co-exact spectrum differs by {error:e} (λ_max {top})"
        );
    }
}

#[test]
fn both_boundary_conditions_decompose_and_fix_what_dec_fixes() {
    let mesh = jitter(&perforated_plate(2, 8), 0.2, 9).expect("finite");
    for boundary in BoundaryCondition::ALL {
        let complex = WhitneyGalerkin::with_boundary(&mesh, boundary).expect("builds");
        assert_eq!(
            complex.id(),
            format!("whitney-galerkin+{}", boundary.name())
        );
        let fixed = &complex.field_nodes().dirichlet;
        let expected_fixed = boundary == BoundaryCondition::Normal;
        for (e, &is_fixed) in fixed.iter().enumerate() {
            assert_eq!(
                is_fixed,
                expected_fixed && mesh.is_boundary_edge(e),
                "edge {e}"
            );
        }
        let field: Vec<f64> = (0..mesh.edge_count())
            .map(|e| {
                if fixed[e] {
                    0.0
                } else {
                    (e as f64 * 0.37).sin()
                }
            })
            .collect();
        let parts = HodgeDecomposer::new(&complex)
            .expect("factors")
            .decompose(&field)
            .expect("decomposes");
        let norm = complex.field_inner(&field, &field);
        for part in [&parts.integrable, &parts.cointegrable, &parts.harmonic] {
            assert!(
                (0..mesh.edge_count()).all(|e| !fixed[e] || part[e] == 0.0),
                "{}: a part is not zero on a fixed edge",
                boundary.name()
            );
        }
        let cross = complex.field_inner(&parts.integrable, &parts.cointegrable);
        assert!(
            cross.abs() <= 1e-10 * norm,
            "{}: {cross:e}",
            boundary.name()
        );
        // 2g + b − 1 = 2 harmonic fields for the pair of pants, as for DEC.
        assert_eq!(complex.topology().harmonic_dimension, 2);
    }
}
