//! [`FullSoftDesign`]: Fisher et al. (2007) soft-constrained design at full resolution,
//! `(S + ωB + εM_X + C̃ᵀ W C̃) x = C̃ᵀ W c`, with a sparse Cholesky and iterative refinement.

use crate::constraint::CompiledConstraint;
use crate::error::DesignError;
use crate::sparse_pattern::{constraint_gram_entries, position, with_extra_entries};
use sprs::CsMat;
use tvf_core::discretization::sparse::{diagonal, linear_combination, mul_vec};
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_solvers::SparseCholesky;

/// Stop refining once the relative residual is below this.
const REFINEMENT_TARGET: f64 = 1e-12;
/// At most this many refinement steps.
const MAX_REFINEMENT_STEPS: usize = 20;

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

/// `ε = 1e-10 · tr(M_X⁻¹ S) / 2F`: ten orders of magnitude below the mean eigenvalue of the
/// Hodge–Laplacian, so it only matters on (near-)kernel directions left free by the constraints.
pub fn default_regularization(dirichlet: &CsMat<f64>, mass: &[f64]) -> f64 {
    let trace: f64 = (0..dirichlet.rows())
        .map(|i| dirichlet.get(i, i).copied().unwrap_or(0.0) / mass[i].max(f64::MIN_POSITIVE))
        .sum();
    1e-10 * trace / dirichlet.rows().max(1) as f64
}

/// What a full solve did: the relative residual `‖b − A x‖₂ / ‖b‖₂` after the direct solve and
/// after every refinement step (`x ← x + A⁻¹(b − A x)`, with the same factorization).
#[derive(Debug, Clone, PartialEq)]
pub struct SolveReport {
    /// Residual history; the last entry is the residual of the returned field.
    pub residuals: Vec<f64>,
}

impl SolveReport {
    /// Relative residual of the returned field.
    pub fn final_residual(&self) -> f64 {
        self.residuals.last().copied().unwrap_or(0.0)
    }
}

/// The full soft-design system and its sparse Cholesky factorization.
///
/// The matrix keeps the **union** of the patterns of `S + ωB` and of every `C̃ᵀC̃` it has seen
/// (as explicit zeros where a constraint left), so changing the constraints refactors
/// numerically with the symbolic analysis (AMD ordering, supernodes) reused, unless a new
/// constraint couples entries outside the pattern; then the pattern grows and one new symbolic
/// analysis is done. With `ω > 0` the pattern of `B` already holds every `C̃ᵀC̃` block of
/// vector, vertex, edge and point constraints, so this happens only for `ω = 0` (and there only
/// for point constraints whose nodes' supports do not share a vertex: S couples faces that do).
#[derive(Debug)]
pub struct FullSoftDesign {
    base: CsMat<f64>,
    system: CsMat<f64>,
    factor: SparseCholesky,
    constraints: Vec<CompiledConstraint>,
    symbolic_analyses: usize,
}

impl FullSoftDesign {
    /// Assembles `S`, `B` and `M_X` of `complex` and factors the system for `constraints`.
    pub fn new<H: HodgeComplex>(
        complex: &H,
        options: SoftOptions,
        constraints: Vec<CompiledConstraint>,
    ) -> Result<Self, DesignError> {
        Self::from_matrices(
            &complex.dirichlet_energy(),
            &complex.biharmonic_energy(),
            complex.m1(),
            options,
            constraints,
        )
    }

    /// The same from the matrices: Dirichlet energy `S` and biharmonic energy `B` (`2F × 2F`,
    /// integrated, symmetric) and the diagonal of `M_X`.
    pub fn from_matrices(
        dirichlet: &CsMat<f64>,
        biharmonic: &CsMat<f64>,
        mass: &[f64],
        options: SoftOptions,
        constraints: Vec<CompiledConstraint>,
    ) -> Result<Self, DesignError> {
        check_options(options)?;
        let n = dirichlet.rows();
        if biharmonic.rows() != n || mass.len() != n {
            return Err(DesignError::DimensionMismatch {
                what: "biharmonic energy / mass (must match S)",
                expected: n,
                actual: if biharmonic.rows() != n { biharmonic.rows() } else { mass.len() },
            });
        }
        check_columns(&constraints, n)?;
        let energy = linear_combination(1.0, dirichlet, options.omega, biharmonic);
        let screened: Vec<f64> = mass.iter().map(|m| options.regularization * m).collect();
        let base = linear_combination(1.0, &energy, 1.0, &diagonal(&screened));
        let base = grow_pattern(&base, &constraints);
        let system = add_constraints(&base, &constraints);
        let factor = SparseCholesky::new(&system)?;
        Ok(Self {
            base,
            system,
            factor,
            constraints,
            symbolic_analyses: 1,
        })
    }

