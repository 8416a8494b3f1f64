//! The consistent (Galerkin) P1 mass and the catalog entries that use it: its rows sum to the
//! barycentric lumped mass; `conforming-consistent` and `nonconforming-consistent` have the
//! spectrum `eig(cotan, consistent P1 mass) ∪ eig(CR stiffness, CR mass)` on a closed mesh and
//! pair the Neumann and Dirichlet problems with boundary; vertices no face uses leave every mass.

use faer::Mat;
use tvf_core::discretization::{
    BoundaryCondition, HodgeComplex, HodgeOperators, MassForm, NodeKind,
};
use tvf_core::generate::{disk, icosphere, jitter, open_cylinder, torus};
use tvf_core::geometry::{cross, dot, norm, sub};
use tvf_core::TriangleMesh;
use tvf_discretizations::{
    catalog_entry, consistent_p1_mass, face_geometry::FaceGeometry, FunctionSpace, HodgeDecomposer,
    LagrangeP1, MassLumping, MatrixComplex, MatrixSampling, PaperSpace,
};
use tvf_solvers::{dense_generalized_eigen, dense_generalized_eigen_with_mass};

/// The three entries with Galerkin masses.
const CONSISTENT_ENTRIES: [&str; 3] = [
    "conforming-consistent",
    "nonconforming-consistent",
    "whitney-galerkin",
];

fn corner_cotangent(mesh: &TriangleMesh, t: usize, c: usize) -> f64 {
    let o = mesh.corner(t, c);
    let u = sub(mesh.corner(t, (c + 1) % 3), o);
    let v = sub(mesh.corner(t, (c + 2) % 3), o);
    dot(u, v) / norm(cross(u, v))
}

/// A scalar problem `(stiffness, mass)` of one space, dense, from the explicit formulas.
struct ScalarProblem {
    stiffness: Mat<f64>,
    mass: Mat<f64>,
    /// The nodes on the boundary (vertices of boundary edges, or boundary edges).
    boundary: Vec<bool>,
}

/// The cotan matrix with the consistent mass `|T| (1 + δ_ij)/12`, on vertices.
fn p1_problem(mesh: &TriangleMesh) -> ScalarProblem {
    let n = mesh.vertex_count();
    let (mut stiffness, mut mass) = (Mat::zeros(n, n), Mat::zeros(n, n));
    for (t, face) in mesh.faces().iter().enumerate() {
        let area = mesh.face_area(t);
        for c in 0..3 {
            let w = corner_cotangent(mesh, t, c) / 2.0;
            let (i, j) = (face[(c + 1) % 3], face[(c + 2) % 3]);
            stiffness[(i, j)] -= w;
            stiffness[(j, i)] -= w;
            stiffness[(i, i)] += w;
            stiffness[(j, j)] += w;
            for d in 0..3 {
                mass[(face[c], face[d])] += area * if c == d { 2.0 } else { 1.0 } / 12.0;
            }
        }
    }
    let mut boundary = vec![false; n];
    for e in mesh.boundary_edges() {
        for v in mesh.edges()[e] {
            boundary[v] = true;
        }
    }
    ScalarProblem {
        stiffness,
        mass,
        boundary,
    }
}

/// The Crouzeix–Raviart stiffness (edges opposite corners `i`, `j` couple by `−2 cot θ_k`) with
/// its mass `|T|/3` per face and edge (the basis is `L²`-orthogonal), on edges.
fn crouzeix_raviart_problem(mesh: &TriangleMesh) -> ScalarProblem {
    let n = mesh.edge_count();
    let (mut stiffness, mut mass) = (Mat::zeros(n, n), Mat::zeros(n, n));
    for (t, edges) in mesh.face_edges().iter().enumerate() {
        let cot: [f64; 3] = std::array::from_fn(|c| corner_cotangent(mesh, t, c));
        for k in 0..3 {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            stiffness[(edges[i], edges[j])] -= 2.0 * cot[k];
            stiffness[(edges[j], edges[i])] -= 2.0 * cot[k];
            stiffness[(edges[k], edges[k])] += 2.0 * (cot[i] + cot[j]);
            mass[(edges[k], edges[k])] += mesh.face_area(t) / 3.0;
        }
    }
    let boundary = (0..n).map(|e| mesh.is_boundary_edge(e)).collect();
    ScalarProblem {
        stiffness,
        mass,
        boundary,
    }
}

impl ScalarProblem {
    /// The eigenvalues on every node (Neumann) or on the interior nodes (`dirichlet`).
    fn eigenvalues(&self, dirichlet: bool) -> Vec<f64> {
        let keep: Vec<usize> = (0..self.boundary.len())
            .filter(|&i| !(dirichlet && self.boundary[i]))
            .collect();
        let pick =
            |m: &Mat<f64>| Mat::from_fn(keep.len(), keep.len(), |a, b| m[(keep[a], keep[b])]);
        dense_generalized_eigen_with_mass(pick(&self.stiffness).as_ref(), pick(&self.mass).as_ref())
            .expect("dense eigenvalues")
            .0
    }
}

