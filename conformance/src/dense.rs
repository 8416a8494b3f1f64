//! Dense eigenvalues and eigenvectors (faer) for the checks on small meshes.

use faer::{Mat, Side};
use sprs::CsMat;

/// `D^{-1/2} A D^{-1/2}` as a dense symmetric matrix (`D = diag(mass)`, `mass > 0`).
fn scaled_dense(a: &CsMat<f64>, mass: &[f64]) -> Mat<f64> {
    let n = a.rows();
    assert_eq!(mass.len(), n, "one mass per row");
    assert!(
        mass.iter().all(|&m| m > 0.0),
        "dense eigenproblems need a positive mass"
    );
    let scale: Vec<f64> = mass.iter().map(|m| 1.0 / m.sqrt()).collect();
    let mut dense = Mat::<f64>::zeros(n, n);
    for (value, (i, j)) in a.iter() {
        dense[(i, j)] += value * scale[i] * scale[j];
    }
    dense
}

/// Eigenvalues (ascending) of the generalized problem `A x = λ diag(mass) x`, computed densely as
/// the eigenvalues of `D^{-1/2} A D^{-1/2}` (symmetric). `A` must be symmetric, `mass > 0`.
pub fn generalized_eigenvalues(a: &CsMat<f64>, mass: &[f64]) -> Vec<f64> {
    scaled_dense(a, mass)
        .self_adjoint_eigenvalues(Side::Lower)
        .expect("dense symmetric eigenvalues converge")
}

/// All eigenpairs of `A x = λ diag(mass) x`, ascending: `(λ, X)` with the columns of `X`
/// (`n × n`) `diag(mass)`-orthonormal.
pub fn generalized_eigenpairs(a: &CsMat<f64>, mass: &[f64]) -> (Vec<f64>, Mat<f64>) {
    let eigen = scaled_dense(a, mass)
        .self_adjoint_eigen(Side::Lower)
        .expect("dense symmetric eigendecomposition converges");
    let values = eigen.S().column_vector().iter().copied().collect();
    let u = eigen.U();
    let vectors = Mat::from_fn(u.nrows(), u.ncols(), |i, j| u[(i, j)] / mass[i].sqrt());
    (values, vectors)
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

/// The eigenproblem `(a, diag(mass))` restricted to the free nodes of `nodes`
/// ([`tvf_core::discretization::NodeSpace::is_free`]): the restricted stiffness and mass, and
/// the full index of every restricted node.
pub fn restrict_to_free(
    a: &CsMat<f64>,
    mass: &[f64],
    nodes: &tvf_core::discretization::NodeSpace,
) -> (CsMat<f64>, Vec<f64>, Vec<usize>) {
    let free: Vec<usize> = (0..nodes.len()).filter(|&i| nodes.is_free(i)).collect();
    let mut restricted = vec![usize::MAX; nodes.len()];
    for (r, &i) in free.iter().enumerate() {
        restricted[i] = r;
    }
    let mut triplets = sprs::TriMat::new((free.len(), free.len()));
    for (&value, (i, j)) in a.iter() {
        if restricted[i] != usize::MAX && restricted[j] != usize::MAX {
            triplets.add_triplet(restricted[i], restricted[j], value);
        }
    }
    let mass = free.iter().map(|&i| mass[i]).collect();
    (triplets.to_csr(), mass, free)
}
