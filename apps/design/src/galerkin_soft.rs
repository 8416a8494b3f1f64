//! [`GalerkinSoftSystem`]: the full soft design of a complex whose masses are not all diagonal,
//! `(S + ωB + εM1 + C̃ᵀWC̃) x = C̃ᵀWc` on the free field nodes, through the augmented system of
//! [`crate::augmented_system`] and refined on the exact operator.

use crate::augmented_system::{assemble, AugmentedFactor, ConstraintTerms, PatternUnion};
use crate::constraint::{CompiledConstraint, RowOrigin, SparseRow};
use crate::error::DesignError;
use crate::galerkin_blocks::{AuxKind, EnergyWeights, GalerkinBlocks};
use crate::regularization::mean_eigenvalue;
use crate::soft_options::SoftOptions;
use crate::soft_system::{Factoring, SoftSystem};
use std::time::Instant;
use tvf_core::discretization::HodgeComplex;
use tvf_solvers::iterative_refinement::{exact, refined_solve, DoubleDouble, SolveReport};
use tvf_solvers::SparseLdlt;

/// The soft-design energy of a complex with non-diagonal masses and its factored augmented
/// system. Vectors of the internal methods are over the free field nodes (`n1f` values); the
/// crate-visible ones take and return `n1` values (zero on fixed field nodes).
#[derive(Debug)]
pub(crate) struct GalerkinSoftSystem {
    blocks: GalerkinBlocks,
    weights: EnergyWeights,
    /// The weights of the factored system: `weights` with the screening raised to
    /// [`FACTORED_SCREENING`] where the field block lacks a term of `S`.
    factored: EnergyWeights,
    factor: AugmentedFactor,
    union: PatternUnion,
    /// Every constraint row over the free field nodes with its weight, for applying `C̃ᵀWC̃`.
    rows: Vec<(SparseRow, f64)>,
}

/// Relative weight (of the mean eigenvalue `λ̄` of the Hodge–Laplacian) of the screening `τ M1`
/// the factored system uses at least when a term of `S` goes through auxiliary unknowns
/// (`M0⁻¹` or `M2` dense): the field block `τ M1 + C̃ᵀWC̃ + S_d` then lacks that term, is
/// singular up to `τ M1` on the gradients (or on the co-gradients), and a factorization without
/// pivoting meets pivots of that size. With the default `ε = 1e-10 λ̄` as the screening, the
/// refined solve of `tvf design --full` on a whitney-galerkin torus of 6,144 triangles at
/// `ω = 100` stalled at a relative residual of 4.8e-2; with `1e-6 λ̄` the direct solve's is
/// 1.3e-5 and five steps reach the rounding floor (2e-10; `1e-8 λ̄`: nine steps, `1e-4 λ̄`:
/// eight). The factored
/// system is then `A + (τ − ε) M1`, which differs from `A` relatively only on the fields of
/// eigenvalue near or below `τ` (the harmonic ones), and the refinement on `A` removes the shift.
const FACTORED_SCREENING: f64 = 1e-6;

/// The weights of the factored system for the energy `weights` (see [`FACTORED_SCREENING`]).
fn factored_weights<H: HodgeComplex + ?Sized>(
    complex: &H,
    blocks: &GalerkinBlocks,
    weights: EnergyWeights,
) -> EnergyWeights {
    if blocks.aux.is_empty() {
        return weights;
    }
    EnergyWeights {
        screening: weights
            .screening
            .max(FACTORED_SCREENING * mean_eigenvalue(complex)),
        ..weights
    }
}

impl GalerkinSoftSystem {
    /// Assembles and factors the system of `complex` for `constraints` (options and columns
    /// checked by the caller); returns it and the time its assembly ended.
    pub(crate) fn new<H: HodgeComplex + ?Sized>(
        complex: &H,
        options: SoftOptions,
        constraints: &[CompiledConstraint],
        factoring: Factoring,
    ) -> Result<(Self, Instant), DesignError> {
        let blocks = GalerkinBlocks::new(complex);
        let weights = EnergyWeights {
            screening: options.regularization,
            dirichlet: 1.0,
            biharmonic: options.omega,
        };
        let factored = factored_weights(complex, &blocks, weights);
        let terms = constraint_terms(&blocks, constraints);
        let mut union = PatternUnion::default();
        union.include(&terms);
        let (upper, layout) = assemble(&blocks, factored, &terms, &union)?;
        let assembled = Instant::now();
        let factor = AugmentedFactor::new(&upper, layout, &blocks, factoring)?;
        let rows = field_rows(&blocks, constraints);
        Ok((
            Self {
                blocks,
                weights,
                factored,
                factor,
                union,
                rows,
            },
            assembled,
        ))
    }

    /// `A x` on the free field nodes (`n1f` values in and out).
    fn apply_free(&self, x: &[f64]) -> Vec<f64> {
        let mut y = self.blocks.energy(self.weights, x);
        for (row, w) in &self.rows {
            let value: f64 = row.iter().map(|&(j, a)| a * x[j]).sum();
            for &(j, a) in row {
                y[j] += w * a * value;
            }
        }
        y
    }