    /// Replaces the constraints and refactors (numerically only when the pattern holds them).
    /// Returns whether the symbolic analysis was reused.
    pub fn set_constraints(&mut self, constraints: Vec<CompiledConstraint>) -> Result<bool, DesignError> {
        check_columns(&constraints, self.base.rows())?;
        let fits = constraint_gram_entries(&constraints)
            .iter()
            .all(|&(i, j, _)| position(&self.base, i, j).is_some());
        if fits {
            let system = add_constraints(&self.base, &constraints);
            self.factor.refactor(&system)?;
            self.system = system;
        } else {
            let base = grow_pattern(&self.base, &constraints);
            let system = add_constraints(&base, &constraints);
            self.factor = SparseCholesky::new(&system)?;
            self.base = base;
            self.system = system;
            self.symbolic_analyses += 1;
        }
        self.constraints = constraints;
        Ok(fits)
    }

    /// How many symbolic analyses were done so far (1 after construction).
    pub fn symbolic_analyses(&self) -> usize {
        self.symbolic_analyses
    }

    /// The current system matrix `S + ωB + εM_X + C̃ᵀ W C̃` (`2F × 2F`, CSR, both triangles).
    pub fn system(&self) -> &CsMat<f64> {
        &self.system
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

    /// Solves for the field `x` (`2F` values) with iterative refinement until the relative
    /// residual is below 1e-12 (or stops decreasing), and reports the residual history.
    pub fn solve(&self) -> (Vec<f64>, SolveReport) {
        let b = self.right_hand_side();
        refined_solve(&self.system, &b, |r| self.factor.solve(r))
    }
}

/// `x = A⁻¹ b` by a direct solve followed by iterative refinement with the same factorization.
pub(crate) fn refined_solve(
    matrix: &CsMat<f64>,
    b: &[f64],
    solve: impl Fn(&[f64]) -> Vec<f64>,
) -> (Vec<f64>, SolveReport) {
    let norm_b = b.iter().map(|x| x * x).sum::<f64>().sqrt();
    if norm_b == 0.0 {
        return (vec![0.0; b.len()], SolveReport { residuals: vec![0.0] });
    }
    let residual = |x: &[f64]| -> (Vec<f64>, f64) {
        let ax = mul_vec(matrix, x);
        let r: Vec<f64> = b.iter().zip(&ax).map(|(bi, ai)| bi - ai).collect();
        let norm = r.iter().map(|v| v * v).sum::<f64>().sqrt() / norm_b;
        (r, norm)
    };
    let mut x = solve(b);
    let (mut r, mut norm) = residual(&x);
    let mut residuals = vec![norm];
    for _ in 0..MAX_REFINEMENT_STEPS {
        if norm <= REFINEMENT_TARGET || !norm.is_finite() {
            break;
        }
        let dx = solve(&r);
        let candidate: Vec<f64> = x.iter().zip(&dx).map(|(a, d)| a + d).collect();
        let (r_new, norm_new) = residual(&candidate);
        if !(norm_new < 0.5 * norm) {
            break;
        }
        x = candidate;
        r = r_new;
        norm = norm_new;
        residuals.push(norm);
    }
    (x, SolveReport { residuals })
}

fn check_options(options: SoftOptions) -> Result<(), DesignError> {
    for (what, value) in [("omega", options.omega), ("regularization", options.regularization)] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(DesignError::BadParameter { what, value });
        }
    }
    Ok(())
}

fn check_columns(constraints: &[CompiledConstraint], n: usize) -> Result<(), DesignError> {
    match constraints.iter().flat_map(|c| c.rows.iter().flatten()).find(|(j, _)| *j >= n) {
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
