//! [`FullSoftDesign`]: Fisher et al. (2007) soft-constrained design at full resolution,
//! `(S + ωB + εM_X + C̃ᵀ W C̃) x = C̃ᵀ W c`, factored through a quasi-definite augmented system
//! (sparse `LDLᵀ`) with iterative refinement.

use crate::constraint::constraint_gram_entries;
use crate::constraint::CompiledConstraint;
use crate::error::DesignError;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Mat, Par};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use sprs::CsMat;
use std::time::{Duration, Instant};
use tvf_core::discretization::sparse::{diagonal, linear_combination, mul_vec};
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_solvers::iterative_refinement::{
    exact, refined_solve, symmetric_product, DoubleDouble, SolveReport,
};
use tvf_solvers::ordering::nested_dissection_of_groups;
use tvf_solvers::sparse_pattern::{position, with_extra_entries};
use tvf_solvers::FactorParallelism;
use tvf_solvers::{FillOrdering, SolverError, SparseLdlt};

/// Parameters of soft design (full and reduced use the same ones, so that they agree).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoftOptions {
    /// Weight `ω ≥ 0` of the biharmonic term: energy `E_D + ω E_B`.
    pub omega: f64,
    /// `ε ≥ 0`: a screening term `ε M_X` (units 1/length²) that makes the system definite on
    /// the harmonic fields when the constraints do not fix them (genus > 0). See
    /// [`default_regularization`].
    pub regularization: f64,
}

/// `ε = 1e-10 · tr(M1⁻¹ S) / n1`: ten orders of magnitude below the mean eigenvalue of the
/// Hodge–Laplacian, so it only matters on (near-)kernel directions left free by the constraints.
/// Where `S` is a sparse matrix and `M1` diagonal the trace is exact; otherwise it is estimated
/// from [`TRACE_PROBES`] seeded random sign vectors `z` as the mean of `zᵀ M1⁻¹ S z` (only the
/// scale of `ε` depends on it).
pub fn default_regularization<H: HodgeComplex + ?Sized>(complex: &H) -> f64 {
    let dirichlet = complex.dirichlet_energy();
    let n = dirichlet.rows().max(1) as f64;
    let trace: f64 = match (dirichlet.as_sparse(), complex.m1().diagonal_values()) {
        (Some(dirichlet), Some(mass)) => (0..dirichlet.rows())
            .map(|i| dirichlet.get(i, i).copied().unwrap_or(0.0) / mass[i].max(f64::MIN_POSITIVE))
            .sum(),
        _ => {
            let mut rng = ChaCha8Rng::seed_from_u64(TRACE_SEED);
            let estimates: f64 = (0..TRACE_PROBES)
                .map(|_| {
                    let z: Vec<f64> = (0..dirichlet.rows())
                        .map(|_| if rng.random_bool(0.5) { 1.0 } else { -1.0 })
                        .collect();
                    let y = complex.m1().solve(&dirichlet.apply(&z));
                    z.iter().zip(&y).map(|(a, b)| a * b).sum::<f64>()
                })
                .sum();
            estimates / TRACE_PROBES as f64
        }
    };
    1e-10 * trace / n
}

/// Random probes of the trace estimate of [`default_regularization`].
pub const TRACE_PROBES: usize = 8;
/// Seed of those probes.
const TRACE_SEED: u64 = 0x7472_6163_655f_6573;

/// Wall-clock times of the last (re)factorization of a [`FullSoftDesign`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FactorTimings {
    /// Assembling `S + εM_X + C̃ᵀWC̃` and the augmented matrix.
    pub assembly: Duration,
    /// Sparse `LDLᵀ`: ordering and symbolic analysis (when done) plus the numeric factorization.
    pub factorization: Duration,
    /// Whether `factorization` included a new ordering and symbolic analysis.
    pub symbolic: bool,
}

