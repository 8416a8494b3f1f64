//! Complexes with non-diagonal masses, built in test code by replacing masses of the catalog's
//! complexes, and dense references of the design problems on them.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use sprs::{CsMat, TriMat};
use tvf_core::discretization::{
    BoundaryCondition, ComplexParts, FieldRotation, FieldSampling, HodgeComplex, HodgeOperators,
    Mass, PointEvaluation,
};
use tvf_core::geometry::{cross, dot, norm, sub};
use tvf_core::TriangleMesh;
use tvf_design::{CompiledConstraint, SoftOptions};
use tvf_discretizations::{Conforming, DecComplex, MassLumping, Nonconforming};

/// A complex with some masses replaced (new parts, fresh operator cache), keeping the
/// capabilities of the complex it wraps.
pub struct Remassed<H> {
    inner: H,
    parts: ComplexParts,
}

impl<H: HodgeComplex> Remassed<H> {
    /// `inner` with `M0`, `M1`, `M2` replaced where given.
    pub fn new(inner: H, id: &str, masses: [Option<Mass>; 3]) -> Self {
        let [m0, m1, m2] = masses;
        let parts = ComplexParts::new(
            id,
            inner.d0().clone(),
            inner.d1().clone(),
            [
                m0.unwrap_or_else(|| inner.m0().clone()),
                m1.unwrap_or_else(|| inner.m1().clone()),
                m2.unwrap_or_else(|| inner.m2().clone()),
            ],
            [
                inner.potential_nodes().clone(),
                inner.field_nodes().clone(),
                inner.co_potential_nodes().clone(),
            ],
            *inner.topology(),
        )
        .expect("replaced masses are positive definite on the free nodes");
        Self { inner, parts }
    }
}

impl<H: HodgeComplex> HodgeComplex for Remassed<H> {
    fn parts(&self) -> &ComplexParts {
        &self.parts
    }
    fn sampling(&self) -> Option<&dyn FieldSampling> {
        self.inner.sampling()
    }
    fn rotation(&self) -> Option<&dyn FieldRotation> {
        self.inner.rotation()
    }
    fn point_evaluation(&self) -> Option<&dyn PointEvaluation> {
        self.inner.point_evaluation()
    }
}

fn area(mesh: &TriangleMesh, face: [usize; 3]) -> f64 {
    let p = face.map(|i| mesh.positions()[i]);
    let u = sub(p[1], p[0]);
    let v = sub(p[2], p[0]);
    0.5 * norm(cross(u, v))
}

/// The consistent P1 mass `Σ_T |T| (1 + δ_ij) / 12` (`V × V`).
pub fn consistent_p1_mass(mesh: &TriangleMesh) -> CsMat<f64> {
    let n = mesh.vertex_count();
    let mut t = TriMat::new((n, n));
    for &f in mesh.faces() {
        let a = area(mesh, f);
        for i in 0..3 {
            for j in 0..3 {
                let factor = if i == j { 2.0 } else { 1.0 };
                t.add_triplet(f[i], f[j], factor * a / 12.0);
            }
        }
    }
    t.to_csr()
}

