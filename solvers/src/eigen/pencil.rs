//! [`Pencil`]: a symmetric pencil `(A, M)` and what is known about the factorizations made for
//! it: each shift's inertia is remembered (a shift counted once is never factored again), the
//! fill-reducing ordering of the first factorization is reused by all later ones, and an
//! interval of the eigensolver solves and refines with the one factorization at its shift,
//! which is freed when the interval is done.
//!
//! Three kinds of pencils:
//! - **diagonal mass** ([`Pencil::new`]): `A` sparse, `M` a positive diagonal; shifts factor
//!   `A − σM`;
//! - **sparse mass** ([`Pencil::with_mass`] with [`MassMatrix::Sparse`]): `M` sparse SPD;
//!   shifts factor `A − σM` on the union of both patterns, and `M⁻¹` (refinement, eigenfield
//!   residuals) is a sparse Cholesky factorization of `M`, made once;
//! - **mixed** ([`Pencil::mixed`]): `A = d1 W⁻¹ d1ᵀ` (dense, never formed) with `W` sparse SPD,
//!   mass `N` diagonal or sparse; `A x` is `d1 (W⁻¹ (d1ᵀ x))` with a sparse Cholesky
//!   factorization of `W`, made once. Shifts factor (see `shift_factor.rs`):
//!   - for a sparse `N`, the saddle matrix `K(σ) = [[−W, d1ᵀ], [d1, −σN]]`, whose inertia is
//!     `n1` negatives plus that of `A − σN` (Sylvester's law, eliminating `−W` first), so the
//!     count below σ is `negatives(K(σ)) − n1` whatever the elimination order;
//!   - for a diagonal `N`, the edges' matrix `C(σ) = d1ᵀ N⁻¹ d1 − σW`. Its negatives at σ > 0
//!     are the eigenvalues of `(d1ᵀ N⁻¹ d1, W)` below σ: the `n1 − r` of its kernel (`r` the
//!     rank of `d1`) and the nonzero ones, which are those of `(A, N)`. The kernel of `A` has
//!     dimension `n2 − r`, so the count below σ is `negatives(C(σ)) + n2 − n1`; below a shift
//!     `≤ 0` there is none (`A` is semidefinite).
//!
//!   Both lose the count at shifts of about `1e-16 λ_max` and below, where the pivots on the
//!   kernel of `d1` (`−σW` in `C(σ)`; in `K(σ)` what is left of `−W` after `d1ᵀ d1 / (σN)`) are
//!   rounding noise: on a Whitney pencil of 480 faces both were refused as having lost accuracy
//!   at `2e-17 λ_max`, and `C(σ)` counted right from `3e-16 λ_max` up (the test
//!   `the_mixed_pencil_counts_right_below_its_smallest_nonzero_eigenvalue` checks down to
//!   `1e-10 λ₁`). The eigensolver's shifts lie above half the smallest nonzero eigenvalue,
//!   about `λ_max / n` on a mesh.

use super::mass::{symmetric_full, Mass, MassMatrix};
use super::mixed_operator::MixedOperator;
use super::shift_factor::{saddle_pattern, KrylovFrame, ShiftFactor};
use super::sparse_summaries::{diagonal_of, max_column_sum};
use super::spectrum_bound::{block_power_norm, hutchinson_trace, upper_bound_of};
use super::statistics::{Phase, SolverStatistics};
use super::stiffness::Stiffness;
use super::stored_mass::{check_diagonal_mass, MassSolver, SparseMass, StoredMass};
use crate::convert::{
    edge_schur_pattern, shifted_upper_triangle, square_dimension, upper_triangle_csc,
    ShiftedPattern,
};
use crate::dense_eigen::{dense_generalized_eigen, dense_generalized_eigen_with_mass};
use crate::error::SolverError;
use crate::sparse_ldlt::{FactorPattern, SparseLdlt};
use faer::sparse::SparseColMat;
use faer::{Mat, Par};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};

/// Upward nudges of a shift that lands on an eigenvalue (a zero pivot) before giving up.
const MAX_NUDGES: i32 = 8;

/// A shift and the exact number of eigenvalues of the pencil strictly below it (Sylvester's law
/// of inertia: the negative pivots of `LDLᵀ = A − σM`, less `n1` for a mixed pencil).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShiftCount {
    /// The shift σ (units of λ), nudged upwards from the one asked for if that one was an
    /// eigenvalue to working precision.
    pub shift: f64,
    /// Eigenvalues strictly below `shift`, kernel included.
    pub below: usize,
}