/// The fill-reducing ordering [`FullSoftDesign::from_matrices`] uses: nested dissection of the
/// faces. On all five Table 1 meshes it needs fewer flops in the numeric factorization than AMD
/// (Gflop, ND vs AMD: hand 4.5 vs 5.1, rocker-arm 6.5 vs 9.2, bunny-closed 60 vs 106,
/// bumpy-torus-x4 107 vs 221, armadillo-x4 329 vs 439) and the whole factorization was faster
/// on each (papers/`examples/full_soft_orderings.rs`).
pub const DEFAULT_FULL_ORDERING: FillOrdering = FillOrdering::NestedDissection;

/// The full soft-design system and its sparse factorization.
///
/// `B = S M_X⁻¹ S` is much denser than `S` (faces two rings apart couple), so instead of factoring
/// `A = S + εM_X + C̃ᵀWC̃ + ωB` this factors the **augmented** system (`4F × 4F`)
///
/// ```text
/// [ S + εM_X + C̃ᵀWC̃   √ω S ] [x]   [C̃ᵀWc]
/// [ √ω S              −M_X ] [y] = [  0  ]      (y = √ω M_X⁻¹ S x)
/// ```
///
/// whose elimination of `y` gives back `A x = C̃ᵀWc`. It has only the sparsity of `S`, and it is
/// quasi-definite (positive definite top-left block, negative definite bottom-right block), so a
/// sparse `LDLᵀ` without pivoting exists for every symmetric ordering ([`DEFAULT_FULL_ORDERING`]
/// unless chosen with [`FullSoftDesign::from_matrices_with_ordering`]); its inertia
/// (`2F` positive, `2F` negative pivots) is checked. Every solve is refined on the original
/// system `A` (applied as `S x + ω S M_X⁻¹ S x + ...`, `B` is never formed).
///
/// The top-left block keeps the **union** of the patterns of `S` and of every `C̃ᵀC̃` it has seen
/// (explicit zeros where a constraint left), so changing the constraints refactors numerically
/// with the symbolic analysis reused, unless a new constraint couples faces that `S` does not
/// (a P1 divergence at a point mixes three vertex one-rings); then the pattern grows and one new
/// symbolic analysis is done.
///
/// Factorizations and solves run on one thread or on all of them, chosen per system by a
/// [`FactorParallelism`] policy (default: one thread below [`crate::SEQUENTIAL_FLOP_LIMIT`]
/// flops, where faer's parallel factorization is slower).
#[derive(Debug)]
pub struct FullSoftDesign {
    dirichlet: CsMat<f64>,
    mass: Vec<f64>,
    omega: f64,
    base: CsMat<f64>,
    top: CsMat<f64>,
    factor: SparseLdlt,
    ordering: FillOrdering,
    parallelism: FactorParallelism,
    constraints: Vec<CompiledConstraint>,
    symbolic_analyses: usize,
    timings: FactorTimings,
}

impl FullSoftDesign {
    /// Assembles `S` and `M1` of `complex` and factors the system for `constraints`, ordered by
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
    /// of the factorizations chosen by the caller.
    pub fn of_complex<H: HodgeComplex + ?Sized>(
        complex: &H,
        options: SoftOptions,
        constraints: Vec<CompiledConstraint>,
        ordering: FillOrdering,
        parallelism: FactorParallelism,
    ) -> Result<Self, DesignError> {
        let (Some(dirichlet), Some(mass)) = (
            complex.dirichlet_energy().as_sparse(),
            complex.m1().diagonal_values(),
        ) else {
            return Err(DesignError::NotSparse {
                what: "the full soft design",
            });
        };
        Self::from_matrices_with(dirichlet, mass, options, constraints, ordering, parallelism)
    }

