//! [`SplineSession`]: tangential vector field splines with hard constraints in a reduced basis
//! (Section 7), as an editing session.

use crate::constraint::CompiledConstraint;
use crate::error::DesignError;
use crate::reduced_basis::{dot, ReducedBasis};
use tvf_solvers::DenseCholesky;

/// Threshold on the relative pivot `(γ − |l|²)/γ` below which an appended constraint row
/// counts as linearly dependent on the active ones.
pub const DEFAULT_DEPENDENCY_TOLERANCE: f64 = 1e-10;

/// One active constraint: its rows, reduced rows and values.
#[derive(Debug, Clone)]
struct Active {
    id: String,
    compiled: CompiledConstraint,
    /// `C = C̃ U`: one `d`-vector per row.
    reduced: Vec<Vec<f64>>,
}

/// Residual of one constraint (serialized with the keys of its fields).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ConstraintResidual {
    /// Constraint id.
    pub id: String,
    /// `‖rows · x − values‖₂` (units of the values).
    pub absolute: f64,
    /// `absolute / max(‖values‖₂, ‖|rows|·|x|‖₂)`: relative to the size of the prescribed values
    /// or of the terms of `rows · x`, whichever is larger (so a zero value still has a scale).
    pub relative: f64,
}

/// An editing session for the tangential vector field spline
///
/// `min E_B(x) + ω E_D(x)  s.t.  C̃ x = c`, restricted to `x = U v`:
/// `min vᵀ D v` with `D = Λ² + ωΛ` (harmonic eigenvalues replaced by a tenth of the lowest
/// non-zero one), `C v = c` with `C = C̃ U`. The Schur complement `K = C D⁻¹ Cᵀ` (`n_c × n_c`) is
/// kept as a dense Cholesky factor ([`tvf_solvers::DenseCholesky`]): [`add`](Self::add) borders
/// it (`O(n_c² + n_c d)`), [`remove`](Self::remove) shrinks it (rank-one update of the trailing
/// block), and
/// [`set_values`](Self::set_values) touches only the right-hand side. [`solve`](Self::solve)
/// returns `v = D⁻¹ Cᵀ K⁻¹ c` (`d` values); map it to the field with [`ReducedBasis::map`].
///
/// A constraint whose rows are (numerically) linear combinations of the active ones in the
/// reduced space is rejected with [`DesignError::Dependent`], naming the constraints involved:
/// the session never produces a NaN field.
#[derive(Debug, Clone)]
pub struct SplineSession<'a> {
    basis: &'a ReducedBasis,
    inverse_energy: Vec<f64>,
    active: Vec<Active>,
    factor: DenseCholesky,
}

impl<'a> SplineSession<'a> {
    /// A session without constraints for weight `ω ≥ 0`.
    pub fn new(basis: &'a ReducedBasis, omega: f64) -> Result<Self, DesignError> {
        if !(omega.is_finite() && omega >= 0.0) {
            return Err(DesignError::BadParameter {
                what: "omega",
                value: omega,
            });
        }
        let lambda = basis.regularised_eigenvalues()?;
        let inverse_energy: Vec<f64> = lambda.iter().map(|&l| 1.0 / (l * l + omega * l)).collect();
        if let Some((&eigenvalue, _)) = lambda
            .iter()
            .zip(&inverse_energy)
            .find(|(_, w)| !w.is_normal())
        {
            return Err(DesignError::OmegaTooLarge { omega, eigenvalue });
        }
        Ok(Self {
            basis,
            inverse_energy,
            active: Vec::new(),
            factor: DenseCholesky::new(faer::Mat::<f64>::zeros(0, 0).as_ref())?,
        })
    }

    /// The basis the session works in.
    pub fn basis(&self) -> &ReducedBasis {
        self.basis
    }

    /// Ids of the active constraints, in the order they were added.
    pub fn ids(&self) -> Vec<&str> {
        self.active.iter().map(|a| a.id.as_str()).collect()
    }

    /// Number of active constraint rows `n_c`.
    pub fn row_count(&self) -> usize {
        self.factor.dimension()
    }

