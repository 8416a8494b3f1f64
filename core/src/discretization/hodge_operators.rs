//! The [`HodgeOperators`] extension: every operator of `shared/docs/MATH.md`, derived once from a
//! [`HodgeComplex`].

use super::sparse::{diagonal, mul_vec, product, reciprocal, scale_cols, scale_rows, transpose};
use super::{FieldSpace, FunctionSpace, HodgeComplex};
use sprs::CsMat;

/// A generalized symmetric eigenproblem `A x = λ diag(mass) x`.
#[derive(Debug, Clone)]
pub struct Eigenproblem {
    /// The stiffness `A` (symmetric positive semi-definite, sparse).
    pub stiffness: CsMat<f64>,
    /// The diagonal of the mass matrix (integrated weights, positive except for unused nodes).
    pub mass: Vec<f64>,
}

/// Operators derived from any [`HodgeComplex`] (blanket-implemented; nothing to write).
///
/// Names say where the result lives: `potential_*` operators return functions in the potential
/// space (`n0` rows), `co_potential_*` ones in the co-potential space (`n2` rows). For the
/// **conforming** complex (`n0 = V`, `n2 = E`):
///
/// | method | paper | matrix |
/// |---|---|---|
/// | [`potential_divergence`](Self::potential_divergence) | `div_h` | `−M⁻¹ Gᵀ M_X` |
/// | [`co_potential_curl`](Self::co_potential_curl) | `curl*_h` | `M*⁻¹ G*ᵀ J M_X` |
/// | [`co_potential_divergence`](Self::co_potential_divergence) | `div*_h` | `−M*⁻¹ G*ᵀ M_X` |
/// | [`potential_curl`](Self::potential_curl) | `curl_h` | `M⁻¹ Gᵀ J M_X` |
/// | [`potential_stiffness`](Self::potential_stiffness) | cotan `S_c` | `Gᵀ M_X G` |
/// | [`co_potential_stiffness`](Self::co_potential_stiffness) | CR `S*_c` | `G*ᵀ M_X G*` |
///
/// The first two are the complex's own pair (they vanish on harmonic fields); the other two are
/// "the other family", available on request. For the nonconforming complex read every row with
/// `(G, M)` and `(G*, M*)` exchanged. All sparse matrices are CSR and are computed on each call.
pub trait HodgeOperators: HodgeComplex {
    /// The gradient `d0` as a map from potentials to fields (`2F × n0`, pointwise).
    fn gradient(&self) -> CsMat<f64> {
        self.d0().clone()
    }

    /// The co-gradient `J G_co` (`2F × n2`, pointwise): the field `J grad g` of a co-potential
    /// `g`; equals `−M1⁻¹ d1ᵀ`.
    fn co_gradient(&self) -> CsMat<f64> {
        product(self.fields().rotation(), self.co_potentials().gradient())
    }

    /// `d0 f` for a potential `f` (`n0` values in, `2F` out).
    fn gradient_field(&self, potential: &[f64]) -> Vec<f64> {
        mul_vec(self.d0(), potential)
    }

    /// `J G_co g` for a co-potential `g` (`n2` values in, `2F` out).
    fn co_gradient_field(&self, co_potential: &[f64]) -> Vec<f64> {
        self.fields()
            .rotate(&mul_vec(self.co_potentials().gradient(), co_potential))
    }

    /// Pointwise divergence into the potential space, `−M0⁻¹ d0ᵀ M1` (`n0 × 2F`); conforming:
    /// `div_h`. Its kernel contains the co-integrable and the harmonic fields.
    fn potential_divergence(&self) -> CsMat<f64> {
        let dt = transpose(self.d0());
        let minus_inv: Vec<f64> = reciprocal(self.m0()).iter().map(|x| -x).collect();
        scale_cols(&scale_rows(&minus_inv, &dt), self.m1())
    }

    /// Pointwise curl into the co-potential space, `M2 d1` (`n2 × 2F`); conforming: `curl*_h`.
    /// Its kernel contains the integrable and the harmonic fields.
    fn co_potential_curl(&self) -> CsMat<f64> {
        scale_rows(self.m2(), self.d1())
    }

    /// Pointwise divergence into the co-potential space, `−M2 G_coᵀ M1` (`n2 × 2F`);
    /// conforming: `div*_h` (the other family).
    fn co_potential_divergence(&self) -> CsMat<f64> {
        let gt = transpose(self.co_potentials().gradient());
        let minus: Vec<f64> = self.m2().iter().map(|x| -x).collect();
        scale_cols(&scale_rows(&minus, &gt), self.m1())
    }