    /// The same from the Dirichlet energy `S` (`2F × 2F`, integrated, symmetric) and the diagonal
    /// of `M_X`, ordered by [`DEFAULT_FULL_ORDERING`].
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
        check_options(options)?;
        let n = dirichlet.rows();
        if mass.len() != n {
            return Err(DesignError::DimensionMismatch {
                what: "mass (must match S)",
                expected: n,
                actual: mass.len(),
            });
        }
        check_columns(&constraints, n)?;
        let dirichlet = if dirichlet.is_csr() {
            dirichlet.clone()
        } else {
            dirichlet.to_csr()
        };
        let screened: Vec<f64> = mass.iter().map(|m| options.regularization * m).collect();
        let base = linear_combination(1.0, &dirichlet, 1.0, &diagonal(&screened));
        let base = grow_pattern(&base, &constraints);
        let top = add_constraints(&base, &constraints);
        let augmented = augmented_upper(&top, &dirichlet, options.omega, mass)?;
        let assembled = Instant::now();
        let factor = factor_augmented(&augmented, n, ordering, parallelism)?;
        let timings = FactorTimings {
            assembly: assembled - start,
            factorization: assembled.elapsed(),
            symbolic: true,
        };
        Ok(Self {
            dirichlet,
            mass: mass.to_vec(),
            omega: options.omega,
            base,
            top,
            factor,
            ordering,
            parallelism,
            constraints,
            symbolic_analyses: 1,
            timings,
        })
    }

    /// Replaces the constraints and refactors (numerically only when the pattern holds them).
    /// Returns whether the symbolic analysis was reused.
    pub fn set_constraints(
        &mut self,
        constraints: Vec<CompiledConstraint>,
    ) -> Result<bool, DesignError> {
        let start = Instant::now();
        check_columns(&constraints, self.base.rows())?;
        let fits = constraint_gram_entries(&constraints)
            .iter()
            .all(|&(i, j, _)| position(&self.base, i, j).is_some());
        let assembled;
        if fits {
            let top = add_constraints(&self.base, &constraints);
            let augmented = augmented_upper(&top, &self.dirichlet, self.omega, &self.mass)?;
            assembled = Instant::now();
            self.factor.refactor(augmented.as_ref())?;
            check_inertia(&self.factor)?;
            self.top = top;
        } else {
            let base = grow_pattern(&self.base, &constraints);
            let top = add_constraints(&base, &constraints);
            let augmented = augmented_upper(&top, &self.dirichlet, self.omega, &self.mass)?;
            assembled = Instant::now();
            self.factor = factor_augmented(
                &augmented,
                self.base.rows(),
                self.ordering,
                self.parallelism,
            )?;
            self.base = base;
            self.top = top;
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
        self.ordering
    }

    /// Whether the factorizations and solves run on all threads (`false`: one thread), as
    /// chosen by the [`FactorParallelism`] policy for this system.
    pub fn is_parallel(&self) -> bool {
        self.factor.parallelism() != Par::Seq
    }

    /// Stored entries of the factor `L` of the augmented system (a measure of fill-in).
    pub fn factor_entries(&self) -> usize {
        self.factor.factor_len()
    }

    /// Floating-point operations of one numeric factorization of the augmented system
    /// (`Σ_j c_j²` over the columns of `L`): the machine-independent cost of the ordering.
    pub fn factor_flop_count(&self) -> f64 {
        self.factor.factor_flop_count()
    }

    /// The active constraints.
    pub fn constraints(&self) -> &[CompiledConstraint] {
        &self.constraints
    }

    /// The right-hand side `C̃ᵀ W c` (`2F` values, integrated units of the constraints).
    pub fn right_hand_side(&self) -> Vec<f64> {
        let mut b = vec![0.0; self.base.rows()];
        for c in &self.constraints {
            for (row, value) in c.rows.iter().zip(&c.values) {
                for &(j, a) in row {
                    b[j] += c.weight * a * value;
                }
            }
        }
        b
    }

    /// `A x = (S + εM_X + C̃ᵀWC̃) x + ω S M_X⁻¹ S x` (`2F` values), without forming `B`.
    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        let mut y = mul_vec(&self.top, x);
        if self.omega > 0.0 {
            let sx: Vec<f64> = mul_vec(&self.dirichlet, x)
                .iter()
                .zip(&self.mass)
                .map(|(v, m)| v / m)
                .collect();
            for (yi, v) in y.iter_mut().zip(mul_vec(&self.dirichlet, &sx)) {
                *yi += self.omega * v;
            }
        }
        y
    }

    /// `b − A x` evaluated in double-double arithmetic (see [`crate::SolveReport`]): `S x`,
    /// `M_X⁻¹ S x` and `S M_X⁻¹ S x` are carried with their rounding errors, so the residual is
    /// accurate even where `ω S M_X⁻¹ S` cancels heavily (slivers).
    pub fn accurate_residual(&self, x: &[f64], b: &[f64]) -> Vec<f64> {
        let x_exact = exact(x);
        let mut r: Vec<DoubleDouble> = symmetric_product(&self.top, &x_exact)
            .into_iter()
            .zip(b)
            .map(|(t, &bi)| DoubleDouble::difference(bi, t))
            .collect();
        if self.omega > 0.0 {
            let scaled: Vec<DoubleDouble> = symmetric_product(&self.dirichlet, &x_exact)
                .into_iter()
                .zip(&self.mass)
                .map(|(v, &m)| v.divide(m))
                .collect();
            for (ri, v) in r
                .iter_mut()
                .zip(symmetric_product(&self.dirichlet, &scaled))
            {
                ri.add_product(-self.omega, v);
            }
        }
        r.into_iter().map(|v| v.hi + v.lo).collect()
    }

    /// Solves for the field `x` (`2F` values) with iterative refinement until the relative
    /// residual `‖b − A x‖/‖b‖` (computed in double-double) is below 1e-12 or stops decreasing,
    /// and reports its history.
    pub fn solve(&self) -> (Vec<f64>, SolveReport) {
        let b = self.right_hand_side();
        let n = b.len();
        refined_solve(
            |x| self.apply(x),
            |x| self.accurate_residual(x, &b),
            &b,
            |r| {
                let mut rhs = Mat::from_fn(2 * n, 1, |i, _| if i < n { r[i] } else { 0.0 });
                self.factor.solve_in_place(rhs.as_mut());
                (0..n).map(|i| rhs[(i, 0)]).collect()
            },
        )
    }
}

