//! [`DiagonalSoftSystem`]: the full soft-design system of a complex whose Dirichlet energy `S` is
//! a sparse matrix and whose field mass `M1` is diagonal (lumped masses, DEC's Hodge stars),
//! factored through the quasi-definite augmented system `[[S + εM1 + C̃ᵀWC̃, √ω S], [√ω S, −M1]]`.

use crate::constraint::constraint_gram_entries;
use crate::constraint::CompiledConstraint;
use crate::error::DesignError;
use crate::soft_options::SoftOptions;
use crate::soft_system::{Factoring, SoftSystem};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::Mat;
use sprs::CsMat;
use std::time::Instant;
use tvf_core::discretization::sparse::{as_csr, diagonal, linear_combination, mul_vec};
use tvf_solvers::iterative_refinement::{
    exact, refined_solve, symmetric_product, DoubleDouble, SolveReport,
};
use tvf_solvers::ordering::nested_dissection_of_groups;
use tvf_solvers::sparse_pattern::{position, with_extra_entries};
use tvf_solvers::{FillOrdering, SolverError, SparseLdlt};

/// The augmented system of a sparse `S` and a diagonal `M1` (see [`crate::FullSoftDesign`]):
/// `S` and `M1`'s diagonal, the top-left block `S + εM1` with the union pattern of every
/// `C̃ᵀC̃` seen (`base`) and with the current constraints added (`top`), and the factor.
#[derive(Debug)]
pub(crate) struct DiagonalSoftSystem {
    dirichlet: CsMat<f64>,
    mass: Vec<f64>,
    omega: f64,
    base: CsMat<f64>,
    top: CsMat<f64>,
    factor: SparseLdlt,
}

impl DiagonalSoftSystem {
    /// Assembles and factors the system of `S` (`n1 × n1`, symmetric; `mass.len() == n1`,
    /// checked by the caller along with the options and the constraint columns); returns it
    /// and the time its assembly ended.
    pub(crate) fn new(
        dirichlet: &CsMat<f64>,
        mass: &[f64],
        options: SoftOptions,
        constraints: &[CompiledConstraint],
        factoring: Factoring,
    ) -> Result<(Self, Instant), DesignError> {
        let n = dirichlet.rows();
        let dirichlet = as_csr(dirichlet);
        let screened: Vec<f64> = mass.iter().map(|m| options.regularization * m).collect();
        let base = linear_combination(1.0, &dirichlet, 1.0, &diagonal(&screened));
        let base = grow_pattern(&base, constraints);
        let top = add_constraints(&base, constraints);
        let augmented = augmented_upper(&top, &dirichlet, options.omega, mass)?;
        let assembled = Instant::now();
        let factor = factor_augmented(&augmented, n, factoring)?;
        Ok((
            Self {
                dirichlet: dirichlet.into_owned(),
                mass: mass.to_vec(),
                omega: options.omega,
                base,
                top,
                factor,
            },
            assembled,
        ))
    }

    /// `A⁻¹ r` through the factor: the `x` part of the augmented solve with right-hand side
    /// `(r, 0)`.
    fn solve_field(&self, r: &[f64]) -> Vec<f64> {
        let n = r.len();
        let mut rhs = Mat::from_fn(2 * n, 1, |i, _| if i < n { r[i] } else { 0.0 });
        self.factor.solve_in_place(rhs.as_mut());
        (0..n).map(|i| rhs[(i, 0)]).collect()
    }
}

impl SoftSystem for DiagonalSoftSystem {
    fn factor(&self) -> &SparseLdlt {
        &self.factor
    }

    fn field_dimension(&self) -> usize {
        self.base.rows()
    }

    fn set_constraints(
        &mut self,
        constraints: &[CompiledConstraint],
        factoring: Factoring,
    ) -> Result<(bool, Instant), DesignError> {
        let fits = constraint_gram_entries(constraints)
            .iter()
            .all(|&(i, j, _)| position(&self.base, i, j).is_some());
        let assembled;
        if fits {
            let top = add_constraints(&self.base, constraints);
            let augmented = augmented_upper(&top, &self.dirichlet, self.omega, &self.mass)?;
            assembled = Instant::now();
            self.factor.refactor(augmented.as_ref())?;
            check_inertia(&self.factor)?;
            self.top = top;
        } else {
            let base = grow_pattern(&self.base, constraints);
            let top = add_constraints(&base, constraints);
            let augmented = augmented_upper(&top, &self.dirichlet, self.omega, &self.mass)?;
            assembled = Instant::now();
            self.factor = factor_augmented(&augmented, self.base.rows(), factoring)?;
            self.base = base;
            self.top = top;
        }
        Ok((fits, assembled))
    }

    /// `(S + εM1 + C̃ᵀWC̃) x + ω S M1⁻¹ S x`: `top` times `x` plus two sparse products and a
    /// diagonal solve.
    fn apply(&self, x: &[f64]) -> Vec<f64> {
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

    fn accurate_residual(&self, x: &[f64], b: &[f64]) -> Vec<f64> {
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

    fn solve(&self, b: &[f64]) -> (Vec<f64>, SolveReport) {
        refined_solve(
            |x| self.apply(x),
            |x| self.accurate_residual(x, b),
            b,
            |r| self.solve_field(r),
        )
    }
}

/// Upper triangle (CSC, sorted rows) of the augmented matrix `[[top, √ω S], [√ω S, −M]]`
/// (`2n × 2n` for `n = n1`); its pattern depends only on the patterns of `top` and `S`.
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
/// graph with a quarter of its vertices. Against METIS on the `2F` graph of `x` (each `y_i`
/// right after its `x_i`) it costs somewhat more flops but a much faster ordering and symbolic
/// analysis, which wins from bunny size up (numbers in `docs/performance.md`).
fn factor_augmented(
    augmented: &SparseColMat<usize, f64>,
    n: usize,
    factoring: Factoring,
) -> Result<SparseLdlt, DesignError> {
    let choose = |flops| factoring.parallelism.choose(flops);
    let factor = match factoring.ordering {
        FillOrdering::Amd => SparseLdlt::with_ordering_and_parallelism(
            augmented.as_ref(),
            factoring.ordering,
            choose,
        )?,
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

/// The augmented matrix must have `n1` positive and `n1` negative pivots (quasi-definite);
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
