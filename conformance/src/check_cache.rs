//! [`CheckCache`]: what several core checks of one complex compute alike — the dense spectra of
//! `L` and of the two scalar pencils, `S` and `B` formed densely, the eigenfields of Lemma 1, the
//! prefactored Hodge decomposer — computed once, on first use, and read by every check after.
//!
//! The checks themselves are unchanged: each still measures what it measured, on the same
//! numbers. Without the cache the spectrum of `L` (the largest dense problem, `n1` free field
//! nodes) was computed three times per complex (semi-definiteness, the kernel, the spectrum
//! union), each scalar spectrum twice, the eigenfields of Lemma 1 up to four times (Lemma 1,
//! the complete basis, fields on fixed nodes, essential boundary conditions) and the Hodge
//! decomposer's factorizations up to four times (on the raw bunny, a saddle factorization of
//! 174k unknowns each for a Galerkin mass).

use crate::dense::{free_eigenproblem, generalized_eigenvalues, hodge_pencil};
use faer::Mat;
use std::cell::OnceCell;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_discretizations::HodgeDecomposer;

/// An eigenfield of Lemma 1 with its eigenvalue: `(λ, u)`, `u` of `n1` coefficients.
pub type Eigenfield = (f64, Vec<f64>);

/// The shared computations of the checks of one complex (see the module documentation). Each is
/// computed on its first use; an error (why a spectrum cannot be computed) is kept and returned
/// to every check that asks, as each check reported it before.
pub struct CheckCache<'a, H: HodgeComplex + ?Sized> {
    complex: &'a H,
    dirichlet_energy: OnceCell<Mat<f64>>,
    biharmonic_energy: OnceCell<Mat<f64>>,
    hodge_spectrum: OnceCell<Result<Vec<f64>, String>>,
    exact_spectrum: OnceCell<Result<Vec<f64>, String>>,
    co_exact_spectrum: OnceCell<Result<Vec<f64>, String>>,
    eigenfields: OnceCell<Result<Vec<Eigenfield>, String>>,
    decomposer: OnceCell<Result<HodgeDecomposer<'a, H>, String>>,
}

impl<'a, H: HodgeComplex + ?Sized> CheckCache<'a, H> {
    /// An empty cache for `complex`.
    pub fn new(complex: &'a H) -> Self {
        Self {
            complex,
            dirichlet_energy: OnceCell::new(),
            biharmonic_energy: OnceCell::new(),
            hodge_spectrum: OnceCell::new(),
            exact_spectrum: OnceCell::new(),
            co_exact_spectrum: OnceCell::new(),
            eigenfields: OnceCell::new(),
            decomposer: OnceCell::new(),
        }
    }

    /// The complex.
    pub fn complex(&self) -> &'a H {
        self.complex
    }

    /// `S` formed densely (`n1 × n1`, every field node).
    pub fn dirichlet_energy(&self) -> &Mat<f64> {
        self.dirichlet_energy
            .get_or_init(|| self.complex.dirichlet_energy().to_dense())
    }

    /// `B` formed densely (`n1 × n1`, every field node).
    pub fn biharmonic_energy(&self) -> &Mat<f64> {
        self.biharmonic_energy
            .get_or_init(|| self.complex.biharmonic_energy().to_dense())
    }

    /// The spectrum of `L`, ascending: the dense generalized eigenvalues of `(S, M1)` on the free
    /// field nodes ([`crate::spectral_checks::measured_hodge_spectrum`]), or why they cannot be
    /// computed.
    pub fn hodge_spectrum(&self) -> Result<&[f64], String> {
        self.hodge_spectrum
            .get_or_init(|| {
                let (s, m, _) = hodge_pencil(self.complex, self.dirichlet_energy());
                generalized_eigenvalues(&s, &m)
            })
            .as_deref()
            .map_err(Clone::clone)
    }

    /// The dense eigenvalues of the exact pair `(d0ᵀ M1 d0, M0)` on the free potential nodes.
    pub fn exact_spectrum(&self) -> Result<&[f64], String> {
        self.exact_spectrum
            .get_or_init(|| {
                let (a, m, _) = free_eigenproblem(
                    &self.complex.exact_eigenproblem(),
                    self.complex.potential_nodes(),
                );
                generalized_eigenvalues(&a, &m)
            })
            .as_deref()
            .map_err(Clone::clone)
    }

    /// The dense eigenvalues of the co-exact pair `(d1 M1⁻¹ d1ᵀ, M2⁻¹)` on the free co-potential
    /// nodes.
    pub fn co_exact_spectrum(&self) -> Result<&[f64], String> {
        self.co_exact_spectrum
            .get_or_init(|| {
                let (a, m, _) = free_eigenproblem(
                    &self.complex.co_exact_eigenproblem(),
                    self.complex.co_potential_nodes(),
                );
                generalized_eigenvalues(&a, &m)
            })
            .as_deref()
            .map_err(Clone::clone)
    }

    /// The eigenfields of Lemma 1 with their eigenvalues
    /// ([`crate::spectral_checks::measured_lemma1_eigenfields`]), or why they cannot be
    /// computed.
    pub fn lemma1_eigenfields(&self) -> Result<&[Eigenfield], String> {
        self.eigenfields
            .get_or_init(|| crate::spectral_checks::measured_lemma1_eigenfields(self.complex))
            .as_deref()
            .map_err(Clone::clone)
    }

    /// The prefactored Hodge decomposer of the complex, or why it could not be factored.
    pub fn decomposer(&self) -> Result<&HodgeDecomposer<'a, H>, String> {
        self.decomposer
            .get_or_init(|| HodgeDecomposer::new(self.complex).map_err(|e| e.to_string()))
            .as_ref()
            .map_err(Clone::clone)
    }
}
