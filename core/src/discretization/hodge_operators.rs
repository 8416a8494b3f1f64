//! The [`HodgeOperators`] extension: every operator of the seam (`docs/conventions.md`), derived
//! once from the five matrices of a [`HodgeComplex`] and cached.

use super::linear_operator::{has_sparse_inverse, Factor, LinearOperator};
use super::sparse::{mul_vec, product, scale_cols, scale_rows, transpose};
use super::{DiscretizationError, FieldSampling, HodgeComplex, Mass, PointEvaluation};
use sprs::CsMat;

/// A generalized symmetric eigenproblem `A x = λ M x` of one scalar space.
#[derive(Debug, Clone)]
pub struct Eigenproblem {
    /// The stiffness `A` (symmetric positive semi-definite).
    pub stiffness: EigenStiffness,
    /// The mass `M` (symmetric positive definite on the free nodes).
    pub mass: Mass,
}

/// The stiffness of an [`Eigenproblem`]: a sparse matrix, or the co-exact stiffness
/// `d1 M1⁻¹ d1ᵀ` of a complex whose `M1` is not diagonal, which is dense and is kept as its two
/// sparse ingredients (eigensolvers shift-invert it through the saddle matrix
/// `[[−M1, d1ᵀ], [d1, −σ M2⁻¹]]`).
#[derive(Debug, Clone)]
pub enum EigenStiffness {
    /// `A` (`n × n`, sparse, symmetric).
    Sparse(CsMat<f64>),
    /// `A = d1 W⁻¹ d1ᵀ` with `W` the field mass `M1` (`n1 × n1`, sparse) and `d1` (`n × n1`).
    Mixed {
        /// `W = M1`.
        field_mass: Mass,
        /// `d1` (`n2 × n1`).
        d1: CsMat<f64>,
    },
}

impl EigenStiffness {
    /// Dimension `n` of the problem.
    pub fn dimension(&self) -> usize {
        match self {
            EigenStiffness::Sparse(a) => a.rows(),
            EigenStiffness::Mixed { d1, .. } => d1.rows(),
        }
    }

    /// The sparse matrix `A`, unless it is kept in mixed form.
    pub fn as_sparse(&self) -> Option<&CsMat<f64>> {
        match self {
            EigenStiffness::Sparse(a) => Some(a),
            EigenStiffness::Mixed { .. } => None,
        }
    }

    /// `A x`.
    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        match self {
            EigenStiffness::Sparse(a) => mul_vec(a, x),
            EigenStiffness::Mixed { field_mass, d1 } => {
                let t = super::sparse::mul_transpose_vec(d1, x);
                mul_vec(d1, &field_mass.solve(&t))
            }
        }
    }
}

/// Operators derived from any [`HodgeComplex`] (blanket-implemented; nothing to write). Every
/// operator is computed from `d0`, `d1`, `M0`, `M1`, `M2` (and, for the other family, the
/// rotation capability) on first use and cached in the complex's [`super::OperatorCache`].
///
/// Operators are [`LinearOperator`]s: sparse matrices where every mass they involve is diagonal
/// (every lumped complex: the matrices are formed exactly as before, entry by entry), and
/// otherwise compositions applied through sparse products and mass solves (an inverse of a
/// consistent or Whitney mass is dense and is never formed). Only the potential stiffness
/// `d0ᵀ M1 d0` is always a sparse matrix.
///
/// Names say where the result lives: `potential_*` operators return functions on the potential
/// nodes (`n0` rows), `co_potential_*` ones on the co-potential nodes (`n2` rows). For the
/// **conforming** complex (`n0 = V`, `n2 = E`):
///
/// | method | paper | matrix |
/// |---|---|---|
/// | [`potential_divergence`](Self::potential_divergence) | `div_h` | `−M0⁻¹ d0ᵀ M1` = `−M⁻¹ Gᵀ M_X` |
/// | [`co_potential_curl`](Self::co_potential_curl) | `curl*_h` | `M2 d1` = `M*⁻¹ G*ᵀ J M_X` |
/// | [`other_divergence`](Self::other_divergence) | `div*_h` | `−M2 d1 M1⁻¹ Jᵀ M1` = `−M*⁻¹ G*ᵀ M_X` |
/// | [`other_curl`](Self::other_curl) | `curl_h` | `M0⁻¹ d0ᵀ J M1` = `M⁻¹ Gᵀ J M_X` |
/// | [`potential_stiffness`](Self::potential_stiffness) | cotan `S_c` | `d0ᵀ M1 d0` |
/// | [`co_potential_stiffness`](Self::co_potential_stiffness) | CR `S*_c` | `d1 M1⁻¹ d1ᵀ` |
///
/// The first two are the complex's own pair (they vanish on harmonic fields); the other two exist
/// where the complex has a [`super::FieldRotation`]. For the nonconforming complex read every
/// row with `(G, M)` and `(G*, M*)` exchanged; for DEC, `potential_divergence` is the DEC
/// divergence `−⋆0⁻¹ d0ᵀ ⋆1` on vertices and `co_potential_curl` the circulation per area
/// `⋆2 d1` on faces.
pub trait HodgeOperators: HodgeComplex {
    /// Number of potential nodes `n0`.
    fn potential_dimension(&self) -> usize {
        self.d0().cols()
    }

