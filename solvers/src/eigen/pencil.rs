//! [`Pencil`]: a symmetric pencil `(A, M)` (`M` diagonal, positive) and what is known about the
//! factorizations of `A − σM` made for it: each shift's inertia is remembered (a shift counted
//! once is never factored again), the fill-reducing ordering of the first factorization is
//! reused by all later ones, and an interval of the eigensolver solves and refines with the one
//! factorization at its shift, which is freed when the interval is done.

use super::statistics::{Phase, SolverStatistics};
use crate::convert::{shifted_upper_triangle, square_dimension, upper_triangle_csc};
use crate::dense_eigen::check_mass;
use crate::error::SolverError;
use crate::sparse_ldlt::{FactorPattern, SparseLdlt};
use faer::sparse::{SparseColMat, Triplet};
use faer::Par;
use std::sync::{Arc, Mutex, PoisonError};

/// Upward nudges of a shift that lands on an eigenvalue (a zero pivot) before giving up.
const MAX_NUDGES: i32 = 8;

/// A shift and the exact number of eigenvalues of the pencil strictly below it (Sylvester's law
/// of inertia: the negative pivots of `LDLᵀ = A − σM`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShiftCount {
    /// The shift σ (units of λ), nudged upwards from the one asked for if that one was an
    /// eigenvalue to working precision.
    pub shift: f64,
    /// Eigenvalues strictly below `shift`, kernel included.
    pub below: usize,
}

/// The generalized symmetric eigenproblem `A x = λ M x` with its factorizations.
///
/// - `A`: `n × n` sparse symmetric (full or upper-triangular storage, CSC or CSR),
///   positive semidefinite (mildly negative eigenvalues are found too).
/// - `M`: the `n` positive entries of a diagonal mass matrix.
pub struct Pencil<'a> {
    stiffness: &'a sprs::CsMat<f64>,
    /// Full symmetric storage of `A` (products, Rayleigh–Ritz, residuals).
    pub(crate) full: SparseColMat<usize, f64>,
    pub(crate) mass: &'a [f64],
    /// Gershgorin bound of the spectrum of `M⁻¹A` (scale of shifts, ≥ every eigenvalue).
    pub(crate) scale: f64,
    /// `trace(A)/trace(M)`: the mean eigenvalue (robust to sliver triangles, unlike `scale`).
    pub(crate) mean_eigenvalue: f64,
    /// The ordering of the first factorization, reused by all later ones (its values are not
    /// kept: a factor of a million-face mesh's pencil takes a gigabyte).
    template: Mutex<Option<Arc<FactorPattern>>>,
    counts: Mutex<Vec<ShiftCount>>,
    statistics: Mutex<SolverStatistics>,
}

impl<'a> Pencil<'a> {
    /// Checks and stores the pencil.
    ///
    /// Errors: [`SolverError::NotSquare`], [`SolverError::DimensionMismatch`],
    /// [`SolverError::NonFinite`], [`SolverError::MassNotPositive`].
    pub fn new(stiffness: &'a sprs::CsMat<f64>, mass: &'a [f64]) -> Result<Self, SolverError> {
        let n = square_dimension(stiffness)?;
        if mass.len() != n {
            return Err(SolverError::DimensionMismatch {
                context: "mass diagonal length",
                expected: n,
                actual: mass.len(),
            });
        }
        check_mass(mass)?;
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
        Ok(Self {
            stiffness,
            full,
            mass,
            scale: if rho > 0.0 { rho } else { 1.0 },
            mean_eigenvalue: if total_mass > 0.0 {
                trace / total_mass
            } else {
                0.0
            },
            template: Mutex::new(None),
            counts: Mutex::new(Vec::new()),
            statistics: Mutex::new(SolverStatistics::default()),
        })
    }

    /// Dimension `n`.
    pub fn dimension(&self) -> usize {
        self.mass.len()
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

    /// `LDLᵀ = A − σM` at `sigma` or, if that is an eigenvalue to working precision (a zero
    /// pivot), at a shift nudged upwards by growing relative steps from 1e-12; records the
    /// count and the factorizations under `phase`.
    pub(crate) fn factor(
        &self,
        sigma: f64,
        phase: Phase,
        parallelism: Par,
    ) -> Result<(Arc<SparseLdlt>, ShiftCount), SolverError> {
        let step = sigma.abs().max(1e-6 * self.scale);
        let mut shift = sigma;
        for attempt in 0..MAX_NUDGES {
            let upper = shifted_upper_triangle(self.stiffness, self.mass, shift)?;
            let result = {
                let mut template = self.template.lock().unwrap_or_else(PoisonError::into_inner);
                match template.as_ref() {
                    Some(pattern) => {
                        let pattern = Arc::clone(pattern);
                        drop(template);
                        pattern.factor(upper.as_ref(), parallelism).map(Arc::new)
                    }
                    None => SparseLdlt::new(upper.as_ref()).map(|mut f| {
                        f.set_parallelism(parallelism);
                        *template = Some(Arc::new(f.pattern()));
                        Arc::new(f)
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
                        let count = ShiftCount {
                            shift,
                            below: inertia.negative,
                        };
                        self.counts
                            .lock()
                            .unwrap_or_else(PoisonError::into_inner)
                            .push(count);
                        return Ok((factor, count));
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

/// Full symmetric storage of the matrix whose upper triangle is `upper`.
fn symmetric_full(
    upper: &SparseColMat<usize, f64>,
) -> Result<SparseColMat<usize, f64>, SolverError> {
    let n = upper.nrows();
    let mut triplets = Vec::with_capacity(2 * upper.val().len());
    let col_ptr = upper.symbolic().col_ptr();
    let row_idx = upper.symbolic().row_idx();
    for j in 0..n {
        for p in col_ptr[j]..col_ptr[j + 1] {
            let i = row_idx[p];
            triplets.push(Triplet::new(i, j, upper.val()[p]));
            if i != j {
                triplets.push(Triplet::new(j, i, upper.val()[p]));
            }
        }
    }
    SparseColMat::try_new_from_triplets(n, n, &triplets)
        .map_err(|e| SolverError::Factorization(format!("{e:?}")))
}