    /// The diagonal `D⁻¹` (`d` values) of the inverse reduced energy.
    pub fn inverse_energy(&self) -> &[f64] {
        &self.inverse_energy
    }

    /// Adds a constraint (all its rows) by bordering the factor. On
    /// [`DesignError::Dependent`] the session is left unchanged.
    pub fn add(&mut self, constraint: CompiledConstraint) -> Result<(), DesignError> {
        if self.active.iter().any(|a| a.id == constraint.id) {
            return Err(DesignError::DuplicateId { id: constraint.id });
        }
        let reduced = self.basis.reduce_constraint(&constraint)?;
        for (k, row) in reduced.iter().enumerate() {
            let weighted: Vec<f64> = row
                .iter()
                .zip(&self.inverse_energy)
                .map(|(c, w)| c * w)
                .collect();
            let mut b: Vec<f64> = self.reduced_rows().map(|r| dot(r, &weighted)).collect();
            b.extend(reduced[..k].iter().map(|r| dot(r, &weighted)));
            let gamma = dot(row, &weighted);
            // Bordered append `[[K, b], [bᵀ, γ]]`: the new pivot² is `γ − bᵀK⁻¹b`; a small one
            // relative to `γ` means the row is (nearly) a combination of the active rows.
            let coefficients = self.factor.solve(&b)?;
            let relative_pivot = (gamma - dot(&b, &coefficients)) / gamma;
            if !(gamma > 0.0 && relative_pivot > DEFAULT_DEPENDENCY_TOLERANCE) {
                for _ in 0..k {
                    self.factor.remove(self.factor.dimension() - 1)?;
                }
                return Err(self.dependency_error(
                    &constraint,
                    k,
                    &coefficients,
                    relative_pivot.max(0.0),
                ));
            }
            b.push(gamma);
            self.factor.append(&b)?;
        }
        self.active.push(Active {
            id: constraint.id.clone(),
            compiled: constraint,
            reduced,
        });
        Ok(())
    }

    /// Removes the constraint `id` (its rows and columns leave the factor by rank-one updates).
    pub fn remove(&mut self, id: &str) -> Result<CompiledConstraint, DesignError> {
        let index = self.index_of(id)?;
        let first: usize = self.active[..index].iter().map(|a| a.reduced.len()).sum();
        let count = self.active[index].reduced.len();
        for k in (0..count).rev() {
            self.factor.remove(first + k)?;
        }
        Ok(self.active.remove(index).compiled)
    }

    /// Changes the prescribed values of `id` (same rows): only the next solve changes.
    pub fn set_values(&mut self, id: &str, values: &[f64]) -> Result<(), DesignError> {
        let index = self.index_of(id)?;
        self.active[index].compiled.set_values(values)
    }

    /// Replaces constraint `id` by `constraint` (same id): a value-only change when the rows are
    /// identical, otherwise remove + add (restoring the old one if the new one is dependent).
    pub fn modify(&mut self, constraint: CompiledConstraint) -> Result<(), DesignError> {
        let index = self.index_of(&constraint.id)?;
        if self.active[index].compiled.rows == constraint.rows {
            return self.set_values(&constraint.id, &constraint.values);
        }
        let old = self.remove(&constraint.id)?;
        if let Err(error) = self.add(constraint) {
            // The old constraint was independent of the others, so it can be re-added.
            self.add(old)?;
            return Err(error);
        }
        Ok(())
    }

    /// The reduced coefficients `v = D⁻¹ Cᵀ μ`, `K μ = c` (`d` values). Without constraints,
    /// `v = 0`.
    pub fn solve(&self) -> Vec<f64> {
        let mut mu: Vec<f64> = self
            .active
            .iter()
            .flat_map(|a| a.compiled.values.iter().copied())
            .collect();
        // `mu` has one value per factored row, so the solve cannot fail.
        let _ = self.factor.solve_in_place(&mut mu);
        let mut v = vec![0.0; self.basis.len()];
        for (row, m) in self.reduced_rows().zip(&mu) {
            for (vi, c) in v.iter_mut().zip(row) {
                *vi += m * c;
            }
        }
        for (vi, w) in v.iter_mut().zip(&self.inverse_energy) {
            *vi *= w;
        }
        v
    }