/// What each kind of pencil stores (see the module documentation; one per pencil).
#[allow(clippy::large_enum_variant)]
enum Kind<'a> {
    Diagonal {
        stiffness: &'a sprs::CsMat<f64>,
        /// Full symmetric storage of `A` (products, Rayleigh–Ritz, residuals).
        full: SparseColMat<usize, f64>,
        mass: &'a [f64],
    },
    SparseMass {
        full: SparseColMat<usize, f64>,
        mass: SparseMass,
        shifted: ShiftedPattern,
        diagonal: Vec<f64>,
        norm: f64,
    },
    Mixed {
        operator: MixedOperator,
        mass: StoredMass<'a>,
        shifted: ShiftedPattern,
        /// Estimate of the diagonal of `A` ([`MixedOperator::diagonal_estimate`]).
        diagonal: Vec<f64>,
        /// Estimate of `‖A‖₂` (Lanczos, see [`Pencil::mixed`]).
        norm: f64,
    },
}

/// What the refinement and the residuals need of a pencil (see `refinement.rs`).
#[derive(Clone, Copy)]
pub(crate) struct PencilOperators<'a> {
    pub stiffness: Stiffness<'a>,
    pub mass: Mass<'a>,
    /// The Cholesky factorization of a sparse mass (`None` for a diagonal one).
    pub mass_factor: Option<&'a SparseLdlt>,
    /// The diagonal of `M` (also for a sparse mass).
    pub mass_diagonal: &'a [f64],
    /// The diagonal of `A` (an estimate for a mixed pencil); empty for a diagonal-mass pencil,
    /// whose residuals compute it as they always did.
    pub stiffness_diagonal: &'a [f64],
    /// `‖A‖` of the relative residuals (see [`crate::Eigenpairs::residuals`]); 0 for a
    /// diagonal-mass pencil (computed by the residuals).
    pub stiffness_norm: f64,
}

/// The generalized symmetric eigenproblem `A x = λ M x` with its factorizations (the three
/// kinds are described in the module documentation of `pencil.rs` and in the crate docs).
pub struct Pencil<'a> {
    kind: Kind<'a>,
    /// The scale of the spectrum: the unit of the nudges of a shift off an eigenvalue and of the
    /// top-shift search when the mean eigenvalue is not positive. With a diagonal mass the
    /// Gershgorin bound (see [`Pencil::spectrum_upper_bound`]); otherwise a cheap estimate of
    /// the top of the spectrum (see [`Pencil::with_mass`], [`Pencil::mixed`]).
    pub(crate) scale: f64,
    /// [`Pencil::spectrum_upper_bound`] of a pencil without a diagonal mass, made on first use.
    bound: OnceLock<f64>,
    /// `trace(A)/Σ_ij M_ij`: the mean eigenvalue (robust to sliver triangles, unlike `scale`).
    pub(crate) mean_eigenvalue: f64,
    /// The ordering of the first factorization, reused by all later ones (its values are not
    /// kept: a factor of a million-face mesh's pencil takes a gigabyte), and the frame of the
    /// Krylov vectors in it.
    template: Mutex<Option<(Arc<FactorPattern>, Arc<KrylovFrame>)>>,
    counts: Mutex<Vec<ShiftCount>>,
    statistics: Mutex<SolverStatistics>,
}

impl<'a> Pencil<'a> {
    /// Checks and stores the pencil with a diagonal mass.
    ///
    /// - `stiffness`: `A`, `n × n` sparse symmetric (full or upper-triangular storage, CSC or
    ///   CSR), positive semidefinite (mildly negative eigenvalues are found too).
    /// - `mass`: the `n` positive entries of a diagonal mass matrix.
    ///
    /// Errors: [`SolverError::NotSquare`], [`SolverError::DimensionMismatch`],
    /// [`SolverError::NonFinite`], [`SolverError::MassNotPositive`].
    pub fn new(stiffness: &'a sprs::CsMat<f64>, mass: &'a [f64]) -> Result<Self, SolverError> {
        let n = square_dimension(stiffness)?;
        check_diagonal_mass(mass, n)?;
        let full = symmetric_full(&upper_triangle_csc(stiffness)?)?;
        let col_ptr = full.symbolic().col_ptr();
        let row_idx = full.symbolic().row_idx();
        let column = |j: usize| col_ptr[j]..col_ptr[j + 1];
        let rho = (0..n)
            .map(|j| column(j).map(|p| full.val()[p].abs()).sum::<f64>() / mass[j])
            .fold(0.0, f64::max);
        let trace: f64 = (0..n)
            .flat_map(|j| column(j).filter(move |&p| row_idx[p] == j))
            .map(|p| full.val()[p])
            .sum();
        let total_mass: f64 = mass.iter().sum();
        Ok(Self::with_kind(
            Kind::Diagonal {
                stiffness,
                full,
                mass,
            },
            if rho > 0.0 { rho } else { 1.0 },
            if total_mass > 0.0 {
                trace / total_mass
            } else {
                0.0
            },
        ))
    }

