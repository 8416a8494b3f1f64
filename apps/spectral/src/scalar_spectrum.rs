//! The lowest non-zero eigenpairs of one scalar Laplacian `(A, M)` of a Hodge complex (the
//! potential or the co-potential eigenproblem), with its kernel removed by count.

use crate::BasisError;
use faer::{ColMut, ColRef, Mat, MatRef};
use rayon::prelude::*;
use sprs::CsMat;
use tvf_core::discretization::sparse::{mul_vec, restricted_to};
use tvf_core::discretization::{EigenStiffness, Eigenproblem, NodeSpace};
use tvf_solvers::{keep_columns, Eigenpairs, MassMatrix, Pencil};

/// The eigenproblem `A x = λ M x` of one function space, restricted to its free nodes (unused
/// nodes carry no mass and Dirichlet nodes of a boundary condition no degree of freedom: the
/// solver needs a mass positive definite on its unknowns). `A` is a sparse matrix, or the
/// co-exact stiffness `d1 M1⁻¹ d1ᵀ` in mixed form (restricted to the free field and co-potential
/// nodes); `M` is a diagonal or a sparse matrix.
pub(crate) struct ScalarSpectrum {
    /// Which problem, for messages: "potential" or "co-potential".
    pub name: &'static str,
    stiffness: RestrictedStiffness,
    mass: RestrictedMass,
    /// Map restricted index → full index, `None` if every node is used.
    used: Option<Vec<usize>>,
    full_dimension: usize,
    /// Kernel dimension: one constant per connected component whose constants are in the kernel.
    components: usize,
}

/// The stiffness on the free nodes.
enum RestrictedStiffness {
    Sparse(CsMat<f64>),
    /// `d1 W⁻¹ d1ᵀ`: `W` (the field mass on the free field nodes) and `d1` (free co-potential
    /// rows, free field columns).
    Mixed {
        w: CsMat<f64>,
        d1: CsMat<f64>,
    },
}

/// The mass on the free nodes.
enum RestrictedMass {
    Diagonal(Vec<f64>),
    Sparse(CsMat<f64>),
}

/// Eigenpairs kept by [`ScalarSpectrum::nonzero`].
pub(crate) struct ScalarEigenpairs {
    /// Non-zero eigenvalues, ascending.
    pub values: Vec<f64>,
    /// `n × k` eigenvectors in the full node numbering (zero on unused nodes), `M`-orthonormal;
    /// `n × 0` where they went to the eigensolver's sink as they were computed.
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
    /// a kernel of dimension `kernel_dimension` there. For a mixed stiffness, `free_fields` are
    /// the free field nodes (the unknowns of `W`).
    pub fn new(
        name: &'static str,
        problem: Eigenproblem,
        free: &[bool],
        free_fields: &[bool],
        kernel_dimension: usize,
    ) -> Self {
        let full_dimension = problem.mass.len();
        let everything = free.iter().all(|&f| f);
        let used: Vec<usize> = (0..full_dimension).filter(|&i| free[i]).collect();
        let position = positions(free);
        let n = used.len();
        let stiffness = match problem.stiffness {
            EigenStiffness::Sparse(a) if everything => RestrictedStiffness::Sparse(a),
            EigenStiffness::Sparse(a) => {
                RestrictedStiffness::Sparse(restricted_to(&a, &position, &position, (n, n)))
            }
            EigenStiffness::Mixed { field_mass, d1 } => {
                let field_position = positions(free_fields);
                let n1 = free_fields.iter().filter(|&&f| f).count();
                let w = field_mass
                    .sparse_matrix()
                    .expect("a field mass is stored directly");
                RestrictedStiffness::Mixed {
                    w: restricted_to(&w, &field_position, &field_position, (n1, n1)),
                    d1: restricted_to(&d1, &position, &field_position, (n, n1)),
                }
            }
        };
        let mass = match (problem.mass.diagonal_values(), problem.mass.sparse_matrix()) {
            (Some(values), _) if everything => RestrictedMass::Diagonal(values.to_vec()),
            (Some(values), _) => {
                RestrictedMass::Diagonal(used.iter().map(|&i| values[i]).collect())
            }
            (None, Some(m)) => {
                RestrictedMass::Sparse(restricted_to(&m, &position, &position, (n, n)))
            }
            (None, None) => unreachable!("an eigenproblem's mass is stored directly"),
        };
        Self {
            name,
            stiffness,
            mass,
            used: if everything { None } else { Some(used) },
            full_dimension,
            components: kernel_dimension,
        }
    }

    /// Number of non-zero eigenvalues the problem has: free nodes minus the kernel dimension.
    pub fn available(&self) -> usize {
        self.dimension().saturating_sub(self.components)
    }

    /// Dimension `n` of `A` and `M` (the free nodes).
    pub fn dimension(&self) -> usize {
        match &self.mass {
            RestrictedMass::Diagonal(values) => values.len(),
            RestrictedMass::Sparse(m) => m.rows(),
        }
    }