    /// Number of field coefficients `n1`.
    fn field_dimension(&self) -> usize {
        self.d0().rows()
    }

    /// Number of co-potential nodes `n2`.
    fn co_potential_dimension(&self) -> usize {
        self.d1().rows()
    }

    /// `d0 f` for a potential `f` (`n0` values in, `n1` out).
    fn gradient_field(&self, potential: &[f64]) -> Vec<f64> {
        mul_vec(self.d0(), potential)
    }

    /// The co-gradient `−M1⁻¹ d1ᵀ` (`n1 × n2`, pointwise): the field of a co-potential;
    /// finite elements: `J G_co`, the rotated gradient.
    fn co_gradient(&self) -> &LinearOperator {
        self.operator_cache()
            .co_gradient
            .get_or_init(|| match self.m1().inverse_diagonal() {
                Some(inverse) => {
                    let minus_inverse: Vec<f64> = inverse.iter().map(|x| -x).collect();
                    LinearOperator::Sparse(scale_rows(&minus_inverse, &transpose(self.d1())))
                }
                None => LinearOperator::product(
                    -1.0,
                    vec![
                        Factor::MassInverse(self.m1().clone()),
                        Factor::transpose(self.d1()),
                    ],
                ),
            })
    }

    /// `−M1⁻¹ d1ᵀ g` for a co-potential `g` (`n2` values in, `n1` out).
    fn co_gradient_field(&self, co_potential: &[f64]) -> Vec<f64> {
        self.co_gradient().apply(co_potential)
    }

    /// Pointwise divergence on the potential nodes, `−M0⁻¹ d0ᵀ M1` (`n0 × n1`). Its kernel
    /// contains the co-integrable and the harmonic fields.
    fn potential_divergence(&self) -> &LinearOperator {
        self.operator_cache().potential_divergence.get_or_init(|| {
            match (self.m0().inverse_diagonal(), self.m1().diagonal_values()) {
                (Some(inverse), Some(m1)) => {
                    let minus_inverse: Vec<f64> = inverse.iter().map(|x| -x).collect();
                    LinearOperator::Sparse(scale_cols(
                        &scale_rows(&minus_inverse, &transpose(self.d0())),
                        m1,
                    ))
                }
                _ => LinearOperator::product(
                    -1.0,
                    vec![
                        Factor::MassInverse(self.m0().clone()),
                        Factor::transpose(self.d0()),
                        Factor::Mass(self.m1().clone()),
                    ],
                ),
            }
        })
    }

    /// Pointwise curl on the co-potential nodes, `M2 d1` (`n2 × n1`). Its kernel contains the
    /// integrable and the harmonic fields.
    fn co_potential_curl(&self) -> &LinearOperator {
        self.operator_cache()
            .co_potential_curl
            .get_or_init(|| match self.m2().diagonal_values() {
                Some(m2) => LinearOperator::Sparse(scale_rows(m2, self.d1())),
                None => LinearOperator::product(
                    1.0,
                    vec![Factor::Mass(self.m2().clone()), Factor::matrix(self.d1())],
                ),
            })
    }

    /// The other family's pointwise divergence, on the co-potential nodes:
    /// `−M2 d1 M1⁻¹ Jᵀ M1` (`n2 × n1`); conforming `div*_h`. `None` without a rotation.
    fn other_divergence(&self) -> Option<&LinearOperator> {
        let rotation = self.rotation()?.rotation();
        Some(self.operator_cache().other_divergence.get_or_init(|| {
            let (m1, m2) = (self.m1(), self.m2());
            match (
                m2.diagonal_values(),
                m1.diagonal_values(),
                m1.inverse_diagonal(),
            ) {
                (Some(m2), Some(m1), Some(m1_inverse)) => {
                    let minus: Vec<f64> = m2.iter().map(|x| -x).collect();
                    let jt_m1 = scale_cols(&transpose(rotation), m1);
                    let inner = scale_rows(&m1_inverse, &jt_m1);
                    LinearOperator::Sparse(product(&scale_rows(&minus, self.d1()), &inner))
                }
                _ => LinearOperator::product(
                    -1.0,
                    vec![
                        Factor::Mass(m2.clone()),
                        Factor::matrix(self.d1()),
                        Factor::MassInverse(m1.clone()),
                        Factor::transpose(rotation),
                        Factor::Mass(m1.clone()),
                    ],
                ),
            }
        }))
    }

