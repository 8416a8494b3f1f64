//! The [`HodgeOperators`] extension: every operator of `shared/docs/MATH.md`, derived once from
//! the five matrices of a [`HodgeComplex`] and cached.

use super::sparse::{diagonal, mul_vec, product, scale_cols, scale_rows, transpose};
use super::{DiscretizationError, FieldSampling, HodgeComplex, PointEvaluation};
use sprs::CsMat;

/// A generalized symmetric eigenproblem `A x = λ diag(mass) x`.
#[derive(Debug, Clone)]
pub struct Eigenproblem {
    /// The stiffness `A` (symmetric positive semi-definite, sparse).
    pub stiffness: CsMat<f64>,
    /// The diagonal of the mass matrix (integrated weights, positive except for unused nodes).
    pub mass: Vec<f64>,
}

/// Operators derived from any [`HodgeComplex`] (blanket-implemented; nothing to write). Every
/// matrix is computed from `d0`, `d1`, `M0`, `M1`, `M2` (and, for the other family, the
/// rotation capability) on first use and cached in the complex's
/// [`super::OperatorCache`].
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
    fn co_gradient(&self) -> &CsMat<f64> {
        self.operator_cache().co_gradient.get_or_init(|| {
            let minus_inverse: Vec<f64> = self.m1().inverse().iter().map(|x| -x).collect();
            scale_rows(&minus_inverse, &transpose(self.d1()))
        })
    }

    /// `−M1⁻¹ d1ᵀ g` for a co-potential `g` (`n2` values in, `n1` out).
    fn co_gradient_field(&self, co_potential: &[f64]) -> Vec<f64> {
        mul_vec(self.co_gradient(), co_potential)
    }

    /// Pointwise divergence on the potential nodes, `−M0⁻¹ d0ᵀ M1` (`n0 × n1`). Its kernel
    /// contains the co-integrable and the harmonic fields.
    fn potential_divergence(&self) -> &CsMat<f64> {
        self.operator_cache().potential_divergence.get_or_init(|| {
            let minus_inverse: Vec<f64> = self.m0().inverse().iter().map(|x| -x).collect();
            scale_cols(
                &scale_rows(&minus_inverse, &transpose(self.d0())),
                self.m1().values(),
            )
        })
    }

    /// Pointwise curl on the co-potential nodes, `M2 d1` (`n2 × n1`). Its kernel contains the
    /// integrable and the harmonic fields.
    fn co_potential_curl(&self) -> &CsMat<f64> {
        self.operator_cache()
            .co_potential_curl
            .get_or_init(|| scale_rows(self.m2().values(), self.d1()))
    }

    /// The other family's pointwise divergence, on the co-potential nodes:
    /// `−M2 d1 M1⁻¹ Jᵀ M1` (`n2 × n1`); conforming `div*_h`. `None` without a rotation.
    fn other_divergence(&self) -> Option<&CsMat<f64>> {
        let rotation = self.rotation()?.rotation();
        Some(self.operator_cache().other_divergence.get_or_init(|| {
            let minus: Vec<f64> = self.m2().values().iter().map(|x| -x).collect();
            let jt_m1 = scale_cols(&transpose(rotation), self.m1().values());
            let inner = scale_rows(&self.m1().inverse(), &jt_m1);
            product(&scale_rows(&minus, self.d1()), &inner)
        }))
    }

    /// The other family's pointwise curl, on the potential nodes: `M0⁻¹ d0ᵀ J M1` (`n0 × n1`);
    /// conforming `curl_h`. `None` without a rotation.
    fn other_curl(&self) -> Option<&CsMat<f64>> {
        let rotation = self.rotation()?.rotation();
        Some(self.operator_cache().other_curl.get_or_init(|| {
            let jm = scale_cols(rotation, self.m1().values());
            scale_rows(&self.m0().inverse(), &product(&transpose(self.d0()), &jm))
        }))
    }

    /// Stiffness of the potential space, `d0ᵀ M1 d0` (`n0 × n0`, integrated, symmetric PSD,
    /// exactly symmetric in floating point); conforming: the cotan matrix.
    fn potential_stiffness(&self) -> &CsMat<f64> {
        self.operator_cache()
            .potential_stiffness
            .get_or_init(|| gram(self.d0(), self.m1().values()))
    }

    /// Stiffness of the co-potential space, `d1 M1⁻¹ d1ᵀ` (`n2 × n2`, integrated, symmetric PSD,
    /// exactly symmetric); conforming: the Crouzeix–Raviart stiffness.
    fn co_potential_stiffness(&self) -> &CsMat<f64> {
        self.operator_cache()
            .co_potential_stiffness
            .get_or_init(|| gram(&transpose(self.d1()), &self.m1().inverse()))
    }

    /// Dirichlet energy of fields, `S = M1 d0 M0⁻¹ d0ᵀ M1 + d1ᵀ M2 d1` (`n1 × n1`, integrated,
    /// symmetric PSD; `xᵀ S x = ∫ (div x)² + (curl x)²`).
    fn dirichlet_energy(&self) -> &CsMat<f64> {
        self.operator_cache().dirichlet_energy.get_or_init(|| {
            let w = scale_cols(
                &scale_rows(self.m1().values(), self.d0()),
                &sqrt_all(&self.m0().inverse()),
            );
            let u = scale_rows(&sqrt_all(self.m2().values()), self.d1());
            let exact = product(&w, &transpose(&w));
            let co_exact = product(&transpose(&u), &u);
            &exact + &co_exact
        })
    }

    /// Hodge–Laplacian `L = M1⁻¹ S` (`n1 × n1`, pointwise; self-adjoint w.r.t. `M1`, eigenvalues
    /// ≥ 0, kernel = harmonic fields).
    fn hodge_laplacian(&self) -> &CsMat<f64> {
        self.operator_cache()
            .hodge_laplacian
            .get_or_init(|| scale_rows(&self.m1().inverse(), self.dirichlet_energy()))
    }

    /// Biharmonic energy `B = S M1⁻¹ S = Lᵀ M1 L` (`n1 × n1`, integrated, symmetric PSD).
    fn biharmonic_energy(&self) -> &CsMat<f64> {
        self.operator_cache().biharmonic_energy.get_or_init(|| {
            let t = scale_cols(self.dirichlet_energy(), &sqrt_all(&self.m1().inverse()));
            product(&t, &transpose(&t))
        })
    }

    /// The exact eigenproblem `(d0ᵀ M1 d0, M0)`: its eigenfunctions `φ` (eigenvalue `λ > 0`) give
    /// the integrable eigenfields `d0 φ / √λ` of `L` with the same eigenvalue.
    fn exact_eigenproblem(&self) -> Eigenproblem {
        Eigenproblem {
            stiffness: self.potential_stiffness().clone(),
            mass: self.m0().values().to_vec(),
        }
    }

    /// The co-exact eigenproblem `(d1 M1⁻¹ d1ᵀ, M2⁻¹)`: its eigenfunctions `ψ` (eigenvalue
    /// `μ > 0`) give the co-integrable eigenfields `−M1⁻¹ d1ᵀ ψ / √μ` of `L` with the same
    /// eigenvalue.
    fn co_exact_eigenproblem(&self) -> Eigenproblem {
        Eigenproblem {
            stiffness: self.co_potential_stiffness().clone(),
            mass: self.m2().inverse(),
        }
    }

    /// `M1` as a sparse diagonal matrix (`n1 × n1`), for code that wants a matrix.
    fn field_mass_matrix(&self) -> CsMat<f64> {
        diagonal(self.m1().values())
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

    /// Total area of the mesh, `Σ M0` (the potential masses partition the area).
    fn total_area(&self) -> f64 {
        self.m0().values().iter().sum()
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

fn sqrt_all(d: &[f64]) -> Vec<f64> {
    d.iter().map(|x| x.max(0.0).sqrt()).collect()
}