    /// Checks and stores the pencil `A x = λ M x` with a mass of either kind:
    /// [`MassMatrix::Diagonal`] is [`Pencil::new`]; [`MassMatrix::Sparse`] (`n × n` SPD) is
    /// factored (sparse Cholesky) once, for `M⁻¹`. The scale of its spectrum (nudges of
    /// shifts) is `max_i Σ_j |A_ij| / M_ii` (not a bound with a non-diagonal `M`: see
    /// [`Pencil::spectrum_upper_bound`]).
    ///
    /// Errors: those of [`Pencil::new`], and [`SolverError::MatrixNotPositiveDefinite`] naming
    /// the mass matrix.
    pub fn with_mass(
        stiffness: &'a sprs::CsMat<f64>,
        mass: MassMatrix<'a>,
    ) -> Result<Self, SolverError> {
        let m = match mass {
            MassMatrix::Diagonal(mass) => return Self::new(stiffness, mass),
            MassMatrix::Sparse(m) => m,
        };
        let n = square_dimension(stiffness)?;
        let upper = upper_triangle_csc(stiffness)?;
        let full = symmetric_full(&upper)?;
        let mass = SparseMass::new(m, n)?;
        let shifted = ShiftedPattern::new(&upper, &upper_triangle_csc(m)?)?;
        let diagonal = diagonal_of(full.as_ref());
        let trace: f64 = diagonal.iter().sum();
        let total_mass: f64 = mass.full.val().iter().sum();
        let col_ptr = full.symbolic().col_ptr();
        let bound = (0..n)
            .map(|j| {
                let sum: f64 = full.val()[col_ptr[j]..col_ptr[j + 1]]
                    .iter()
                    .map(|v| v.abs())
                    .sum();
                sum / mass.diagonal[j]
            })
            .fold(0.0, f64::max);
        let norm = max_column_sum(full.as_ref());
        Ok(Self::with_kind(
            Kind::SparseMass {
                full,
                mass,
                shifted,
                diagonal,
                norm,
            },
            if bound > 0.0 { bound } else { 1.0 },
            if total_mass > 0.0 {
                trace / total_mass
            } else {
                0.0
            },
        ))
    }