    /// Pointwise curl into the potential space, `M0⁻¹ d0ᵀ J M1` (`n0 × 2F`); conforming:
    /// `curl_h` (the other family).
    fn potential_curl(&self) -> CsMat<f64> {
        let dt = transpose(self.d0());
        let jm = scale_cols(self.fields().rotation(), self.m1());
        scale_rows(&reciprocal(self.m0()), &product(&dt, &jm))
    }

    /// Stiffness of the potential space, `d0ᵀ M1 d0` (`n0 × n0`, integrated, symmetric PSD,
    /// exactly symmetric in floating point); conforming: the cotan matrix `S_c`.
    fn potential_stiffness(&self) -> CsMat<f64> {
        gram(self.d0(), self.m1())
    }

    /// Stiffness of the co-potential space, `G_coᵀ M1 G_co = d1 M1⁻¹ d1ᵀ` (`n2 × n2`, integrated,
    /// symmetric PSD); conforming: the Crouzeix–Raviart stiffness `S*_c`.
    fn co_potential_stiffness(&self) -> CsMat<f64> {
        gram(self.co_potentials().gradient(), self.m1())
    }

    /// Dirichlet energy of fields, `S = M1 d0 M0⁻¹ d0ᵀ M1 + d1ᵀ M2 d1` (`2F × 2F`, integrated,
    /// symmetric PSD; `vᵀ S v = ∫ (div v)² + (curl v)²`). Conforming:
    /// `M_X (G M⁻¹ Gᵀ − J G* M*⁻¹ G*ᵀ J) M_X`.
    fn dirichlet_energy(&self) -> CsMat<f64> {
        let w = scale_cols(
            &scale_rows(self.m1(), self.d0()),
            &sqrt_all(&reciprocal(self.m0())),
        );
        let u = scale_rows(&sqrt_all(self.m2()), self.d1());
        let exact = product(&w, &transpose(&w));
        let co_exact = product(&transpose(&u), &u);
        &exact + &co_exact
    }

    /// Hodge–Laplacian `L = M1⁻¹ S` (`2F × 2F`, pointwise; self-adjoint w.r.t. `M1`, eigenvalues
    /// ≥ 0, kernel = harmonic fields).
    fn hodge_laplacian(&self) -> CsMat<f64> {
        scale_rows(&reciprocal(self.m1()), &self.dirichlet_energy())
    }

    /// Biharmonic energy `B = S M1⁻¹ S = Lᵀ M1 L` (`2F × 2F`, integrated, symmetric PSD).
    fn biharmonic_energy(&self) -> CsMat<f64> {
        let t = scale_cols(&self.dirichlet_energy(), &sqrt_all(&reciprocal(self.m1())));
        product(&t, &transpose(&t))
    }

    /// The exact eigenproblem `(d0ᵀ M1 d0, M0)`: its eigenfunctions `φ` (eigenvalue `λ > 0`) give
    /// the integrable eigenfields `d0 φ / √λ` of `L` with the same eigenvalue.
    fn exact_eigenproblem(&self) -> Eigenproblem {
        Eigenproblem {
            stiffness: self.potential_stiffness(),
            mass: self.m0().to_vec(),
        }
    }

    /// The co-exact eigenproblem `(d1 M1⁻¹ d1ᵀ, M2⁻¹)` = `(G_coᵀ M1 G_co, co-potential mass)`:
    /// its eigenfunctions `ψ` (eigenvalue `μ > 0`) give the co-integrable eigenfields
    /// `J G_co ψ / √μ` of `L` with the same eigenvalue.
    fn co_exact_eigenproblem(&self) -> Eigenproblem {
        Eigenproblem {
            stiffness: self.co_potential_stiffness(),
            mass: self.co_potentials().mass().to_vec(),
        }
    }

    /// `M1` as a sparse diagonal matrix (`2F × 2F`), for code that wants a matrix.
    fn field_mass_matrix(&self) -> CsMat<f64> {
        diagonal(self.m1())
    }

    /// The `M1` inner product `xᵀ M1 y` of two fields (integrated).
    fn field_inner(&self, x: &[f64], y: &[f64]) -> f64 {
        x.iter()
            .zip(y)
            .zip(self.m1())
            .map(|((a, b), m)| a * b * m)
            .sum()
    }
}

impl<T: HodgeComplex + ?Sized> HodgeOperators for T {}

/// `aᵀ diag(w) a`, exactly symmetric: `(√w a)ᵀ (√w a)`.
fn gram(a: &CsMat<f64>, w: &[f64]) -> CsMat<f64> {
    let b = scale_rows(&sqrt_all(w), a);
    product(&transpose(&b), &b)
}

fn sqrt_all(d: &[f64]) -> Vec<f64> {
    d.iter().map(|x| x.max(0.0).sqrt()).collect()
}