/// Upper triangle (CSC, sorted rows) of the augmented matrix `[[top, √ω S], [√ω S, −M]]`
/// (`2n × 2n` for `n = 2F`); its pattern depends only on the patterns of `top` and `S`.
///
/// Built column by column without a transpose: column `c < n` of the upper triangle of the
/// symmetric `top` is its row `c` up to the diagonal, and column `n + i` is `√ω` times row `i` of
/// the symmetric `S` followed by the diagonal `−M_i`.
fn augmented_upper(
    top: &CsMat<f64>,
    dirichlet: &CsMat<f64>,
    omega: f64,
    mass: &[f64],
) -> Result<SparseColMat<usize, f64>, DesignError> {
    let n = top.rows();
    let root = omega.sqrt();
    let capacity = top.nnz() / 2 + n + dirichlet.nnz() + n;
    let mut col_ptr = Vec::with_capacity(2 * n + 1);
    let mut row_idx = Vec::with_capacity(capacity);
    let mut values = Vec::with_capacity(capacity);
    col_ptr.push(0);
    for c in 0..n {
        if let Some(row) = top.outer_view(c) {
            for (r, &v) in row.iter().take_while(|(r, _)| *r <= c) {
                row_idx.push(r);
                values.push(v);
            }
        }
        col_ptr.push(row_idx.len());
    }
    for (i, m) in mass.iter().enumerate() {
        if let Some(row) = dirichlet.outer_view(i) {
            for (r, &v) in row.iter() {
                row_idx.push(r);
                values.push(root * v);
            }
        }
        row_idx.push(n + i);
        values.push(-m);
        col_ptr.push(row_idx.len());
    }
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        let col = col_ptr.partition_point(|&p| p <= k) - 1;
        return Err(DesignError::Solver(SolverError::NonFinite {
            context: "soft-design system",
            row: row_idx[k],
            col,
            value: values[k],
        }));
    }
    let symbolic = SymbolicSparseColMat::new_checked(2 * n, 2 * n, col_ptr, None, row_idx);
    Ok(SparseColMat::new(symbolic, values))
}