    /// Dimension of the kernel of `A` on the free nodes.
    pub fn components(&self) -> usize {
        self.components
    }

    /// The pencil `(A, M)` for the eigensolver and inertia counts.
    ///
    /// Errors: [`BasisError::Eigen`] if the matrices are not a valid pencil.
    pub fn pencil(&self) -> Result<Pencil<'_>, BasisError> {
        let mass = match &self.mass {
            RestrictedMass::Diagonal(values) => MassMatrix::Diagonal(values),
            RestrictedMass::Sparse(m) => MassMatrix::Sparse(m),
        };
        match &self.stiffness {
            RestrictedStiffness::Sparse(a) => Pencil::with_mass(a, mass),
            RestrictedStiffness::Mixed { w, d1 } => Pencil::mixed(w, d1, mass),
        }
        .map_err(|source| BasisError::Eigen {
            problem: self.name,
            source,
        })
    }

    /// An upper bound of every eigenvalue of `(A, M)` (units of `λ`, 1/length²). With a diagonal
    /// mass and a sparse stiffness: Gershgorin's bound `max_i Σ_j |A_ij| / M_ii` on `M⁻¹A`,
    /// which has the same eigenvalues; otherwise the pencil's estimate
    /// ([`Pencil::spectrum_upper_bound`]).
    pub fn eigenvalue_upper_bound(&self, pencil: &Pencil<'_>) -> f64 {
        match (&self.stiffness, &self.mass) {
            (RestrictedStiffness::Sparse(a), RestrictedMass::Diagonal(mass)) => {
                let mut row_sums = vec![0.0; mass.len()];
                for (&value, (i, _)) in a.iter() {
                    row_sums[i] += value.abs();
                }
                row_sums
                    .iter()
                    .zip(mass)
                    .fold(0.0, |bound: f64, (sum, mass)| bound.max(sum / mass))
            }
            _ => pencil.spectrum_upper_bound(),
        }
    }

    /// `√(λ_j · x_jᵀ M x_j)` for the eigenpairs `(λ_j, x_j)` of `(A, M)` given as `values` and the
    /// columns of `vectors` (`full_dimension × k` in the full node numbering, zero on the nodes
    /// that are not free, as [`ScalarSpectrum::nonzero`] returns them; `k ≤ values.len()`).
    ///
    /// That is the `A`-norm `√(x_jᵀ A x_j)`: the eigenvalues the solver returns are the Rayleigh
    /// quotients `x_jᵀ A x_j / x_jᵀ M x_j` of its vectors (each interval's Rayleigh–Ritz; the
    /// M-orthogonalisation across interval boundaries changes a vector by the size of its residual
    /// and its Rayleigh quotient only by the square of that). Since `A = Dᵀ M1 D` for the gradient
    /// `D` of either family (`d0`, or the co-gradient `−M1⁻¹ d1ᵀ` with `A = d1 M1⁻¹ d1ᵀ`), it is
    /// the `M1` norm of the eigenfield `D x_j` without forming it: for a non-diagonal `M1` forming
    /// and weighting the fields took a block solve with `M1` per family.
    pub fn energy_norms(&self, values: &[f64], vectors: MatRef<'_, f64>) -> Vec<f64> {
        let restricted = |j: usize| -> Vec<f64> {
            let column = vectors.col(j);
            match &self.used {
                None => column.iter().copied().collect(),
                Some(used) => used.iter().map(|&i| column[i]).collect(),
            }
        };
        (0..vectors.ncols())
            .into_par_iter()
            .map(|j| {
                let x = restricted(j);
                let squared: f64 = match &self.mass {
                    RestrictedMass::Diagonal(mass) => {
                        x.iter().zip(mass).map(|(x, m)| x * x * m).sum()
                    }
                    RestrictedMass::Sparse(m) => {
                        x.iter().zip(mul_vec(m, &x)).map(|(x, y)| x * y).sum()
                    }
                };
                (values[j] * squared).sqrt()
            })
            .collect()
    }

    /// Number of nodes of the space, free or not: the rows of the eigenvectors in the full
    /// numbering.
    pub fn full_dimension(&self) -> usize {
        self.full_dimension
    }

    /// Writes the eigenvector `restricted` (on the free nodes) into `full` (the full numbering,
    /// zero on the other nodes: `full` must be zero there already).
    pub fn to_full(&self, restricted: ColRef<'_, f64>, mut full: ColMut<'_, f64>) {
        match &self.used {
            None => full.copy_from(restricted),
            Some(used) => {
                for (r, &i) in used.iter().enumerate() {
                    full[i] = restricted[r];
                }
            }
        }
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
            // The vectors went to the eigensolver's sink of finished eigenvectors.
            _ if all_vectors.ncols() < all_values.len() => Mat::zeros(n, 0),
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

/// Position of each free node among the free nodes (`usize::MAX` for the others).
fn positions(free: &[bool]) -> Vec<usize> {
    let mut next = 0;
    free.iter()
        .map(|&f| {
            if f {
                next += 1;
                next - 1
            } else {
                usize::MAX
            }
        })
        .collect()
}