    /// The full field `x = U v` (`n1` values) of [`solve`](Self::solve), multithreaded.
    pub fn field(&self) -> Vec<f64> {
        let v = self.solve();
        let mut x = vec![0.0; self.basis.field_dimension()];
        // The lengths come from the same basis, so the map cannot fail.
        let _ = self.basis.map(&v, &mut x);
        x
    }

    /// Residuals of every active constraint for a full field `x` (`n1` values).
    pub fn residuals(&self, field: &[f64]) -> Vec<ConstraintResidual> {
        self.active
            .iter()
            .map(|a| residual(&a.compiled, field))
            .collect()
    }

    fn reduced_rows(&self) -> impl Iterator<Item = &Vec<f64>> {
        self.active.iter().flat_map(|a| a.reduced.iter())
    }

    fn index_of(&self, id: &str) -> Result<usize, DesignError> {
        self.active
            .iter()
            .position(|a| a.id == id)
            .ok_or_else(|| DesignError::UnknownId { id: id.to_string() })
    }

    fn dependency_error(
        &self,
        constraint: &CompiledConstraint,
        row: usize,
        coefficients: &[f64],
        relative_pivot: f64,
    ) -> DesignError {
        // Which rows (and thus constraints) the new row depends on, and the value they imply.
        let values: Vec<f64> = self
            .active
            .iter()
            .flat_map(|a| a.compiled.values.iter().copied())
            .chain(constraint.values[..row].iter().copied())
            .collect();
        let owners: Vec<&str> = self
            .active
            .iter()
            .flat_map(|a| a.reduced.iter().map(move |_| a.id.as_str()))
            .chain(std::iter::repeat_n(constraint.id.as_str(), row))
            .collect();
        let largest = coefficients.iter().fold(0.0f64, |m, y| m.max(y.abs()));
        let mut contributions: Vec<(f64, &str)> = coefficients
            .iter()
            .zip(&owners)
            .filter(|(y, _)| y.abs() > 1e-6 * largest)
            .map(|(y, o)| (y.abs(), *o))
            .collect();
        contributions.sort_by(|a, b| b.0.total_cmp(&a.0));
        let mut involved: Vec<String> = Vec::new();
        for (_, id) in contributions {
            if !involved.iter().any(|i| i == id) {
                involved.push(id.to_string());
            }
        }
        let implied: f64 = coefficients.iter().zip(&values).map(|(y, c)| y * c).sum();
        let scale: f64 = coefficients
            .iter()
            .zip(&values)
            .map(|(y, c)| (y * c).abs())
            .sum::<f64>()
            + constraint.values[row].abs();
        let conflicting =
            (implied - constraint.values[row]).abs() > 1e-8 * scale.max(f64::MIN_POSITIVE);
        if involved.iter().all(|i| *i == constraint.id) {
            // Nothing else is involved: the basis cannot hold this constraint on its own.
            return DesignError::NotRepresentable {
                id: constraint.id.clone(),
                basis_size: self.basis.len(),
                detail: if involved.is_empty() {
                    "its rows vanish there".to_string()
                } else {
                    format!(
                        "its {} rows are linearly dependent there",
                        constraint.rows.len()
                    )
                },
            };
        }
        DesignError::Dependent {
            id: constraint.id.clone(),
            involved,
            conflicting,
            relative_pivot,
        }
    }
}

/// The residual of one compiled constraint for a full field.
pub fn residual(constraint: &CompiledConstraint, field: &[f64]) -> ConstraintResidual {
    let r = constraint.residuals(field);
    let absolute = r.iter().map(|x| x * x).sum::<f64>().sqrt();
    let terms = constraint
        .rows
        .iter()
        .map(|row| {
            row.iter()
                .map(|&(j, a)| (a * field[j]).abs())
                .sum::<f64>()
                .powi(2)
        })
        .sum::<f64>()
        .sqrt();
    let scale = constraint.value_scale().max(terms).max(f64::MIN_POSITIVE);
    ConstraintResidual {
        id: constraint.id.clone(),
        absolute,
        relative: absolute / scale,
    }
}
