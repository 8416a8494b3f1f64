//! [`FullSoftDesign`]: Fisher et al. (2007) soft-constrained design at full resolution,
//! `(S + ωB + εM1 + C̃ᵀ W C̃) x = C̃ᵀ W c`, factored through a sparse augmented system (sparse
//! `LDLᵀ`) with iterative refinement. Diagonal masses: [`crate::diagonal_system`]; other masses:
//! [`crate::galerkin_soft`].

use crate::constraint::CompiledConstraint;
use crate::diagonal_system::DiagonalSoftSystem;
use crate::error::DesignError;
use crate::galerkin_soft::GalerkinSoftSystem;
use crate::soft_options::SoftOptions;
use crate::soft_system::{Factoring, SoftSystem};
use faer::Par;
use sprs::CsMat;
use std::time::{Duration, Instant};
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_solvers::iterative_refinement::SolveReport;
use tvf_solvers::FactorParallelism;
use tvf_solvers::{FillOrdering, SparseLdlt};

/// Wall-clock times of the last (re)factorization of a [`FullSoftDesign`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FactorTimings {
    /// Assembling the augmented matrix (and, at construction from a complex with non-diagonal
    /// masses, its sparse blocks).
    pub assembly: Duration,
    /// Sparse `LDLᵀ`: ordering and symbolic analysis (when done) plus the numeric factorization.
    pub factorization: Duration,
    /// Whether `factorization` included a new ordering and symbolic analysis.
    pub symbolic: bool,
}

/// The fill-reducing ordering [`FullSoftDesign::new`] uses: nested dissection of the
/// faces. On all five Table 1 meshes it needs fewer flops in the numeric factorization than AMD
/// (up to half as many) and the whole factorization was faster on each (numbers in
/// `docs/performance.md`, measured with papers/`examples/full_soft_orderings.rs`).
pub const DEFAULT_FULL_ORDERING: FillOrdering = FillOrdering::NestedDissection;