/// The nonzero values of an ascending spectrum (those above `1e-9 ·` its largest) and the count
/// of the others.
fn nonzero(values: &[f64]) -> (usize, Vec<f64>) {
    let top = values.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let rest: Vec<f64> = values
        .iter()
        .copied()
        .filter(|x| x.abs() > 1e-9 * top)
        .collect();
    (values.len() - rest.len(), rest)
}

/// The spectrum of `L`: eigenvalues of `(S, M1)` with `S` formed densely and `M1` diagonal.
fn hodge_spectrum(complex: &dyn HodgeComplex) -> Vec<f64> {
    let m1 = complex
        .m1()
        .diagonal_values()
        .expect("face fields: M1 is diagonal");
    dense_generalized_eigen(complex.dirichlet_energy().to_dense().as_ref(), m1)
        .expect("dense eigenvalues")
        .0
}

/// `L` of the finite-element entry `id` with `boundary` has `harmonic` zeros and the nonzero
/// spectrum of the P1 problem (Dirichlet if `p1_dirichlet`) joined with the CR problem (the
/// other condition); returns the largest difference relative to `λ_max`.
fn union_error(
    mesh: &TriangleMesh,
    id: &str,
    boundary: BoundaryCondition,
    p1_dirichlet: bool,
    harmonic: usize,
) -> f64 {
    let complex = catalog_entry(id)
        .expect("in the catalog")
        .build_with(mesh, boundary)
        .expect("builds");
    let (zeros, spectrum) = nonzero(&hodge_spectrum(complex.as_ref()));
    assert_eq!(zeros, harmonic, "{id}: zeros of L");
    let p1 = nonzero(&p1_problem(mesh).eigenvalues(p1_dirichlet)).1;
    let cr = nonzero(&crouzeix_raviart_problem(mesh).eigenvalues(!p1_dirichlet)).1;
    let mut union: Vec<f64> = p1.into_iter().chain(cr).collect();
    union.sort_by(f64::total_cmp);
    assert_eq!(union.len(), spectrum.len(), "{id}: nonzero eigenvalues");
    let top = spectrum[spectrum.len() - 1];
    spectrum
        .iter()
        .zip(&union)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / top
}

#[test]
fn consistent_mass_rows_sum_to_the_barycentric_mass() {
    for mesh in [
        icosphere(2),
        jitter(&torus(1.0, 0.4, 12, 6).unwrap(), 0.2, 1).unwrap(),
        disk(3),
    ] {
        let geometry = FaceGeometry::new(&mesh).expect("not degenerate");
        let consistent = consistent_p1_mass(&mesh, &geometry);
        assert_eq!(
            consistent,
            consistent.transpose_view().to_csr(),
            "symmetric"
        );
        let lumped = LagrangeP1::new(&mesh, MassLumping::Barycentric).expect("builds");
        let mut rows = vec![0.0; mesh.vertex_count()];
        for (&v, (i, _)) in consistent.iter() {
            rows[i] += v;
        }
        for (i, (&row, &m)) in rows.iter().zip(lumped.mass()).enumerate() {
            assert!(
                (row - m).abs() <= 1e-15 * m,
                "vertex {i}: row sum {row} vs lumped {m}"
            );
        }
        let total: f64 = consistent.data().iter().sum();
        let area = mesh.total_area();
        assert!(
            (total - area).abs() <= 1e-13 * area,
            "1ᵀ M 1 = {total} vs area {area}"
        );
    }
}

#[test]
fn consistent_entries_have_the_union_spectrum_on_closed_meshes() {
    let meshes = [
        ("icosphere(1)", icosphere(1), 0),
        (
            "jittered torus 10×6",
            jitter(&torus(1.0, 0.4, 10, 6).unwrap(), 0.2, 4).unwrap(),
            2,
        ),
    ];
    for (name, mesh, harmonic) in meshes {
        for id in ["conforming-consistent", "nonconforming-consistent"] {
            let error = union_error(&mesh, id, BoundaryCondition::default(), false, harmonic);
            eprintln!("{name}, {id}: eig(L) vs eig(cotan, consistent) ∪ eig(CR): {error:.1e}");
            assert!(error <= 1e-10, "{name}, {id}: {error:e}");
        }
    }
}

#[test]
fn boundary_conditions_pair_neumann_and_dirichlet_problems() {
    let meshes = [
        ("disk(3)", disk(3), 0),
        ("open cylinder 8×3", open_cylinder(8, 3, 1.0), 1),
    ];
    // (entry, condition, whether the P1 problem is the Dirichlet one)
    let cases = [
        (
            "conforming-consistent",
            BoundaryCondition::Tangential,
            false,
        ),
        ("conforming-consistent", BoundaryCondition::Normal, true),
        (
            "nonconforming-consistent",
            BoundaryCondition::Tangential,
            true,
        ),
        ("nonconforming-consistent", BoundaryCondition::Normal, false),
    ];
    for (name, mesh, harmonic) in meshes {
        for (id, boundary, p1_dirichlet) in cases {
            let error = union_error(&mesh, id, boundary, p1_dirichlet, harmonic);
            eprintln!("{name}, {id}+{}: {error:.1e}", boundary.name());
            assert!(
                error <= 1e-10,
                "{name}, {id}+{}: {error:e}",
                boundary.name()
            );
        }
    }
}