    /// The other family's pointwise curl, on the potential nodes: `M0⁻¹ d0ᵀ J M1` (`n0 × n1`);
    /// conforming `curl_h`. `None` without a rotation.
    fn other_curl(&self) -> Option<&LinearOperator> {
        let rotation = self.rotation()?.rotation();
        Some(self.operator_cache().other_curl.get_or_init(|| {
            match (self.m0().inverse_diagonal(), self.m1().diagonal_values()) {
                (Some(m0_inverse), Some(m1)) => {
                    let jm = scale_cols(rotation, m1);
                    LinearOperator::Sparse(scale_rows(
                        &m0_inverse,
                        &product(&transpose(self.d0()), &jm),
                    ))
                }
                _ => LinearOperator::product(
                    1.0,
                    vec![
                        Factor::MassInverse(self.m0().clone()),
                        Factor::transpose(self.d0()),
                        Factor::matrix(rotation),
                        Factor::Mass(self.m1().clone()),
                    ],
                ),
            }
        }))
    }

    /// Stiffness of the potential space, `d0ᵀ M1 d0` (`n0 × n0`, integrated, symmetric PSD,
    /// exactly symmetric in floating point); conforming: the cotan matrix. Always sparse.
    fn potential_stiffness(&self) -> &CsMat<f64> {
        self.operator_cache().potential_stiffness.get_or_init(|| {
            match self.m1().diagonal_values() {
                Some(m1) => gram(self.d0(), m1),
                None => {
                    let m1 = self
                        .m1()
                        .sparse_matrix()
                        .expect("a field mass is stored directly");
                    symmetrized(&product(&transpose(self.d0()), &product(&m1, self.d0())))
                }
            }
        })
    }

    /// Stiffness of the co-potential space, `d1 M1⁻¹ d1ᵀ` (`n2 × n2`, integrated, symmetric PSD,
    /// exactly symmetric where it is a sparse matrix); conforming: the Crouzeix–Raviart stiffness.
    fn co_potential_stiffness(&self) -> &LinearOperator {
        self.operator_cache()
            .co_potential_stiffness
            .get_or_init(|| match self.m1().inverse_diagonal() {
                Some(inverse) => LinearOperator::Sparse(gram(&transpose(self.d1()), &inverse)),
                None => LinearOperator::product(
                    1.0,
                    vec![
                        Factor::matrix(self.d1()),
                        Factor::MassInverse(self.m1().clone()),
                        Factor::transpose(self.d1()),
                    ],
                ),
            })
    }

    /// Dirichlet energy of fields, `S = M1 d0 M0⁻¹ d0ᵀ M1 + d1ᵀ M2 d1` (`n1 × n1`, integrated,
    /// symmetric PSD; `xᵀ S x = ∫ (div x)² + (curl x)²`).
    fn dirichlet_energy(&self) -> &LinearOperator {
        self.operator_cache().dirichlet_energy.get_or_init(|| {
            let (m0, m1, m2) = (self.m0(), self.m1(), self.m2());
            match (
                m0.inverse_diagonal(),
                m1.diagonal_values(),
                m2.diagonal_values(),
            ) {
                (Some(m0_inverse), Some(m1), Some(m2)) => {
                    let w = scale_cols(&scale_rows(m1, self.d0()), &sqrt_all(&m0_inverse));
                    let u = scale_rows(&sqrt_all(m2), self.d1());
                    let exact = product(&w, &transpose(&w));
                    let co_exact = product(&transpose(&u), &u);
                    LinearOperator::Sparse(&exact + &co_exact)
                }
                _ => LinearOperator::sum(vec![
                    (
                        1.0,
                        vec![
                            Factor::Mass(m1.clone()),
                            Factor::matrix(self.d0()),
                            Factor::MassInverse(m0.clone()),
                            Factor::transpose(self.d0()),
                            Factor::Mass(m1.clone()),
                        ],
                    ),
                    (
                        1.0,
                        vec![
                            Factor::transpose(self.d1()),
                            Factor::Mass(m2.clone()),
                            Factor::matrix(self.d1()),
                        ],
                    ),
                ]),
            }
        })
    }

    /// Hodge–Laplacian `L = M1⁻¹ S` (`n1 × n1`, pointwise; self-adjoint w.r.t. `M1`, eigenvalues
    /// ≥ 0, kernel = harmonic fields).
    fn hodge_laplacian(&self) -> &LinearOperator {
        self.operator_cache().hodge_laplacian.get_or_init(|| {
            let energy = self.dirichlet_energy();
            match (self.m1().inverse_diagonal(), energy.as_sparse()) {
                (Some(inverse), Some(s)) => LinearOperator::Sparse(scale_rows(&inverse, s)),
                _ => LinearOperator::product(
                    1.0,
                    vec![
                        Factor::MassInverse(self.m1().clone()),
                        Factor::Operator(std::sync::Arc::new(energy.clone())),
                    ],
                ),
            }
        })
    }