    /// `b − A x` in double-double on the free field nodes (`n1f` values in and out).
    fn residual_free(&self, x: &[f64], b: &[f64]) -> Vec<f64> {
        let x = exact(x);
        let mut r: Vec<DoubleDouble> = self
            .blocks
            .accurate_energy(self.weights, &x)
            .into_iter()
            .zip(b)
            .map(|(ax, &bi)| DoubleDouble::difference(bi, ax))
            .collect();
        for (row, w) in &self.rows {
            let mut value = DoubleDouble::default();
            for &(j, a) in row {
                value.add_product(a, x[j]);
            }
            for &(j, a) in row {
                r[j].add_product(-w * a, value);
            }
        }
        r.into_iter().map(|v| v.hi + v.lo).collect()
    }
}

impl SoftSystem for GalerkinSoftSystem {
    fn factor(&self) -> &SparseLdlt {
        self.factor.ldlt()
    }

    fn field_dimension(&self) -> usize {
        self.blocks.field.space_len()
    }

    fn set_constraints(
        &mut self,
        constraints: &[CompiledConstraint],
        factoring: Factoring,
    ) -> Result<(bool, Instant), DesignError> {
        let terms = constraint_terms(&self.blocks, constraints);
        self.union.include(&terms);
        let (upper, layout) = assemble(&self.blocks, self.factored, &terms, &self.union)?;
        let assembled = Instant::now();
        let reused = self.factor.refactor(&upper, &layout)?;
        if !reused {
            self.factor = AugmentedFactor::new(&upper, layout, &self.blocks, factoring)?;
        }
        self.rows = field_rows(&self.blocks, constraints);
        Ok((reused, assembled))
    }

    fn apply(&self, x: &[f64]) -> Vec<f64> {
        let field = &self.blocks.field;
        field.scatter(&self.apply_free(&field.gather(x)))
    }

    fn accurate_residual(&self, x: &[f64], b: &[f64]) -> Vec<f64> {
        let field = &self.blocks.field;
        field.scatter(&self.residual_free(&field.gather(x), &field.gather(b)))
    }

    /// Solves on the free field nodes (the entries of `b` on fixed ones are dropped: the field
    /// is zero there).
    fn solve(&self, b: &[f64]) -> (Vec<f64>, SolveReport) {
        let field = &self.blocks.field;
        let b = field.gather(b);
        let (x, report) = refined_solve(
            |x| self.apply_free(x),
            |x| self.residual_free(x, &b),
            &b,
            |r| self.factor.solve_field(r),
        );
        (field.scatter(&x), report)
    }
}

/// Every constraint row restricted to the free field nodes, with its weight.
fn field_rows(
    blocks: &GalerkinBlocks,
    constraints: &[CompiledConstraint],
) -> Vec<(SparseRow, f64)> {
    constraints
        .iter()
        .flat_map(|c| {
            c.rows
                .iter()
                .map(move |row| (blocks.field.restrict_row(row), c.weight))
        })
        .collect()
}

/// The constraint terms of the augmented system: a divergence or curl of a space with auxiliary
/// unknowns on them ([`RowOrigin::Potential`], [`RowOrigin::CoPotential`]), a row of a composed
/// operator ([`RowOrigin::Composed`]) as a dense row, every other row (sparse over the field) in
/// the field block. A row without an origin counts as [`RowOrigin::Field`].
fn constraint_terms(
    blocks: &GalerkinBlocks,
    constraints: &[CompiledConstraint],
) -> ConstraintTerms {
    let mut terms = ConstraintTerms {
        aux: vec![Vec::new(); blocks.aux.len()],
        ..ConstraintTerms::default()
    };
    let aux_of = |kind: AuxKind| blocks.aux.iter().position(|space| space.kind == kind);
    for c in constraints {
        for (k, row) in c.rows.iter().enumerate() {
            let nodal = match c.origins.get(k) {
                Some(RowOrigin::Potential(a)) => aux_of(AuxKind::Potential).map(|s| (s, a)),
                Some(RowOrigin::CoPotential(a)) => aux_of(AuxKind::CoPotential).map(|s| (s, a)),
                _ => None,
            };
            match (nodal, c.origins.get(k)) {
                (Some((space, a)), _) => {
                    let a = blocks.aux[space].nodes.restrict_row(a);
                    gram(&mut terms.aux[space], &a, c.weight);
                }
                (None, Some(RowOrigin::Composed)) => {
                    terms.dense.push((blocks.field.restrict_row(row), c.weight))
                }
                (None, _) => gram(&mut terms.field, &blocks.field.restrict_row(row), c.weight),
            }
        }
    }
    terms
}

/// Appends `w a aᵀ` (both triangles).
fn gram(entries: &mut Vec<(usize, usize, f64)>, a: &[(usize, f64)], w: f64) {
    for &(i, ai) in a {
        for &(j, aj) in a {
            entries.push((i, j, w * ai * aj));
        }
    }
}