/// The Whitney 1-form mass `∫ ⟨W_e, W_f⟩` (`E × E`) of the edges as DEC numbers and orients them
/// (`W_(a,b) = λ_a ∇λ_b − λ_b ∇λ_a` for `a < b`).
pub fn whitney_mass(mesh: &TriangleMesh) -> CsMat<f64> {
    let n = mesh.edge_count();
    let mut t = TriMat::new((n, n));
    for (face, edges) in mesh.faces().iter().zip(mesh.face_edges()) {
        let p = face.map(|i| mesh.positions()[i]);
        let a = area(mesh, *face);
        // ∇λ_c · ∇λ_d = (e_c · e_d) / 4|T|², e_c the edge vector opposite corner c.
        let opposite: [[f64; 3]; 3] = std::array::from_fn(|c| sub(p[(c + 2) % 3], p[(c + 1) % 3]));
        let grad = |c: usize, d: usize| dot(opposite[c], opposite[d]) / (4.0 * a * a);
        let lambda = |c: usize, d: usize| a * if c == d { 2.0 } else { 1.0 } / 12.0;
        let inner = |(p, q): (usize, usize), (r, s): (usize, usize)| {
            lambda(p, r) * grad(q, s) - lambda(p, s) * grad(q, r) - lambda(q, r) * grad(p, s)
                + lambda(q, s) * grad(p, r)
        };
        // Edge opposite corner c joins corners c+1 and c+2; local orientation low → high vertex.
        let local: [(usize, usize); 3] = std::array::from_fn(|c| {
            let (j, k) = ((c + 1) % 3, (c + 2) % 3);
            if face[j] < face[k] {
                (j, k)
            } else {
                (k, j)
            }
        });
        for c in 0..3 {
            for d in 0..3 {
                t.add_triplet(edges[c], edges[d], inner(local[c], local[d]));
            }
        }
    }
    t.to_csr()
}

/// The face mass `M_X` plus `δ Σ_e w_e |v_t − v_u|²` over the interior edges (faces `t`, `u`;
/// `v` the 3D vector of the face-frame coefficients, `w_e` a third of the two areas): sparse,
/// symmetric positive definite, coupling the coefficients of faces that share an edge.
pub fn coupled_face_mass(complex: &Conforming, mesh: &TriangleMesh, delta: f64) -> CsMat<f64> {
    let sampling = complex.sampling().expect("face fields are sampled");
    let areas = complex.m1().diagonal_values().expect("lumped face mass");
    let n = 2 * mesh.face_count();
    let mut t = TriMat::new((n, n));
    for (i, &m) in areas.iter().enumerate() {
        t.add_triplet(i, i, m);
    }
    let mut faces_of_edge = vec![Vec::new(); mesh.edge_count()];
    for (f, edges) in mesh.face_edges().iter().enumerate() {
        for &e in edges {
            faces_of_edge[e].push(f);
        }
    }
    for faces in faces_of_edge.iter().filter(|f| f.len() == 2) {
        let (a, b) = (faces[0], faces[1]);
        let w = delta * (areas[2 * a] + areas[2 * b]) / 3.0;
        let frames = [sampling.frame(a), sampling.frame(b)];
        // v_a − v_b = Σ_k s_k E_k x_k with s = (+1, −1).
        for (ka, &sa) in [1.0, -1.0].iter().enumerate() {
            for (kb, &sb) in [1.0, -1.0].iter().enumerate() {
                let (fa, fb) = ([a, b][ka], [a, b][kb]);
                for i in 0..2 {
                    for j in 0..2 {
                        let value = sa * sb * dot(frames[ka][i], frames[kb][j]);
                        t.add_triplet(2 * fa + i, 2 * fb + j, w * value);
                    }
                }
            }
        }
    }
    t.to_csr()
}

/// Conforming (barycentric) with the consistent P1 mass as `M0`.
pub fn conforming_consistent(
    mesh: &TriangleMesh,
    boundary: BoundaryCondition,
) -> Remassed<Conforming> {
    let inner = Conforming::with_boundary(mesh, MassLumping::Barycentric, boundary).unwrap();
    let m0 = Mass::sparse("M0 (consistent P1)", consistent_p1_mass(mesh)).unwrap();
    Remassed::new(inner, "conforming-consistent", [Some(m0), None, None])
}

/// Nonconforming (barycentric) with `M2⁻¹` the consistent P1 mass (`M2` dense).
pub fn nonconforming_consistent(mesh: &TriangleMesh) -> Remassed<Nonconforming> {
    let inner = Nonconforming::new(mesh, MassLumping::Barycentric).unwrap();
    let m2 = Mass::sparse_inverse("M2 (inverse consistent P1)", consistent_p1_mass(mesh)).unwrap();
    Remassed::new(inner, "nonconforming-consistent", [None, None, Some(m2)])
}

