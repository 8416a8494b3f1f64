//! Dense generalized symmetric-definite eigenproblems `A x = λ M x` (faer) for the checks on
//! small meshes: the stiffness formed densely from a sparse matrix or a [`LinearOperator`], the
//! mass a positive diagonal or a dense SPD matrix ([`DenseMass`]).

use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par, Side};
use sprs::CsMat;
use tvf_core::discretization::{
    EigenStiffness, Eigenproblem, HodgeComplex, LinearOperator, Mass, NodeSpace,
};
use tvf_solvers::symmetric_eigen;

/// The mass of a dense generalized eigenproblem.
#[derive(Debug, Clone)]
pub enum DenseMass {
    /// A diagonal (`n` entries).
    Diagonal(Vec<f64>),
    /// A symmetric matrix (`n × n`).
    Full(Mat<f64>),
}

impl DenseMass {
    /// The matrix `M` of a seam mass: its diagonal, or `M` applied to the identity (a mass
    /// stored as its inverse is applied through its factorization, on its free nodes).
    pub fn of(mass: &Mass) -> Self {
        match mass.diagonal_values() {
            Some(values) => DenseMass::Diagonal(values.to_vec()),
            None => {
                let n = mass.len();
                DenseMass::Full(mass.apply_block(Mat::<f64>::identity(n, n).as_ref()))
            }
        }
    }

    /// Number of rows `n`.
    pub fn len(&self) -> usize {
        match self {
            DenseMass::Diagonal(values) => values.len(),
            DenseMass::Full(m) => m.nrows(),
        }
    }

    /// Whether the mass has no row.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The rows and columns `keep` (full indices).
    fn restricted(&self, keep: &[usize]) -> Self {
        match self {
            DenseMass::Diagonal(values) => {
                DenseMass::Diagonal(keep.iter().map(|&i| values[i]).collect())
            }
            DenseMass::Full(m) => DenseMass::Full(pick(m, keep)),
        }
    }
}

/// A sparse matrix as a dense one (duplicates summed).
pub fn dense(a: &CsMat<f64>) -> Mat<f64> {
    LinearOperator::Sparse(a.clone()).to_dense()
}

/// The stiffness of an eigenproblem as a dense matrix: the sparse matrix, or `d1 W⁻¹ d1ᵀ` of a
/// mixed one formed column by column through `W`'s solves.
pub fn dense_stiffness(stiffness: &EigenStiffness) -> Mat<f64> {
    match stiffness {
        EigenStiffness::Sparse(a) => dense(a),
        EigenStiffness::Mixed { field_mass, d1 } => {
            let d1 = LinearOperator::Sparse(d1.clone());
            let d1t = d1.to_dense().transpose().to_owned();
            d1.apply_block(field_mass.solve_block(d1t.as_ref()).as_ref())
        }
    }
}

/// Rows and columns `keep` of a square matrix.
fn pick(a: &Mat<f64>, keep: &[usize]) -> Mat<f64> {
    Mat::from_fn(keep.len(), keep.len(), |r, c| a[(keep[r], keep[c])])
}