    /// Biharmonic energy `B = S M1⁻¹ S = Lᵀ M1 L` (`n1 × n1`, integrated, symmetric PSD).
    fn biharmonic_energy(&self) -> &LinearOperator {
        self.operator_cache().biharmonic_energy.get_or_init(|| {
            let energy = self.dirichlet_energy();
            match (self.m1().inverse_diagonal(), energy.as_sparse()) {
                (Some(inverse), Some(s)) => {
                    let t = scale_cols(s, &sqrt_all(&inverse));
                    LinearOperator::Sparse(product(&t, &transpose(&t)))
                }
                _ => {
                    let energy = std::sync::Arc::new(energy.clone());
                    LinearOperator::product(
                        1.0,
                        vec![
                            Factor::Operator(energy.clone()),
                            Factor::MassInverse(self.m1().clone()),
                            Factor::Operator(energy),
                        ],
                    )
                }
            }
        })
    }

    /// The exact eigenproblem `(d0ᵀ M1 d0, M0)`: its eigenfunctions `φ` (eigenvalue `λ > 0`) give
    /// the integrable eigenfields `d0 φ / √λ` of `L` with the same eigenvalue.
    fn exact_eigenproblem(&self) -> Eigenproblem {
        Eigenproblem {
            stiffness: EigenStiffness::Sparse(self.potential_stiffness().clone()),
            mass: self.m0().clone(),
        }
    }

    /// The co-exact eigenproblem `(d1 M1⁻¹ d1ᵀ, M2⁻¹)`: its eigenfunctions `ψ` (eigenvalue
    /// `μ > 0`) give the co-integrable eigenfields `−M1⁻¹ d1ᵀ ψ / √μ` of `L` with the same
    /// eigenvalue. With a non-diagonal `M1` the stiffness is kept in mixed form.
    fn co_exact_eigenproblem(&self) -> Eigenproblem {
        let stiffness = match self.co_potential_stiffness().as_sparse() {
            Some(a) => EigenStiffness::Sparse(a.clone()),
            None => EigenStiffness::Mixed {
                field_mass: self.m1().clone(),
                d1: self.d1().clone(),
            },
        };
        Eigenproblem {
            stiffness,
            mass: self.m2().inverse(),
        }
    }

    /// The `M1` inner product `xᵀ M1 y` of two fields (integrated).
    fn field_inner(&self, x: &[f64], y: &[f64]) -> f64 {
        self.m1().inner(x, y)
    }

    /// The sampling capability, or [`DiscretizationError::MissingCapability`] naming the complex.
    fn require_sampling(&self) -> Result<&dyn FieldSampling, DiscretizationError> {
        self.sampling()
            .ok_or_else(|| missing(self.id(), "sampling fields as 3D vectors"))
    }

    /// The point-evaluation capability, or [`DiscretizationError::MissingCapability`].
    fn require_point_evaluation(&self) -> Result<&dyn PointEvaluation, DiscretizationError> {
        self.point_evaluation()
            .ok_or_else(|| missing(self.id(), "evaluating potentials at points"))
    }

    /// Total area of the mesh, `1ᵀ M0 1` (the potential masses partition the area).
    fn total_area(&self) -> f64 {
        self.m0().total()
    }
}

impl<T: HodgeComplex + ?Sized> HodgeOperators for T {}

fn missing(id: &str, capability: &'static str) -> DiscretizationError {
    DiscretizationError::MissingCapability {
        discretization: id.to_string(),
        capability,
    }
}

/// `aᵀ diag(w) a`, exactly symmetric: `(√w a)ᵀ (√w a)`.
fn gram(a: &CsMat<f64>, w: &[f64]) -> CsMat<f64> {
    let b = scale_rows(&sqrt_all(w), a);
    product(&transpose(&b), &b)
}

/// `(A + Aᵀ)/2`: exactly symmetric.
fn symmetrized(a: &CsMat<f64>) -> CsMat<f64> {
    (a + &transpose(a)).map(|x| 0.5 * x)
}

fn sqrt_all(d: &[f64]) -> Vec<f64> {
    d.iter().map(|x| x.max(0.0).sqrt()).collect()
}

/// Whether every operator of a complex with these masses is a sparse matrix.
pub fn all_sparse(m0: &Mass, m1: &Mass, m2: &Mass) -> bool {
    has_sparse_inverse(m0) && m1.is_diagonal() && m2.sparse_matrix().is_some()
}
