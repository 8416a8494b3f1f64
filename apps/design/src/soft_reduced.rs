//! [`ReducedSoftDesign`]: soft-constrained design in the eigenbasis (Section 8.4),
//! `(Λ + ωΛ² + ε + Cᵀ W C) v = Cᵀ W c`, with a dense Cholesky factor kept up to date by low-rank
//! updates when constraints are added or removed.

use crate::constraint::CompiledConstraint;
use crate::error::DesignError;
use crate::reduced_basis::ReducedBasis;
use crate::soft_options::SoftOptions;
use faer::linalg::cholesky::llt::update::rank_r_update_clobber;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Col, Mat, Par};

/// One active soft constraint and its reduced rows `C̃_row U`.
#[derive(Debug, Clone)]
struct Active {
    compiled: CompiledConstraint,
    reduced: Vec<Vec<f64>>,
}

/// The reduced soft-design system: `K = diag(λ + ωλ² + ε) + Σ_rows w c cᵀ` (`d × d`) as a dense
/// lower Cholesky factor `L`.
///
/// Construction factors the diagonal part (trivially); [`add`](Self::add) applies a rank-`r`
/// update (`r` = 2 for a vector constraint, 1 for divergence / curl), [`remove`](Self::remove) the
/// matching downdate: `O(d² r)` each, never a refactorisation. The harmonic fields (`λ = 0`) are
/// held only by `ε` and the constraints, exactly as in [`crate::FullSoftDesign`] with the same
/// [`SoftOptions`] (in the eigenbasis `Uᵀ S U = Λ`, `Uᵀ B U = Λ²`, `Uᵀ M1 U = I`), so the two
/// agree as `d` grows; `ε` must therefore be positive when the basis has harmonic fields.
#[derive(Debug, Clone)]
pub struct ReducedSoftDesign<'a> {
    basis: &'a ReducedBasis,
    factor: Mat<f64>,
    active: Vec<Active>,
}

impl<'a> ReducedSoftDesign<'a> {
    /// The system without constraints.
    pub fn new(basis: &'a ReducedBasis, options: SoftOptions) -> Result<Self, DesignError> {
        options.check()?;
        let diagonal: Vec<f64> = basis
            .eigenvalues()
            .iter()
            .zip(basis.harmonic())
            .map(|(&l, &h)| {
                let l = if h { 0.0 } else { l };
                l + options.omega * l * l + options.regularization
            })
            .collect();
        if let Some((&eigenvalue, _)) = basis
            .eigenvalues()
            .iter()
            .zip(&diagonal)
            .find(|(_, x)| !x.is_finite())
        {
            return Err(DesignError::OmegaTooLarge {
                omega: options.omega,
                eigenvalue,
            });
        }
        if diagonal.iter().any(|&x| x <= 0.0) {
            return Err(DesignError::BadBasis(
                "the basis has harmonic fields: soft design needs a positive regularization".into(),
            ));
        }
        let d = diagonal.len();
        let factor = Mat::from_fn(d, d, |i, j| if i == j { diagonal[i].sqrt() } else { 0.0 });
        Ok(Self {
            basis,
            factor,
            active: Vec::new(),
        })
    }

    /// Adds a constraint: rank-`r` update `K += w Cᵀ C` of the factor.
    pub fn add(&mut self, constraint: CompiledConstraint) -> Result<(), DesignError> {
        if self.active.iter().any(|a| a.compiled.id == constraint.id) {
            return Err(DesignError::DuplicateId { id: constraint.id });
        }
        let reduced = self.basis.reduce_constraint(&constraint)?;
        self.update(&reduced, constraint.weight)?;
        self.active.push(Active {
            compiled: constraint,
            reduced,
        });
        Ok(())
    }

    /// Adds several constraints (one rank-`r` update each).
    pub fn add_all(
        &mut self,
        constraints: impl IntoIterator<Item = CompiledConstraint>,
    ) -> Result<(), DesignError> {
        constraints.into_iter().try_for_each(|c| self.add(c))
    }

    /// Removes constraint `id`: rank-`r` downdate `K −= w Cᵀ C`.
    pub fn remove(&mut self, id: &str) -> Result<CompiledConstraint, DesignError> {
        let index = self.index_of(id)?;
        let weight = self.active[index].compiled.weight;
        let reduced = self.active[index].reduced.clone();
        self.update(&reduced, -weight)?;
        Ok(self.active.remove(index).compiled)
    }

    /// Changes the values of constraint `id` (same rows): only the right-hand side changes.
    pub fn set_values(&mut self, id: &str, values: &[f64]) -> Result<(), DesignError> {
        let index = self.index_of(id)?;
        self.active[index].compiled.set_values(values)
    }

    /// The active constraints.
    pub fn constraints(&self) -> impl Iterator<Item = &CompiledConstraint> {
        self.active.iter().map(|a| &a.compiled)
    }

    /// The reduced coefficients `v = K⁻¹ Cᵀ W c` (`d` values): two triangular solves.
    pub fn solve(&self) -> Vec<f64> {
        let d = self.basis.len();
        let mut rhs = Mat::<f64>::zeros(d, 1);
        for a in &self.active {
            for (row, value) in a.reduced.iter().zip(&a.compiled.values) {
                let s = a.compiled.weight * value;
                for (k, c) in row.iter().enumerate() {
                    rhs[(k, 0)] += s * c;
                }
            }
        }
        solve_lower_triangular_in_place(self.factor.as_ref(), rhs.as_mut(), Par::Seq);
        solve_upper_triangular_in_place(self.factor.transpose(), rhs.as_mut(), Par::Seq);
        (0..d).map(|k| rhs[(k, 0)]).collect()
    }

    /// The full field `x = U v` (`n1` values, multithreaded).
    pub fn field(&self) -> Vec<f64> {
        let v = self.solve();
        let mut x = vec![0.0; self.basis.field_dimension()];
        // The lengths come from the same basis, so the map cannot fail.
        let _ = self.basis.map(&v, &mut x);
        x
    }

    fn update(&mut self, reduced: &[Vec<f64>], weight: f64) -> Result<(), DesignError> {
        let d = self.basis.len();
        let mut w = Mat::from_fn(d, reduced.len(), |i, j| reduced[j][i]);
        let mut alpha = Col::from_fn(reduced.len(), |_| weight);
        rank_r_update_clobber(
            self.factor.as_mut(),
            w.as_mut(),
            alpha.as_mut().as_diagonal_mut(),
        )
        .map_err(|_| {
            DesignError::NotPositiveDefinite(
                "the updated reduced soft-design system (its factor is no longer usable)".into(),
            )
        })
    }

    fn index_of(&self, id: &str) -> Result<usize, DesignError> {
        self.active
            .iter()
            .position(|a| a.compiled.id == id)
            .ok_or_else(|| DesignError::UnknownId { id: id.to_string() })
    }
}