/// Factors the augmented matrix. Nested dissection orders the **faces**: the quotient graph of
/// the augmented matrix under unknown ↦ face (`x_2t, x_2t+1` live in face `t` and so do their
/// auxiliaries `y_i` = unknown `n + i`; it is the face graph of `S` plus the constraints), and
/// eliminates each face's four unknowns `x_2t, x_2t+1, y_2t, y_2t+1` together. A face separator,
/// with all four unknowns of its faces, separates the augmented graph (`y_i` couples only to
/// `x_j` with `S_ij ≠ 0`), so this is a nested dissection of the augmented system computed on a
/// graph with a quarter of its vertices. Measured against METIS on the `2F` graph of `x` (each
/// `y_i` right after its `x_i`): 16 % more flops on bunny-closed, but ordering plus symbolic
/// analysis took 2.1 s instead of 6.5 s on bumpy-torus-x4, which wins from bunny size up.
fn factor_augmented(
    augmented: &SparseColMat<usize, f64>,
    n: usize,
    ordering: FillOrdering,
    parallelism: FactorParallelism,
) -> Result<SparseLdlt, DesignError> {
    let choose = |flops| parallelism.choose(flops);
    let factor = match ordering {
        FillOrdering::Amd => {
            SparseLdlt::with_ordering_and_parallelism(augmented.as_ref(), ordering, choose)?
        }
        FillOrdering::NestedDissection => {
            let faces = n.div_ceil(2);
            let face_of: Vec<usize> = (0..2 * n).map(|i| (i % n) / 2).collect();
            let permutation: Vec<usize> =
                nested_dissection_of_groups(augmented.symbolic(), &face_of, faces)?
                    .into_iter()
                    .flat_map(|t| {
                        let unknowns = 2 * t..(2 * t + 2).min(n);
                        unknowns.clone().chain(unknowns.map(|i| n + i))
                    })
                    .collect();
            SparseLdlt::with_permutation_and_parallelism(augmented.as_ref(), &permutation, choose)?
        }
    };
    check_inertia(&factor)?;
    Ok(factor)
}

/// The augmented matrix must have `2F` positive and `2F` negative pivots (quasi-definite);
/// otherwise the top-left block was not positive definite.
fn check_inertia(factor: &SparseLdlt) -> Result<(), DesignError> {
    let inertia = factor.inertia();
    let half = factor.dimension() / 2;
    if inertia.positive == half && inertia.negative == half {
        Ok(())
    } else {
        Err(DesignError::Solver(SolverError::Factorization(format!(
            "the soft-design system is not positive definite (inertia {} positive, {} negative, {} zero pivots);              use a positive regularization",
            inertia.positive, inertia.negative, inertia.zero
        ))))
    }
}

fn check_options(options: SoftOptions) -> Result<(), DesignError> {
    for (what, value) in [
        ("omega", options.omega),
        ("regularization", options.regularization),
    ] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(DesignError::BadParameter { what, value });
        }
    }
    Ok(())
}

fn check_columns(constraints: &[CompiledConstraint], n: usize) -> Result<(), DesignError> {
    match constraints
        .iter()
        .flat_map(|c| c.rows.iter().flatten())
        .find(|(j, _)| *j >= n)
    {
        Some(&(j, _)) => Err(DesignError::DimensionMismatch {
            what: "constraint row column (must be < 2F)",
            expected: n,
            actual: j,
        }),
        None => Ok(()),
    }
}

/// `base` with its pattern extended by every `C̃ᵀC̃` entry of `constraints` it lacks.
fn grow_pattern(base: &CsMat<f64>, constraints: &[CompiledConstraint]) -> CsMat<f64> {
    let extra: Vec<(usize, usize)> = constraint_gram_entries(constraints)
        .into_iter()
        .filter(|&(i, j, _)| position(base, i, j).is_none())
        .map(|(i, j, _)| (i, j))
        .collect();
    if extra.is_empty() {
        base.clone()
    } else {
        with_extra_entries(base, &extra)
    }
}

/// `base + C̃ᵀ W C̃`, with exactly `base`'s pattern (which must hold every entry).
fn add_constraints(base: &CsMat<f64>, constraints: &[CompiledConstraint]) -> CsMat<f64> {
    let mut system = base.clone();
    for (i, j, v) in constraint_gram_entries(constraints) {
        if let Some(p) = position(base, i, j) {
            system.data_mut()[p] += v;
        }
    }
    system
}