/// DEC with the consistent P1 mass as `M0` and the Whitney mass as `M1` (`M2 = ⋆2`).
pub fn whitney_galerkin(mesh: &TriangleMesh, boundary: BoundaryCondition) -> Remassed<DecComplex> {
    let inner = DecComplex::with_boundary(mesh, MassLumping::Voronoi, boundary).unwrap();
    let m0 = Mass::sparse("M0 (consistent P1)", consistent_p1_mass(mesh)).unwrap();
    let m1 = Mass::sparse("M1 (Whitney)", whitney_mass(mesh)).unwrap();
    Remassed::new(inner, "whitney-galerkin", [Some(m0), Some(m1), None])
}

/// Conforming (barycentric) with `M1` the [`coupled_face_mass`] (`δ = 0.3`): a sparse field
/// mass on face fields, so that the other family's operators are composed.
pub fn conforming_coupled_fields(mesh: &TriangleMesh) -> Remassed<Conforming> {
    let inner = Conforming::new(mesh, MassLumping::Barycentric).unwrap();
    let m1 = Mass::sparse("M1 (coupled faces)", coupled_face_mass(&inner, mesh, 0.3)).unwrap();
    Remassed::new(inner, "conforming-coupled-fields", [None, Some(m1), None])
}

/// A flat patch of `2n²` equilateral triangles (Delaunay, one boundary loop).
pub fn flat_patch(n: usize) -> TriangleMesh {
    let index = |i: usize, j: usize| j * (n + 1) + i;
    let positions = (0..=n)
        .flat_map(|j| {
            (0..=n).map(move |i| [i as f64 + 0.5 * j as f64, j as f64 * 3f64.sqrt() / 2.0, 0.0])
        })
        .collect();
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            faces.push([index(i, j), index(i + 1, j), index(i, j + 1)]);
            faces.push([index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)]);
        }
    }
    TriangleMesh::new(positions, faces).expect("valid patch")
}

/// The free field nodes of a complex.
pub fn free_fields<H: HodgeComplex + ?Sized>(complex: &H) -> Vec<usize> {
    let nodes = complex.field_nodes();
    (0..nodes.len()).filter(|&i| nodes.is_free(i)).collect()
}

/// `M1` dense on the free field nodes.
pub fn dense_field_mass<H: HodgeComplex + ?Sized>(complex: &H) -> Mat<f64> {
    let free = free_fields(complex);
    let stored = complex.m1().stored_matrix();
    let mut position = vec![usize::MAX; complex.field_dimension()];
    for (k, &i) in free.iter().enumerate() {
        position[i] = k;
    }
    let mut m = Mat::zeros(free.len(), free.len());
    for (&v, (i, j)) in stored.iter() {
        if position[i] != usize::MAX && position[j] != usize::MAX {
            m[(position[i], position[j])] += v;
        }
    }
    m
}

/// `S` dense on the free field nodes (the seam's operator applied to unit vectors).
pub fn dense_dirichlet<H: HodgeComplex + ?Sized>(complex: &H) -> Mat<f64> {
    let free = free_fields(complex);
    let s = complex.dirichlet_energy().to_dense();
    Mat::from_fn(free.len(), free.len(), |i, j| s[(free[i], free[j])])
}

/// `M1⁻¹ S` and `S M1⁻¹ S` dense on the free field nodes.
fn dense_biharmonic<H: HodgeComplex + ?Sized>(complex: &H) -> (Mat<f64>, Mat<f64>) {
    let s = dense_dirichlet(complex);
    let m = dense_field_mass(complex);
    let laplacian = m.llt(Side::Lower).expect("M1 is SPD").solve(&s);
    let b = &s * &laplacian;
    (s, b)
}

