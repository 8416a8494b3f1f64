//! The lowest non-zero eigenpairs of one scalar Laplacian `(A, M)` of a Hodge complex (the
//! potential or the co-potential eigenproblem), with its kernel removed by count.

use crate::BasisError;
use faer::Mat;
use sprs::CsMat;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::discretization::{Eigenproblem, NodeSpace};
use tvf_solvers::{keep_columns, Eigenpairs, Pencil};

/// The eigenproblem `A x = λ M x` of one function space, restricted to its free nodes (unused
/// nodes have zero mass and are decoupled, the solver needs a positive mass; Dirichlet nodes of a
/// boundary condition carry no degree of freedom, their row and column of `A` are zero).
pub(crate) struct ScalarSpectrum {
    /// Which problem, for messages: "potential" or "co-potential".
    pub name: &'static str,
    stiffness: CsMat<f64>,
    mass: Vec<f64>,
    /// Map restricted index → full index, `None` if every node is used.
    used: Option<Vec<usize>>,
    full_dimension: usize,
    /// Kernel dimension: one constant per connected component whose constants are in the kernel.
    components: usize,
}

/// Eigenpairs kept by [`ScalarSpectrum::nonzero`].
pub(crate) struct ScalarEigenpairs {
    /// Non-zero eigenvalues, ascending.
    pub values: Vec<f64>,
    /// `n × k` eigenvectors in the full node numbering (zero on unused nodes), `M`-orthonormal.
    pub vectors: Mat<f64>,
    /// The dropped kernel eigenvalues (one per component with constants in the kernel), for the
    /// report.
    pub kernel_values: Vec<f64>,
    /// Largest relative residual reported by the solver.
    pub max_residual: f64,
    /// Largest relative eigenfield residual reported by the solver (after its refinement).
    pub max_field_residual: f64,
    /// Largest rounding floor of those residuals.
    pub max_field_residual_floor: f64,
}

/// Whether each node of `nodes` is free ([`NodeSpace::is_free`]).
pub(crate) fn free_nodes(nodes: &NodeSpace) -> Vec<bool> {
    (0..nodes.len()).map(|i| nodes.is_free(i)).collect()
}

impl ScalarSpectrum {
    /// The problem restricted to the nodes `i` with `free[i]` (`n` entries), whose stiffness has
    /// a kernel of dimension `kernel_dimension` there.
    pub fn new(
        name: &'static str,
        problem: Eigenproblem,
        free: &[bool],
        kernel_dimension: usize,
    ) -> Self {
        let components = kernel_dimension;
        let full_dimension = problem.mass.len();
        if free.iter().all(|&f| f) {
            return Self {
                name,
                stiffness: problem.stiffness,
                mass: problem.mass,
                used: None,
                full_dimension,
                components,
            };
        }
        let used: Vec<usize> = (0..full_dimension).filter(|&i| free[i]).collect();
        let mut restricted = vec![usize::MAX; full_dimension];
        for (r, &i) in used.iter().enumerate() {
            restricted[i] = r;
        }
        let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
        for (&value, (i, j)) in problem.stiffness.iter() {
            if restricted[i] != usize::MAX && restricted[j] != usize::MAX {
                rows.push(restricted[i]);
                cols.push(restricted[j]);
                values.push(value);
            }
        }
        let n = used.len();
        Self {
            name,
            stiffness: from_triplets(n, n, rows, cols, values),
            mass: used.iter().map(|&i| problem.mass[i]).collect(),
            used: Some(used),
            full_dimension,
            components,
        }
    }

    /// Number of non-zero eigenvalues the problem has: free nodes minus the kernel dimension.
    pub fn available(&self) -> usize {
        self.mass.len().saturating_sub(self.components)
    }

    /// Dimension `n` of `A` and `M` (the used nodes).
    pub fn dimension(&self) -> usize {
        self.mass.len()
    }

    /// Dimension of the kernel of `A` on the free nodes.
    pub fn components(&self) -> usize {
        self.components
    }

    /// The pencil `(A, M)` for the eigensolver and inertia counts.
    ///
    /// Errors: [`BasisError::Eigen`] if the matrices are not a valid pencil.
    pub fn pencil(&self) -> Result<Pencil<'_>, BasisError> {
        Pencil::new(&self.stiffness, &self.mass).map_err(|source| BasisError::Eigen {
            problem: self.name,
            source,
        })
    }

    /// An upper bound of every eigenvalue of `(A, M)` (units of `λ`, 1/length²): Gershgorin's
    /// bound `max_i Σ_j |A_ij| / M_ii` on `M⁻¹A`, which has the same eigenvalues.
    pub fn eigenvalue_upper_bound(&self) -> f64 {
        let mut row_sums = vec![0.0; self.mass.len()];
        for (&value, (i, _)) in self.stiffness.iter() {
            row_sums[i] += value.abs();
        }
        row_sums
            .iter()
            .zip(&self.mass)
            .fold(0.0, |bound: f64, (sum, mass)| bound.max(sum / mass))
    }

    /// The lowest `count` non-zero eigenpairs from the solver's lowest `count + components()`
    /// eigenpairs `pairs` of [`ScalarSpectrum::pencil`]. The `components` lowest are the kernel
    /// (constants per component) and are dropped by count; they are checked to be small against
    /// the first kept eigenvalue.
    ///
    /// Errors: [`BasisError::KernelMismatch`].
    pub fn nonzero(&self, pairs: Eigenpairs, count: usize) -> Result<ScalarEigenpairs, BasisError> {
        let max_residual = pairs.residuals.iter().fold(0.0, |m: f64, &r| m.max(r));
        let max_field_residual = pairs
            .field_residuals
            .iter()
            .fold(0.0, |m: f64, &r| m.max(r));
        let max_field_residual_floor = pairs
            .field_residual_floors
            .iter()
            .fold(0.0, |m: f64, &r| m.max(r));
        let (all_values, all_vectors) = (pairs.values, pairs.vectors);
        let count = count.min(all_values.len().saturating_sub(self.components));
        let kernel_values = all_values[..self.components].to_vec();
        let values = all_values[self.components..].to_vec();
        if let Some(&first_nonzero) = values.first() {
            // Kernel eigenvalues are round-off (~1e-15 relative); a genuine eigenvalue is not.
            if let Some(&value) = kernel_values
                .iter()
                .find(|v| v.abs() > 1e-6 * first_nonzero)
            {
                return Err(BasisError::KernelMismatch {
                    problem: self.name,
                    components: self.components,
                    value,
                    first_nonzero,
                });
            }
        }
        let n = self.full_dimension;
        let vectors = match &self.used {
            None => keep_columns(all_vectors, self.components, count),
            Some(used) => {
                let mut full = Mat::zeros(n, count);
                for j in 0..count {
                    for (r, &i) in used.iter().enumerate() {
                        full[(i, j)] = all_vectors[(r, self.components + j)];
                    }
                }
                full
            }
        };
        Ok(ScalarEigenpairs {
            values,
            vectors,
            kernel_values,
            max_residual,
            max_field_residual,
            max_field_residual_floor,
        })
    }
}