/// The full soft-design system and its sparse factorization.
///
/// `B = S M1⁻¹ S` is much denser than `S` (faces two rings apart couple), and with a
/// non-diagonal mass `S` itself is dense, so `A = S + εM1 + C̃ᵀWC̃ + ωB` is never formed. What is
/// factored depends on the masses of the complex:
///
/// - **`S` sparse and `M1` diagonal** (lumped masses, DEC): the quasi-definite augmented system
///   (`2 n1 × 2 n1`)
///
///   ```text
///   [ S + εM1 + C̃ᵀWC̃   √ω S ] [x]   [C̃ᵀWc]
///   [ √ω S             −M1  ] [y] = [  0  ]      (y = √ω M1⁻¹ S x)
///   ```
///
///   whose elimination of `y` gives back `A x = C̃ᵀWc`. It has only the sparsity of `S`, and it
///   is quasi-definite (positive definite top-left block, negative definite bottom-right block),
///   so a sparse `LDLᵀ` without pivoting exists for every symmetric ordering
///   ([`DEFAULT_FULL_ORDERING`] unless chosen with [`FullSoftDesign::of_complex`] or
///   [`FullSoftDesign::from_matrices_with_ordering`]); its inertia (`n1` positive, `n1`
///   negative pivots) is checked. The nested-dissection ordering groups the unknowns per face.
/// - **any other masses** (a consistent `M0`, a sparse `M1` such as the Whitney 1-form mass, a
///   co-potential mass stored as `M2⁻¹`): the same system on the free field nodes (a field is
///   zero on the others), with `−M1` sparse, and for each scalar space whose term `Rᵀ D⁻¹ R` of
///   `S` is dense (potentials: `R = d0ᵀ M1`, `D = M0`; co-potentials: `R = d1`, `D = M2⁻¹`) its
///   nodal quantity `p = D⁻¹ R x` (`M0⁻¹ d0ᵀ M1 x`, minus the divergence; `M2 d1 x`, the curl)
///   and a multiplier `s` as auxiliary unknowns on the free nodes of the space:
///
///   ```text
///          x           y            p             s      λ
///   x [ T + S_d      √ω S_d         0             Rᵀ     g   ]
///   y [ √ω S_d       −M1           √ω Rᵀ          0      0   ]      T = εM1 + C̃ᵀWC̃,
///   p [ 0            √ω R          D + W_p       −D      0   ]      S_d = the sparse terms of S
///   s [ R            0             −D             0      0   ]
///   λ [ gᵀ           0              0             0    −1/w  ]
///   ```
///
///   Eliminating `(p, s)` gives back the system above with `S = S_d + Rᵀ D⁻¹ R`. Every block is
///   sparse. A divergence or curl constraint of such a space is a sparse row `a` on `p` (its
///   term `W_p = w a aᵀ`), and a constraint row that stays dense over the field (the other
///   family through an inverse mass) is an unknown `λ` of its own (coupling `g`, the row). The
///   system is not quasi-definite (the `s` block is zero), but with each `p_i` eliminated before
///   its `s_i` an `LDLᵀ` exists with positive pivots on `x, p` and negative ones on `y, s, λ`;
///   the ordering groups the unknowns per field element and per scalar node to that end, and the
///   inertia is checked. A term of `S` with a sparse middle mass stays in `S_d` (so the potentials
///   of polygon-dec's diagonal `M0` with its sparse `M1`): through `(p, s)` the field block would
///   be singular up to `εM1` on those fields and the factorization inaccurate. Where a term must
///   go through `(p, s)`, the factored system uses a larger screening (1e-6 of the mean
///   eigenvalue) for the same reason, and the refinement removes it.
///
/// Every solve is refined on the original system `A` (applied as `S x + ω S M1⁻¹ S x + ...`
/// through sparse products and mass solves, `B` is never formed), with residuals in
/// double-double (see [`crate::SolveReport`]).
///
/// The constraint blocks keep the **union** of the patterns of every set of constraints seen
/// (explicit zeros where a constraint left), so changing the constraints refactors with the
/// symbolic analysis reused, unless a new constraint couples unknowns that the system does not
/// (a P1 divergence at a point mixes three vertex one-rings, a dense row adds an unknown); then the
/// pattern grows and one new symbolic analysis is done.
///
/// Factorizations and solves run on one thread or on all of them, chosen per system by a
/// [`FactorParallelism`] policy (default: one thread below [`crate::SEQUENTIAL_FLOP_LIMIT`]
/// flops, where faer's parallel factorization is slower).
#[derive(Debug)]
pub struct FullSoftDesign {
    /// The factored system, by the kind of masses: [`DiagonalSoftSystem`] or
    /// [`GalerkinSoftSystem`].
    system: Box<dyn SoftSystem>,
    factoring: Factoring,
    constraints: Vec<CompiledConstraint>,
    symbolic_analyses: usize,
    timings: FactorTimings,
}

impl FullSoftDesign {
    /// Assembles the system of `complex` and factors it for `constraints`, ordered by
    /// [`DEFAULT_FULL_ORDERING`].
    pub fn new<H: HodgeComplex + ?Sized>(
        complex: &H,
        options: SoftOptions,
        constraints: Vec<CompiledConstraint>,
    ) -> Result<Self, DesignError> {
        Self::of_complex(
            complex,
            options,
            constraints,
            DEFAULT_FULL_ORDERING,
            FactorParallelism::default(),
        )
    }