/// The symmetric matrix `C` with the eigenvalues of `(A, M)`, and how to map its eigenvectors
/// back: `D^{-1/2} A D^{-1/2}` for a diagonal `M = D` (`D > 0`), `L⁻¹ A L⁻ᵀ` with the Cholesky
/// factor `M = L Lᵀ` of a full one. An error if `M` is not positive definite or the transformed
/// matrix is not finite (a mass so small, e.g. `1e-310`, that `1/√m` overflows).
fn transformed(a: &Mat<f64>, mass: &DenseMass) -> Result<(Mat<f64>, Back), String> {
    let n = a.nrows();
    assert_eq!(mass.len(), n, "one mass row per row");
    let (c, back) = match mass {
        DenseMass::Diagonal(values) => {
            if let Some(i) = values.iter().position(|&m| m.is_nan() || m <= 0.0) {
                return Err(format!(
                    "the mass is not positive (entry {i} is {})",
                    values[i]
                ));
            }
            let scale: Vec<f64> = values.iter().map(|m| 1.0 / m.sqrt()).collect();
            let c = Mat::from_fn(n, n, |i, j| a[(i, j)] * scale[i] * scale[j]);
            (c, Back::Scale(scale))
        }
        DenseMass::Full(m) => {
            let symmetric = Mat::from_fn(n, n, |i, j| 0.5 * (m[(i, j)] + m[(j, i)]));
            let llt = symmetric
                .llt(Side::Lower)
                .map_err(|_| "the mass is not positive definite (no Cholesky factor)")?;
            let l = llt.L().to_owned();
            let mut y = a.clone();
            solve_lower_triangular_in_place(l.as_ref(), y.as_mut(), Par::Seq);
            let mut c = y.transpose().to_owned();
            solve_lower_triangular_in_place(l.as_ref(), c.as_mut(), Par::Seq);
            let c = Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]));
            (c, Back::Cholesky(l))
        }
    };
    if c.col_iter()
        .any(|column| column.iter().any(|x| !x.is_finite()))
    {
        return Err(
            "the pencil scaled by the mass is not finite (a mass entry so small, or a stiffness \
             entry so large, that the ratio overflows)"
                .into(),
        );
    }
    Ok((c, back))
}

/// How eigenvectors of the transformed problem map back to those of `(A, M)`.
enum Back {
    /// `x = D^{-1/2} y`.
    Scale(Vec<f64>),
    /// `x = L⁻ᵀ y`.
    Cholesky(Mat<f64>),
}

/// Eigenvalues (ascending) of the generalized problem `A x = λ M x`, `A` symmetric (`n × n`) and
/// `M` positive definite, from the symmetric transformed problem (its lower triangle); an error
/// saying why they cannot be computed (a mass that is not positive definite, an overflow, no
/// convergence).
pub fn generalized_eigenvalues(a: &Mat<f64>, mass: &DenseMass) -> Result<Vec<f64>, String> {
    transformed(a, mass)?
        .0
        .self_adjoint_eigenvalues(Side::Lower)
        .map_err(|e| format!("the dense eigensolver did not converge ({e:?})"))
}

/// All eigenpairs of `A x = λ M x`, ascending: `(λ, X)` with the columns of `X` (`n × n`)
/// `M`-orthonormal, from [`symmetric_eigen`] on the transformed problem (every pair with a
/// round-off residual: faer's divide and conquer alone misses it on some close pairs); an error
/// as for [`generalized_eigenvalues`].
pub fn generalized_eigenpairs(
    a: &Mat<f64>,
    mass: &DenseMass,
) -> Result<(Vec<f64>, Mat<f64>), String> {
    let (c, back) = transformed(a, mass)?;
    let (values, mut vectors) = symmetric_eigen(c.as_ref()).map_err(|e| e.to_string())?;
    match back {
        Back::Scale(scale) => {
            for j in 0..vectors.ncols() {
                for (i, s) in scale.iter().enumerate() {
                    vectors[(i, j)] *= s;
                }
            }
        }
        Back::Cholesky(l) => {
            solve_upper_triangular_in_place(l.transpose(), vectors.as_mut(), Par::Seq)
        }
    }
    Ok((values, vectors))
}

/// Splits ascending eigenvalues into (count of those `≤ tolerance · max`, the rest).
pub fn split_zeros(eigenvalues: &[f64], relative_tolerance: f64) -> (usize, Vec<f64>) {
    let max = eigenvalues.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let zeros = eigenvalues
        .iter()
        .filter(|x| x.abs() <= relative_tolerance * max)
        .count();
    let rest = eigenvalues
        .iter()
        .copied()
        .filter(|x| x.abs() > relative_tolerance * max)
        .collect();
    (zeros, rest)
}

/// The problem `(a, mass)` restricted to the free nodes of `nodes` ([`NodeSpace::is_free`]):
/// the restricted stiffness and mass, and the full index of every restricted node.
pub fn restrict_to_free(
    a: &Mat<f64>,
    mass: &DenseMass,
    nodes: &NodeSpace,
) -> (Mat<f64>, DenseMass, Vec<usize>) {
    let free: Vec<usize> = (0..nodes.len()).filter(|&i| nodes.is_free(i)).collect();
    (pick(a, &free), mass.restricted(&free), free)
}