#[test]
fn nonconforming_consistent_stores_m2_as_its_sparse_inverse() {
    let mesh = icosphere(1);
    let complex = catalog_entry("nonconforming-consistent")
        .unwrap()
        .build(&mesh)
        .unwrap();
    let m2 = complex.m2();
    assert_eq!(m2.form(), MassForm::Inverse);
    assert!(m2.sparse_matrix().is_none(), "M2 itself is dense");
    let geometry = FaceGeometry::new(&mesh).unwrap();
    assert_eq!(
        m2.sparse_inverse_matrix().expect("M2⁻¹ is sparse"),
        consistent_p1_mass(&mesh, &geometry)
    );
    // M2 M2⁻¹ x = x.
    let x: Vec<f64> = (0..mesh.vertex_count()).map(|i| (i as f64).cos()).collect();
    let back = m2.apply(&m2.solve(&x));
    let error = back
        .iter()
        .zip(&x)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(error <= 1e-12, "M2 M2⁻¹ x differs from x by {error:e}");
}

/// `mesh` with `extra` vertices no face uses appended.
fn with_unreferenced_vertices(mesh: &TriangleMesh, extra: usize) -> TriangleMesh {
    let mut positions = mesh.positions().to_vec();
    positions.extend((0..extra).map(|k| [5.0 + k as f64, -3.0, 2.0]));
    TriangleMesh::new(positions, mesh.faces().to_vec()).expect("unreferenced vertices are valid")
}

#[test]
fn unreferenced_vertices_leave_the_masses() {
    let mesh = jitter(&torus(1.0, 0.4, 10, 6).unwrap(), 0.2, 2).unwrap();
    let padded = with_unreferenced_vertices(&mesh, 3);
    let v = mesh.vertex_count();
    for id in CONSISTENT_ENTRIES {
        let entry = catalog_entry(id).unwrap();
        let plain = entry.build(&mesh).unwrap();
        let complex = entry.build(&padded).unwrap_or_else(|e| panic!("{id}: {e}"));
        // The P1 space (potentials, or co-potentials for the nonconforming complex): its unused
        // vertices are not free, their rows of the consistent mass are empty and every solve
        // with the mass leaves them at zero.
        let (nodes, mass) = if complex.potential_nodes().kind == NodeKind::Vertices {
            (complex.potential_nodes(), complex.m0().clone())
        } else {
            (complex.co_potential_nodes(), complex.m2().inverse())
        };
        let ones = vec![1.0; padded.vertex_count()];
        let (applied, solved) = (mass.apply(&ones), mass.solve(&ones));
        for i in v..padded.vertex_count() {
            assert!(!nodes.is_free(i), "{id}: unused vertex {i} is free");
            assert_eq!((applied[i], solved[i]), (0.0, 0.0), "{id}: vertex {i}");
        }
        // The Hodge decomposition is that of the mesh without them.
        let field: Vec<f64> = (0..complex.field_dimension())
            .map(|i| (0.3 * i as f64).sin())
            .collect();
        let parts = HodgeDecomposer::new(complex.as_ref())
            .unwrap_or_else(|e| panic!("{id}: {e}"))
            .decompose(&field)
            .unwrap();
        let plain_parts = HodgeDecomposer::new(plain.as_ref())
            .unwrap()
            .decompose(&field)
            .unwrap();
        let scale = norm_max(&field);
        for (a, b) in [
            (&parts.integrable, &plain_parts.integrable),
            (&parts.cointegrable, &plain_parts.cointegrable),
            (&parts.harmonic, &plain_parts.harmonic),
        ] {
            let error = a
                .iter()
                .zip(b)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            assert!(
                error <= 1e-9 * scale,
                "{id}: decomposition differs by {error:e}"
            );
        }
    }
    // A complex from matrices keeps the unused vertices and the zero rows of its M0.
    let whitney = catalog_entry("whitney-galerkin")
        .unwrap()
        .build(&padded)
        .unwrap();
    let rebuilt = MatrixComplex::new(
        "whitney-from-matrices",
        &padded.clone().into(),
        whitney.d0().clone(),
        whitney.d1().clone(),
        whitney.m0().clone(),
        whitney.m1().clone(),
        whitney.m2().clone(),
        MatrixSampling::Whitney,
    )
    .expect("zero rows of M0 at unused vertices are accepted");
    let field: Vec<f64> = (0..rebuilt.field_dimension())
        .map(|i| (i as f64).cos())
        .collect();
    let parts = HodgeDecomposer::new(&rebuilt)
        .unwrap()
        .decompose(&field)
        .unwrap();
    let norm = rebuilt.field_inner(&field, &field);
    let cross = rebuilt.field_inner(&parts.integrable, &parts.cointegrable);
    assert!(
        cross.abs() <= 1e-10 * norm,
        "integrable and co-integrable parts: {cross:e}"
    );
}

fn norm_max(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}