    /// The same as [`FullSoftDesign::new`] with the fill-reducing `ordering` and the threading
    /// of the factorizations chosen by the caller. A complex whose `S` is a sparse matrix and
    /// whose `M1` is diagonal gets the system of [`FullSoftDesign::from_matrices_with`]; any
    /// other the augmented system of its non-diagonal masses.
    pub fn of_complex<H: HodgeComplex + ?Sized>(
        complex: &H,
        options: SoftOptions,
        constraints: Vec<CompiledConstraint>,
        ordering: FillOrdering,
        parallelism: FactorParallelism,
    ) -> Result<Self, DesignError> {
        if let (Some(dirichlet), Some(mass)) = (
            complex.dirichlet_energy().as_sparse(),
            complex.m1().diagonal_values(),
        ) {
            return Self::from_matrices_with(
                dirichlet,
                mass,
                options,
                constraints,
                ordering,
                parallelism,
            );
        }
        let start = Instant::now();
        options.check()?;
        check_columns(&constraints, complex.field_dimension())?;
        let factoring = Factoring {
            ordering,
            parallelism,
        };
        Self::built(start, constraints, factoring, |constraints| {
            GalerkinSoftSystem::new(complex, options, constraints, factoring)
        })
    }

    /// The same from the Dirichlet energy `S` (`n1 × n1`, integrated, symmetric) and the
    /// diagonal of `M1`, ordered by [`DEFAULT_FULL_ORDERING`].
    pub fn from_matrices(
        dirichlet: &CsMat<f64>,
        mass: &[f64],
        options: SoftOptions,
        constraints: Vec<CompiledConstraint>,
    ) -> Result<Self, DesignError> {
        Self::from_matrices_with_ordering(
            dirichlet,
            mass,
            options,
            constraints,
            DEFAULT_FULL_ORDERING,
        )
    }

    /// The same as [`FullSoftDesign::from_matrices`] with the fill-reducing `ordering` of the
    /// augmented system chosen by the caller (kept for later symbolic analyses).
    pub fn from_matrices_with_ordering(
        dirichlet: &CsMat<f64>,
        mass: &[f64],
        options: SoftOptions,
        constraints: Vec<CompiledConstraint>,
        ordering: FillOrdering,
    ) -> Result<Self, DesignError> {
        Self::from_matrices_with(
            dirichlet,
            mass,
            options,
            constraints,
            ordering,
            FactorParallelism::default(),
        )
    }

    /// The same as [`FullSoftDesign::from_matrices_with_ordering`] with the threading of the
    /// factorizations and solves chosen by the caller (kept for later factorizations);
    /// the other constructors use [`FactorParallelism::default`].
    pub fn from_matrices_with(
        dirichlet: &CsMat<f64>,
        mass: &[f64],
        options: SoftOptions,
        constraints: Vec<CompiledConstraint>,
        ordering: FillOrdering,
        parallelism: FactorParallelism,
    ) -> Result<Self, DesignError> {
        let start = Instant::now();
        options.check()?;
        let n = dirichlet.rows();
        if mass.len() != n {
            return Err(DesignError::DimensionMismatch {
                what: "mass (must match S)",
                expected: n,
                actual: mass.len(),
            });
        }
        check_columns(&constraints, n)?;
        let factoring = Factoring {
            ordering,
            parallelism,
        };
        Self::built(start, constraints, factoring, |constraints| {
            DiagonalSoftSystem::new(dirichlet, mass, options, constraints, factoring)
        })
    }