    /// Checks and stores the mixed pencil `d1 W⁻¹ d1ᵀ ψ = μ N ψ` (dimension `n2`):
    ///
    /// - `w`: `W`, `n1 × n1` sparse SPD (full or upper storage), e.g. the Whitney 1-form mass
    ///   on edges; factored once (sparse Cholesky);
    /// - `d1`: `n2 × n1` sparse, e.g. the signed face–edge incidence;
    /// - `mass`: `N`, diagonal (`n2` positive entries, e.g. face areas) or sparse SPD `n2 × n2`.
    ///
    /// `A = d1 W⁻¹ d1ᵀ` is dense and never formed (except on the dense path of small
    /// problems). Its norm in the relative residuals ([`crate::Eigenpairs::residuals`]) is
    /// `‖A‖₂ = λ_max(A)` estimated by [`POWER_STEPS`] steps of block power iteration (eight
    /// pseudo-random vectors, the largest Rayleigh quotient: an estimate from below, whose
    /// relative error shrinks as `(λ_2/λ_1)^(2·steps)`); the scale of the spectrum is that norm over the smallest
    /// `N_ii`; the mean eigenvalue that anchors the first trial shift uses a Hutchinson estimate
    /// of `trace(A)` (eight random sign vectors).
    ///
    /// Errors: [`SolverError::NotSquare`], [`SolverError::DimensionMismatch`],
    /// [`SolverError::NonFinite`], [`SolverError::MassNotPositive`],
    /// [`SolverError::MatrixNotPositiveDefinite`] naming `W` or the mass matrix.
    pub fn mixed(
        w: &sprs::CsMat<f64>,
        d1: &sprs::CsMat<f64>,
        mass: MassMatrix<'a>,
    ) -> Result<Self, SolverError> {
        let operator = MixedOperator::new(w, d1)?;
        let (n1, n2) = (operator.inner_dimension(), operator.dimension());
        let mass = StoredMass::new(mass, n2)?;
        let w_upper = upper_triangle_csc(w)?;
        let shifted = match &mass {
            StoredMass::Diagonal(values) => edge_schur_pattern(w, d1, values)?,
            StoredMass::Sparse(_) => saddle_pattern(&w_upper, d1, &mass, n1, n2)?,
        };
        let diagonal = operator.diagonal_estimate(&diagonal_of(w_upper.as_ref()));
        let stiffness = Stiffness::Mixed(&operator);
        let norm = block_power_norm(stiffness, n2);
        let smallest_mass = match &mass {
            StoredMass::Diagonal(d) => d.iter().copied().fold(f64::INFINITY, f64::min),
            StoredMass::Sparse(m) => m.diagonal.iter().copied().fold(f64::INFINITY, f64::min),
        };
        let bound = norm / smallest_mass;
        let trace = hutchinson_trace(stiffness, n2);
        let total_mass = mass.total();
        Ok(Self::with_kind(
            Kind::Mixed {
                operator,
                mass,
                shifted,
                diagonal,
                norm: norm.max(f64::MIN_POSITIVE),
            },
            if bound > 0.0 { bound } else { 1.0 },
            if total_mass > 0.0 {
                trace / total_mass
            } else {
                0.0
            },
        ))
    }

    fn with_kind(kind: Kind<'a>, scale: f64, mean_eigenvalue: f64) -> Self {
        Self {
            kind,
            scale,
            mean_eigenvalue,
            bound: OnceLock::new(),
            template: Mutex::new(None),
            counts: Mutex::new(Vec::new()),
            statistics: Mutex::new(SolverStatistics::default()),
        }
    }

    /// Dimension of the eigenproblem: `n`, or `n2` for a mixed pencil.
    pub fn dimension(&self) -> usize {
        match &self.kind {
            Kind::Diagonal { mass, .. } => mass.len(),
            Kind::SparseMass { full, .. } => full.nrows(),
            Kind::Mixed { operator, .. } => operator.dimension(),
        }
    }

    /// An upper bound of the spectrum (units of λ, ≥ every eigenvalue):
    /// - diagonal mass: the Gershgorin bound `max_i Σ_j |A_ij| / M_ii`, rigorous;
    /// - sparse mass and mixed pencils: Gershgorin is no bound there (the consistent P1 mass
    ///   has `M_ii = Σ_{j≠i} |M_ij|`), so it is `(θ + ρ) · 1.05` from 40 Lanczos steps on
    ///   `M⁻¹ A` (largest Ritz value θ, its residual norm ρ: see `spectrum_bound.rs`), computed
    ///   on the first call (40 products with `A` and solves with `M`) and remembered: an
    ///   inflated estimate, not a proof.
    pub fn spectrum_upper_bound(&self) -> f64 {
        let (stiffness, mass) = match &self.kind {
            Kind::Diagonal { .. } => return self.scale,
            Kind::SparseMass { full, mass, .. } => {
                (Stiffness::Sparse(full.as_ref()), MassSolver::Sparse(mass))
            }
            Kind::Mixed { operator, mass, .. } => (
                Stiffness::Mixed(operator),
                match mass {
                    StoredMass::Diagonal(d) => MassSolver::Diagonal(d),
                    StoredMass::Sparse(m) => MassSolver::Sparse(m),
                },
            ),
        };
        *self
            .bound
            .get_or_init(|| upper_bound_of(stiffness, mass, self.dimension()))
    }