/// A constraint row restricted to the free field nodes, dense.
fn dense_row(row: &[(usize, f64)], free: &[usize], n1: usize) -> Vec<f64> {
    let mut full = vec![0.0; n1];
    for &(j, a) in row {
        full[j] += a;
    }
    free.iter().map(|&i| full[i]).collect()
}

/// The full soft design `(S + ωB + εM1 + C̃ᵀWC̃) x = C̃ᵀWc` solved densely (`n1` values, zero on
/// fixed field nodes).
pub fn dense_soft_design<H: HodgeComplex + ?Sized>(
    complex: &H,
    options: SoftOptions,
    constraints: &[CompiledConstraint],
) -> Vec<f64> {
    let free = free_fields(complex);
    let n1 = complex.field_dimension();
    let (s, b) = dense_biharmonic(complex);
    let m = dense_field_mass(complex);
    let n = free.len();
    let mut a = Mat::from_fn(n, n, |i, j| {
        s[(i, j)] + options.omega * b[(i, j)] + options.regularization * m[(i, j)]
    });
    let mut rhs = Mat::zeros(n, 1);
    for c in constraints {
        for (row, value) in c.rows.iter().zip(&c.values) {
            let r = dense_row(row, &free, n1);
            for i in 0..n {
                rhs[(i, 0)] += c.weight * r[i] * value;
                for j in 0..n {
                    a[(i, j)] += c.weight * r[i] * r[j];
                }
            }
        }
    }
    let x = symmetric_solve(&a, &rhs);
    scatter(&free, n1, &x)
}

/// The spline `min xᵀ(B + ωS + εM1)x` s.t. `C̃x = c` solved densely through its KKT system
/// (`n1` values, zero on fixed field nodes).
pub fn dense_spline<H: HodgeComplex + ?Sized>(
    complex: &H,
    omega: f64,
    epsilon: f64,
    constraints: &[CompiledConstraint],
) -> Vec<f64> {
    let free = free_fields(complex);
    let n1 = complex.field_dimension();
    let (s, b) = dense_biharmonic(complex);
    let m = dense_field_mass(complex);
    let n = free.len();
    let rows: Vec<(Vec<f64>, f64)> = constraints
        .iter()
        .flat_map(|c| c.rows.iter().zip(&c.values))
        .map(|(row, &v)| (dense_row(row, &free, n1), v))
        .collect();
    let nc = rows.len();
    let mut kkt = Mat::zeros(n + nc, n + nc);
    for i in 0..n {
        for j in 0..n {
            kkt[(i, j)] = b[(i, j)] + omega * s[(i, j)] + epsilon * m[(i, j)];
        }
    }
    let mut rhs = Mat::zeros(n + nc, 1);
    for (k, (row, value)) in rows.iter().enumerate() {
        for i in 0..n {
            kkt[(n + k, i)] = row[i];
            kkt[(i, n + k)] = row[i];
        }
        rhs[(n + k, 0)] = *value;
    }
    let solution = kkt.partial_piv_lu().solve(&rhs);
    let x: Vec<f64> = (0..n).map(|i| solution[(i, 0)]).collect();
    scatter(&free, n1, &x)
}

fn symmetric_solve(a: &Mat<f64>, rhs: &Mat<f64>) -> Vec<f64> {
    let x = a
        .llt(Side::Lower)
        .expect("the dense system is SPD")
        .solve(rhs);
    (0..a.nrows()).map(|i| x[(i, 0)]).collect()
}

fn scatter(free: &[usize], n1: usize, x: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; n1];
    for (&i, &v) in free.iter().zip(x) {
        out[i] = v;
    }
    out
}

/// `‖a − b‖_{M1} / ‖b‖_{M1}` with a sparse or diagonal `M1`.
pub fn mass_relative_difference<H: HodgeComplex + ?Sized>(
    complex: &H,
    a: &[f64],
    b: &[f64],
) -> f64 {
    let diff: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    (complex.m1().inner(&diff, &diff) / complex.m1().inner(b, b)).sqrt()
}