    /// The design of the system that `assemble_and_factor` builds for `constraints` (checked
    /// by the caller, which started at `start`), with the timings of that first factorization.
    fn built<S: SoftSystem + 'static>(
        start: Instant,
        constraints: Vec<CompiledConstraint>,
        factoring: Factoring,
        assemble_and_factor: impl FnOnce(&[CompiledConstraint]) -> Result<(S, Instant), DesignError>,
    ) -> Result<Self, DesignError> {
        let (system, assembled) = assemble_and_factor(&constraints)?;
        Ok(Self {
            system: Box::new(system),
            factoring,
            constraints,
            symbolic_analyses: 1,
            timings: FactorTimings {
                assembly: assembled - start,
                factorization: assembled.elapsed(),
                symbolic: true,
            },
        })
    }

    /// Replaces the constraints and refactors (numerically only when the pattern holds them).
    /// Returns whether the symbolic analysis was reused.
    pub fn set_constraints(
        &mut self,
        constraints: Vec<CompiledConstraint>,
    ) -> Result<bool, DesignError> {
        let start = Instant::now();
        check_columns(&constraints, self.system.field_dimension())?;
        let (fits, assembled) = self.system.set_constraints(&constraints, self.factoring)?;
        if !fits {
            self.symbolic_analyses += 1;
        }
        self.timings = FactorTimings {
            assembly: assembled - start,
            factorization: assembled.elapsed(),
            symbolic: !fits,
        };
        self.constraints = constraints;
        Ok(fits)
    }

    /// How many symbolic analyses were done so far (1 after construction).
    pub fn symbolic_analyses(&self) -> usize {
        self.symbolic_analyses
    }

    /// Times of the last factorization (construction or [`FullSoftDesign::set_constraints`]).
    pub fn timings(&self) -> FactorTimings {
        self.timings
    }

    /// The fill-reducing ordering of the augmented system.
    pub fn ordering(&self) -> FillOrdering {
        self.factoring.ordering
    }

    /// Whether the factorizations and solves run on all threads (`false`: one thread), as
    /// chosen by the [`FactorParallelism`] policy for this system.
    pub fn is_parallel(&self) -> bool {
        self.factor().parallelism() != Par::Seq
    }

    /// Stored entries of the factor `L` of the augmented system (a measure of fill-in).
    pub fn factor_entries(&self) -> usize {
        self.factor().factor_len()
    }

    /// Floating-point operations of one numeric factorization of the augmented system
    /// (`Σ_j c_j²` over the columns of `L`): the machine-independent cost of the ordering.
    pub fn factor_flop_count(&self) -> f64 {
        self.factor().factor_flop_count()
    }

    /// The active constraints.
    pub fn constraints(&self) -> &[CompiledConstraint] {
        &self.constraints
    }

    /// The right-hand side `C̃ᵀ W c` (`n1` values, integrated units of the constraints).
    pub fn right_hand_side(&self) -> Vec<f64> {
        let mut b = vec![0.0; self.system.field_dimension()];
        for c in &self.constraints {
            for (row, value) in c.rows.iter().zip(&c.values) {
                for &(j, a) in row {
                    b[j] += c.weight * a * value;
                }
            }
        }
        b
    }

    /// `A x = (S + εM1 + C̃ᵀWC̃) x + ω S M1⁻¹ S x` (`n1` values), without forming `B` (nor `S`
    /// where a mass is not diagonal). With fixed field nodes (a boundary condition on the field)
    /// `A` is the system on the free ones: the entries of `x` there are ignored and those of
    /// `A x` are zero.
    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        self.system.apply(x)
    }

    /// `b − A x` evaluated in double-double arithmetic (see [`crate::SolveReport`]): `S x`,
    /// `M1⁻¹ S x` and `S M1⁻¹ S x` are carried with their rounding errors, so the residual is
    /// accurate even where `ω S M1⁻¹ S` cancels heavily (slivers). Mass solves with a
    /// non-diagonal mass are applied in `f64` to both parts of the double-double vectors.
    pub fn accurate_residual(&self, x: &[f64], b: &[f64]) -> Vec<f64> {
        self.system.accurate_residual(x, b)
    }

    /// Solves for the field `x` (`n1` values) with iterative refinement until the relative
    /// residual `‖b − A x‖/‖b‖` (computed in double-double) is below 1e-12 or stops decreasing,
    /// and reports its history.
    pub fn solve(&self) -> (Vec<f64>, SolveReport) {
        self.system.solve(&self.right_hand_side())
    }

    fn factor(&self) -> &SparseLdlt {
        self.system.factor()
    }
}

/// Every constraint column below `n` (the number of field coefficients `n1`).
fn check_columns(constraints: &[CompiledConstraint], n: usize) -> Result<(), DesignError> {
    match constraints
        .iter()
        .flat_map(|c| c.rows.iter().flatten())
        .find(|(j, _)| *j >= n)
    {
        Some(&(j, _)) => Err(DesignError::DimensionMismatch {
            what: "constraint row column (must be < n1)",
            expected: n,
            actual: j,
        }),
        None => Ok(()),
    }
}