    /// The operators of the pencil for products, refinement and residuals.
    pub(crate) fn operators(&self) -> PencilOperators<'_> {
        match &self.kind {
            Kind::Diagonal { full, mass, .. } => PencilOperators {
                stiffness: Stiffness::Sparse(full.as_ref()),
                mass: Mass::Diagonal(mass),
                mass_factor: None,
                mass_diagonal: mass,
                stiffness_diagonal: &[],
                stiffness_norm: 0.0,
            },
            Kind::SparseMass {
                full,
                mass,
                diagonal,
                norm,
                ..
            } => PencilOperators {
                stiffness: Stiffness::Sparse(full.as_ref()),
                mass: Mass::Sparse(mass.full.as_ref()),
                mass_factor: Some(&mass.factor),
                mass_diagonal: &mass.diagonal,
                stiffness_diagonal: diagonal,
                stiffness_norm: *norm,
            },
            Kind::Mixed {
                operator,
                mass,
                diagonal,
                norm,
                ..
            } => PencilOperators {
                stiffness: Stiffness::Mixed(operator),
                mass: mass.view(),
                mass_factor: match mass {
                    StoredMass::Sparse(m) => Some(&m.factor),
                    StoredMass::Diagonal(_) => None,
                },
                mass_diagonal: match mass {
                    StoredMass::Sparse(m) => &m.diagonal,
                    StoredMass::Diagonal(d) => d,
                },
                stiffness_diagonal: diagonal,
                stiffness_norm: *norm,
            },
        }
    }

    /// The mass in the pencil's input order.
    pub(crate) fn mass(&self) -> Mass<'_> {
        self.operators().mass
    }

    /// All eigenpairs by the dense solver (small problems): ascending values, M-orthonormal
    /// vectors (`n × n`).
    ///
    /// Errors: those of [`dense_generalized_eigen`] and [`dense_generalized_eigen_with_mass`].
    pub(crate) fn dense_eigenpairs(&self) -> Result<(Vec<f64>, Mat<f64>), SolverError> {
        match &self.kind {
            Kind::Diagonal { full, mass, .. } => {
                dense_generalized_eigen(full.to_dense().as_ref(), mass)
            }
            Kind::SparseMass { full, mass, .. } => dense_generalized_eigen_with_mass(
                full.to_dense().as_ref(),
                mass.full.to_dense().as_ref(),
            ),
            Kind::Mixed { operator, mass, .. } => {
                let a = operator.dense();
                match mass {
                    StoredMass::Diagonal(d) => dense_generalized_eigen(a.as_ref(), d),
                    StoredMass::Sparse(m) => {
                        dense_generalized_eigen_with_mass(a.as_ref(), m.full.to_dense().as_ref())
                    }
                }
            }
        }
    }

    /// The exact number of eigenvalues strictly below `t` (kernel included), at `t` or, if `t`
    /// is an eigenvalue to working precision, at a shift nudged slightly upwards. A shift counted
    /// before is not factored again.
    ///
    /// Errors: [`SolverError::NoConvergence`] if every nudged shift is singular, factorization
    /// failures.
    pub fn count_below(&self, t: f64) -> Result<ShiftCount, SolverError> {
        if let Some(known) = self.counted().into_iter().find(|c| c.shift == t) {
            return Ok(known);
        }
        let (_, count) = self.factor(t, Phase::Counting, Par::Seq)?;
        Ok(count)
    }

    /// Every shift counted so far (by [`Pencil::count_below`] or by the eigensolver), ascending.
    pub fn counted(&self) -> Vec<ShiftCount> {
        let mut counts = self
            .counts
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone();
        counts.sort_by(|a, b| a.shift.total_cmp(&b.shift));
        counts
    }

    /// Factorizations and solves so far, by phase (no times: those belong to the caller's phases).
    pub fn statistics(&self) -> SolverStatistics {
        *self
            .statistics
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    /// Adds `solves` single-vector solves to `phase`.
    pub(crate) fn add_solves(&self, phase: Phase, solves: usize) {
        self.statistics
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .phase_mut(phase)
            .solves += solves;
    }

    /// The upper triangle of the matrix factored at `shift`: `A − σM` or `K(σ)`.
    fn shifted(&self, shift: f64) -> Result<SparseColMat<usize, f64>, SolverError> {
        match &self.kind {
            Kind::Diagonal {
                stiffness, mass, ..
            } => shifted_upper_triangle(stiffness, mass, shift),
            Kind::SparseMass { shifted, .. } | Kind::Mixed { shifted, .. } => Ok(shifted.at(shift)),
        }
    }

    /// The eigenvalues below `shift` from the `negative` pivots of the matrix factored there
    /// (see the module documentation): all of them for `A − σM`; less the `n1` of `−W` for
    /// `K(σ)`; plus `n2 − n1` for `C(σ)` at `σ > 0` (none below a shift `≤ 0`, where `C(σ)` is
    /// positive semidefinite).
    ///
    /// Errors: [`SolverError::NoConvergence`] when the pivots are fewer than that structure
    /// allows (the factorization lost accuracy).
    fn eigenvalues_below(&self, negative: usize, shift: f64) -> Result<usize, SolverError> {
        let Kind::Mixed { operator, mass, .. } = &self.kind else {
            return Ok(negative);
        };
        let (n1, n2) = (operator.inner_dimension(), operator.dimension());
        let count = match mass {
            StoredMass::Sparse(_) => negative.checked_sub(n1),
            StoredMass::Diagonal(_) if shift <= 0.0 => Some(0),
            StoredMass::Diagonal(_) => (negative + n2).checked_sub(n1),
        };
        count.ok_or_else(|| SolverError::NoConvergence {
            reason: format!(
                "the matrix factored at {shift:e} has {negative} negative pivots, fewer than the \
                 {n1} unknowns of W and the {n2} of the pencil allow: its factorization lost \
                 accuracy"
            ),
        })
    }

    /// The frame of the Krylov vectors for the first factorization `ldlt` of the pencil.
    fn frame(&self, ldlt: &SparseLdlt) -> Result<KrylovFrame, SolverError> {
        match &self.kind {
            Kind::Diagonal { .. } => KrylovFrame::standard(ldlt, None),
            Kind::SparseMass { mass, .. } => KrylovFrame::standard(ldlt, Some(mass.full.as_ref())),
            Kind::Mixed {
                operator,
                mass,
                shifted,
                ..
            } => {
                let (base, shift_part) = shifted.parts();
                let shift_part = symmetric_full(&shift_part)?;
                match mass.view() {
                    // `C(σ) = base − σ W`: its shift part is `W`.
                    Mass::Diagonal(values) => KrylovFrame::edge_schur(
                        ldlt,
                        operator.incidence(),
                        values,
                        shift_part.as_ref(),
                    ),
                    Mass::Sparse(m) => KrylovFrame::saddle(
                        ldlt,
                        operator.inner_dimension(),
                        Some(m),
                        (symmetric_full(&base)?.as_ref(), shift_part.as_ref()),
                    ),
                }
            }
        }
    }

    /// The factorization at `sigma` (`LDLᵀ` of `A − σM` or of `K(σ)`) or, if that is an
    /// eigenvalue to working precision (a zero pivot), at a shift nudged upwards by growing
    /// relative steps from 1e-12; records the count and the factorizations under `phase`.
    pub(crate) fn factor(
        &self,
        sigma: f64,
        phase: Phase,
        parallelism: Par,
    ) -> Result<(Arc<ShiftFactor>, ShiftCount), SolverError> {
        let step = sigma.abs().max(1e-6 * self.scale);
        let mut shift = sigma;
        for attempt in 0..MAX_NUDGES {
            let upper = self.shifted(shift)?;
            let result = {
                let mut template = self.template.lock().unwrap_or_else(PoisonError::into_inner);
                match template.as_ref() {
                    Some((pattern, frame)) => {
                        let (pattern, frame) = (Arc::clone(pattern), Arc::clone(frame));
                        drop(template);
                        pattern
                            .factor(upper.as_ref(), parallelism)
                            .map(|ldlt| ShiftFactor::new(ldlt, shift, frame))
                    }
                    None => SparseLdlt::new(upper.as_ref()).and_then(|mut ldlt| {
                        ldlt.set_parallelism(parallelism);
                        let frame = Arc::new(self.frame(&ldlt)?);
                        *template = Some((Arc::new(ldlt.pattern()), Arc::clone(&frame)));
                        Ok(ShiftFactor::new(ldlt, shift, frame))
                    }),
                }
            };
            self.statistics
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .phase_mut(phase)
                .factorizations += 1;
            match result {
                Ok(factor) => {
                    let inertia = factor.inertia();
                    if inertia.zero == 0 {
                        let below = self.eigenvalues_below(inertia.negative, shift)?;
                        let count = ShiftCount { shift, below };
                        self.counts
                            .lock()
                            .unwrap_or_else(PoisonError::into_inner)
                            .push(count);
                        return Ok((Arc::new(factor), count));
                    }
                }
                Err(SolverError::Singular { .. }) => {}
                Err(e) => return Err(e),
            }
            shift = sigma + step * 1e-12 * 16f64.powi(attempt + 1);
        }
        Err(SolverError::NoConvergence {
            reason: format!(
                "every shift tried near {sigma:e} is an eigenvalue to working precision (zero \
                 pivots), so the eigenvalues below it cannot be counted"
            ),
        })
    }
}