/// A scalar eigenproblem of a complex in dense form, restricted to the free nodes of `nodes`
/// ([`restrict_to_free`]).
pub fn free_eigenproblem(
    problem: &Eigenproblem,
    nodes: &NodeSpace,
) -> (Mat<f64>, DenseMass, Vec<usize>) {
    restrict_to_free(
        &dense_stiffness(&problem.stiffness),
        &DenseMass::of(&problem.mass),
        nodes,
    )
}

/// The dense problem `(S, M1)` of the Hodge–Laplacian `L = M1⁻¹ S`, restricted to the free field
/// nodes: its eigenvalues are the spectrum of `L`. `dirichlet_energy` is `S` formed densely
/// (`complex.dirichlet_energy().to_dense()`, `n1 × n1`).
pub fn hodge_pencil<H: HodgeComplex + ?Sized>(
    complex: &H,
    dirichlet_energy: &Mat<f64>,
) -> (Mat<f64>, DenseMass, Vec<usize>) {
    restrict_to_free(
        dirichlet_energy,
        &DenseMass::of(complex.m1()),
        complex.field_nodes(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::discretization::HodgeOperators;
    use tvf_core::generate::genus_surface;
    use tvf_discretizations::build_complex;

    /// The co-exact pencil of `conforming-voronoi` on the coarse genus-5 plate (624 edges) has
    /// eigenvalue pairs `6.6e-8` apart near 393 (λ_max ≈ 469), where faer's divide and conquer
    /// alone returned a pair with `‖A x − λ M x‖_{M⁻¹} = 1.6e-5`: every pair must have a
    /// round-off residual, `≤ 1e-12 · λ_max`.
    #[test]
    fn eigenpairs_of_a_pencil_with_close_pairs_have_round_off_residuals() {
        let mesh = genus_surface(5, 2);
        let complex = build_complex("conforming-voronoi", None, &mesh).expect("builds");
        let (a, mass, _) = free_eigenproblem(
            &complex.co_exact_eigenproblem(),
            complex.co_potential_nodes(),
        );
        let DenseMass::Diagonal(m) = &mass else {
            panic!("the Voronoi co-exact mass is diagonal")
        };
        let (values, x) = generalized_eigenpairs(&a, &mass).unwrap();
        let max = values.last().copied().unwrap_or(0.0);
        let ax = &a * &x;
        for (k, lambda) in values.iter().enumerate() {
            let residual: f64 = (0..m.len())
                .map(|i| (ax[(i, k)] - lambda * m[i] * x[(i, k)]).powi(2) / m[i])
                .sum::<f64>()
                .sqrt();
            assert!(
                residual <= 1e-12 * max,
                "pair {k} (λ = {lambda}): residual {residual:e}, λ_max {max}"
            );
        }
    }

    /// A mass of denormal entries (`1e-310`) overflows the scaled pencil: an error that says so,
    /// not a panic (`tvf check` once printed a backtrace).
    #[test]
    fn an_overflowing_pencil_is_an_error() {
        let a = Mat::from_fn(3, 3, |i, j| if i == j { 2.0 } else { -0.5 });
        let tiny = DenseMass::Diagonal(vec![1e-310; 3]);
        let message = generalized_eigenvalues(&a, &tiny).unwrap_err();
        assert!(message.contains("not finite"), "{message}");
        assert!(generalized_eigenpairs(&a, &tiny).is_err());
        let negative = DenseMass::Diagonal(vec![1.0, -1.0, 1.0]);
        let message = generalized_eigenvalues(&a, &negative).unwrap_err();
        assert!(message.contains("entry 1"), "{message}");
        assert_eq!(
            generalized_eigenvalues(&a, &DenseMass::Diagonal(vec![1.0; 3]))
                .unwrap()
                .len(),
            3
        );
    }
}
