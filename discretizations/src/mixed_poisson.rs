//! Solves the co-exact Poisson problem `(d1 M1⁻¹ d1ᵀ) g = b` of a complex whose field mass `M1`
//! is not diagonal (the Whitney 1-form mass): `d1 M1⁻¹ d1ᵀ` is dense, so it is solved in mixed
//! form through a sparse saddle-point system and never formed.

use crate::DecompositionError;
use faer::Mat;
use sprs::{CsMat, TriMat};
use tvf_core::discretization::sparse::{mul_transpose_vec, mul_vec};
use tvf_core::discretization::{DiscretizationError, Mass, NodeSpace, NO_COMPONENT};
use tvf_solvers::{SolverError, SparseLdlt};

/// Refinement steps at most; each divides the error by at least `λ₁/(λ₁ + ε)`.
const MAX_STEPS: usize = 40;
/// The regularisation `ε` relative to the mean eigenvalue of `(A, N)`.
const RELATIVE_REGULARISATION: f64 = 1e-8;
/// Relative residual `‖b − A g‖/‖b‖` the refinement stops at.
const TARGET: f64 = 1e-13;

/// The factorization of the quasi-definite saddle matrix
///
/// ```text
/// K = [[−M1, d1ᵀ], [d1, ε N]]      (free field nodes, free co-potential nodes)
/// ```
///
/// whose Schur complement is `d1 M1⁻¹ d1ᵀ + ε N` (`N = M2⁻¹`, the co-potential mass). With
/// `−M1` negative definite and `ε N` positive definite, `K` has an `LDLᵀ` factorization in every
/// fill-reducing order (quasi-definite matrices are strongly factorizable). The regularisation is
/// removed by iterative refinement: `g ← g + (A + εN)⁻¹ (b − A g)` converges to the solution of
/// `A g = b` on the complement of the kernel (constants per component with constants in the
/// kernel), and the result is shifted to zero `N`-mean on each such component, as the pinned
/// Poisson solve of the diagonal case does.
#[derive(Debug)]
pub struct MixedPoisson {
    ldlt: SparseLdlt,
    field_mass: Mass,
    co_potential_mass: Mass,
    d1: CsMat<f64>,
    /// Free field nodes (full indices), then free co-potential nodes: the saddle's unknowns.
    free_fields: Vec<usize>,
    free_co_potentials: Vec<usize>,
    /// Component of every co-potential node whose constants are in the kernel, else
    /// `NO_COMPONENT`.
    shifted: Vec<usize>,
    component_count: usize,
}

impl MixedPoisson {
    /// Factors the saddle matrix for the field mass `m1` (on `field_nodes`), `d1` (`n2 × n1`)
    /// and the co-potential mass `n = M2⁻¹` (on `co_potential_nodes`).
    pub fn new(
        m1: &Mass,
        d1: &CsMat<f64>,
        n: &Mass,
        field_nodes: &NodeSpace,
        co_potential_nodes: &NodeSpace,
    ) -> Result<Self, DecompositionError> {
        let free_fields: Vec<usize> = (0..field_nodes.len())
            .filter(|&i| field_nodes.is_free(i))
            .collect();
        let free_co_potentials: Vec<usize> = (0..co_potential_nodes.len())
            .filter(|&i| co_potential_nodes.is_free(i))
            .collect();
        let (n1, n2) = (free_fields.len(), free_co_potentials.len());
        let mut field_position = vec![usize::MAX; field_nodes.len()];
        for (k, &i) in free_fields.iter().enumerate() {
            field_position[i] = k;
        }
        let mut co_position = vec![usize::MAX; co_potential_nodes.len()];
        for (k, &i) in free_co_potentials.iter().enumerate() {
            co_position[i] = n1 + k;
        }
        let m1_matrix = m1.sparse_matrix().ok_or_else(|| {
            DiscretizationError::Inconsistent("the field mass M1 is stored as its inverse".into())
        })?;
        let epsilon = RELATIVE_REGULARISATION * mean_eigenvalue(&m1_matrix, d1, n);
        let mut upper = TriMat::new((n1 + n2, n1 + n2));
        for (&value, (i, j)) in m1_matrix.iter() {
            let (p, q) = (field_position[i], field_position[j]);
            if p != usize::MAX && q != usize::MAX && p <= q {
                upper.add_triplet(p, q, -value);
            }
        }
        for (&value, (r, c)) in d1.iter() {
            let (p, q) = (field_position[c], co_position[r]);
            if p != usize::MAX && q != usize::MAX {
                upper.add_triplet(p, q, value);
            }
        }
        let n_matrix = co_potential_mass_matrix(n)?;
        for (&value, (i, j)) in n_matrix.iter() {
            let (p, q) = (co_position[i], co_position[j]);
            if p != usize::MAX && q != usize::MAX && p <= q {
                upper.add_triplet(p, q, epsilon * value);
            }
        }
        let upper: CsMat<f64> = upper.to_csc();
        let upper = tvf_solvers::convert::upper_triangle_csc(&upper)?;
        let ldlt = SparseLdlt::new(upper.as_ref()).map_err(|e| match e {
            SolverError::Singular { .. } => SolverError::Factorization(
                "the mixed Poisson system of the co-exact part is singular: M1 is not positive \
                 definite on the free field nodes"
                    .into(),
            ),
            other => other,
        })?;
        let component_count = co_potential_nodes.constant_kernel.len();
        let shifted = (0..co_potential_nodes.len())
            .map(|i| {
                let c = co_potential_nodes.components[i];
                if co_potential_nodes.is_free(i)
                    && c != NO_COMPONENT
                    && co_potential_nodes.constant_kernel[c]
                {
                    c
                } else {
                    NO_COMPONENT
                }
            })
            .collect();
        Ok(Self {
            ldlt,
            field_mass: m1.clone(),
            co_potential_mass: n.clone(),
            d1: d1.clone(),
            free_fields,
            free_co_potentials,
            shifted,
            component_count,
        })
    }

    /// `A g` for every `g` of `columns`, the `M1` solves of all columns as one block.
    fn apply_many(&self, columns: &[&[f64]]) -> Vec<Vec<f64>> {
        let weighted: Vec<Vec<f64>> = columns
            .iter()
            .map(|g| mul_transpose_vec(&self.d1, g))
            .collect();
        let solved: Vec<Vec<f64>> = if self.field_mass.diagonal_values().is_some() {
            weighted.iter().map(|w| self.field_mass.solve(w)).collect()
        } else {
            let rows = weighted.first().map_or(0, Vec::len);
            let block = Mat::from_fn(rows, weighted.len(), |i, j| weighted[j][i]);
            let x = self.field_mass.solve_block(block.as_ref());
            (0..x.ncols())
                .map(|j| (0..rows).map(|i| x[(i, j)]).collect())
                .collect()
        };
        solved.iter().map(|y| mul_vec(&self.d1, y)).collect()
    }

    /// `(A + εN)⁻¹ r` through the saddle system for every `r` of `residuals` (on the
    /// co-potential nodes, zero result on the nodes that are not free), one multi-column solve.
    fn regularised_solve_many(&self, residuals: &[&[f64]]) -> Vec<Vec<f64>> {
        let n1 = self.free_fields.len();
        let mut rhs = Mat::zeros(n1 + self.free_co_potentials.len(), residuals.len());
        for (j, r) in residuals.iter().enumerate() {
            for (k, &i) in self.free_co_potentials.iter().enumerate() {
                rhs[(n1 + k, j)] = r[i];
            }
        }
        self.ldlt.solve_in_place(rhs.as_mut());
        (0..residuals.len())
            .map(|j| {
                let mut g = vec![0.0; residuals[j].len()];
                for (k, &i) in self.free_co_potentials.iter().enumerate() {
                    g[i] = rhs[(n1 + k, j)];
                }
                g
            })
            .collect()
    }

    /// Solves `A g = b` on the free co-potential nodes for every `b` of `rhs` (each must sum to
    /// zero over each component with constants in the kernel; what does not, round-off of a
    /// consistent right-hand side, is dropped); each result has zero `N`-weighted mean on every
    /// such component and is zero on the nodes that are not free. The right-hand sides are
    /// refined together: every step solves the columns still refining as one block (the saddle
    /// factor and the `M1` factor read once for all of them), and each column stops by its own
    /// test — at the target or when a step no longer lowers its residual — as it would alone. One
    /// right-hand side is solved with the same arithmetic as a block of one.
    pub fn solve_many(&self, rhs: &[&[f64]]) -> Vec<Vec<f64>> {
        let b: Vec<Vec<f64>> = rhs.iter().map(|b| self.in_range(b)).collect();
        let norms: Vec<f64> = b
            .iter()
            .map(|b| b.iter().map(|x| x * x).sum::<f64>().sqrt())
            .collect();
        let mut g: Vec<Vec<f64>> = b.iter().map(|b| vec![0.0; b.len()]).collect();
        let mut previous = vec![f64::INFINITY; b.len()];
        let mut refining: Vec<usize> = (0..b.len()).filter(|&j| norms[j] > 0.0).collect();
        for _ in 0..MAX_STEPS {
            if refining.is_empty() {
                break;
            }
            let columns: Vec<&[f64]> = refining.iter().map(|&j| g[j].as_slice()).collect();
            let ag = self.apply_many(&columns);
            let mut residuals = Vec::with_capacity(refining.len());
            let mut still = Vec::with_capacity(refining.len());
            for (&j, ag) in refining.iter().zip(&ag) {
                let r: Vec<f64> = b[j].iter().zip(ag).map(|(x, y)| x - y).collect();
                let r_norm = r.iter().map(|x| x * x).sum::<f64>().sqrt();
                if r_norm <= TARGET * norms[j] || r_norm >= previous[j] {
                    continue;
                }
                previous[j] = r_norm;
                residuals.push(r);
                still.push(j);
            }
            if still.is_empty() {
                break;
            }
            let residuals: Vec<&[f64]> = residuals.iter().map(Vec::as_slice).collect();
            let steps = self.regularised_solve_many(&residuals);
            for (&j, step) in still.iter().zip(&steps) {
                g[j].iter_mut().zip(step).for_each(|(x, s)| *x += s);
            }
            refining = still;
        }
        for g in &mut g {
            self.remove_means(g);
        }
        g
    }

    /// The part of `b` in the range of `A`: zero on the nodes that are not free, and the mean
    /// removed on every component with constants in the kernel (`A` is symmetric, so its range is
    /// what sums to zero there).
    fn in_range(&self, b: &[f64]) -> Vec<f64> {
        let mut sums = vec![0.0; self.component_count];
        let mut counts = vec![0usize; self.component_count];
        for (&x, &c) in b.iter().zip(&self.shifted) {
            if c != NO_COMPONENT {
                sums[c] += x;
                counts[c] += 1;
            }
        }
        (0..b.len())
            .map(|i| match self.shifted[i] {
                _ if !self.is_free(i) => 0.0,
                NO_COMPONENT => b[i],
                c => b[i] - sums[c] / counts[c] as f64,
            })
            .collect()
    }

    fn is_free(&self, i: usize) -> bool {
        self.co_potential_mass.is_free(i)
    }

    /// Shifts `g` to zero `N`-weighted mean on every component with constants in the kernel.
    fn remove_means(&self, g: &mut [f64]) {
        if self.component_count == 0 {
            return;
        }
        let ng = self.co_potential_mass.apply(g);
        let indicator: Vec<f64> = self
            .shifted
            .iter()
            .map(|&c| if c != NO_COMPONENT { 1.0 } else { 0.0 })
            .collect();
        let n_one = self.co_potential_mass.apply(&indicator);
        let mut sums = vec![0.0; self.component_count];
        let mut weights = vec![0.0; self.component_count];
        for (i, &c) in self.shifted.iter().enumerate() {
            if c != NO_COMPONENT {
                sums[c] += ng[i];
                weights[c] += n_one[i];
            }
        }
        for (x, &c) in g.iter_mut().zip(&self.shifted) {
            if c != NO_COMPONENT && weights[c] > 0.0 {
                *x -= sums[c] / weights[c];
            }
        }
    }
}

/// `N` as a sparse matrix (the co-potential mass is stored directly when it is not diagonal).
fn co_potential_mass_matrix(n: &Mass) -> Result<CsMat<f64>, DecompositionError> {
    n.sparse_matrix().ok_or_else(|| {
        DiscretizationError::Inconsistent(
            "the co-potential mass M2⁻¹ is dense: the mixed Poisson solve needs it sparse".into(),
        )
        .into()
    })
}

/// An estimate of the mean eigenvalue of `(d1 M1⁻¹ d1ᵀ, N)`: `Σ_rc d1_rc² / M1_cc` over `1ᵀ N 1`
/// (the diagonal of `M1` stands in for `M1`, which is spectrally equivalent on meshes without
/// degenerate faces). Only the scale of the regularisation depends on it.
fn mean_eigenvalue(m1: &CsMat<f64>, d1: &CsMat<f64>, n: &Mass) -> f64 {
    let mut diagonal = vec![0.0; m1.rows()];
    for (&value, (i, j)) in m1.iter() {
        if i == j {
            diagonal[i] += value;
        }
    }
    let trace: f64 = d1
        .iter()
        .filter(|(_, (_, c))| diagonal[*c] > 0.0)
        .map(|(&v, (_, c))| v * v / diagonal[c])
        .sum();
    let total = n.total();
    if trace > 0.0 && total > 0.0 {
        trace / total
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::WhitneyGalerkin;
    use tvf_core::discretization::HodgeComplex;
    use tvf_core::generate::{icosphere, jitter};

    #[test]
    fn solves_consistent_systems_and_drops_the_constant_part() {
        let mesh = jitter(&icosphere(2), 0.2, 4).unwrap();
        let complex = WhitneyGalerkin::new(&mesh).unwrap();
        let n = complex.m2().inverse();
        let poisson = MixedPoisson::new(
            complex.m1(),
            complex.d1(),
            &n,
            complex.field_nodes(),
            complex.co_potential_nodes(),
        )
        .unwrap();
        let f = mesh.face_count();
        let mut b: Vec<f64> = (0..f).map(|t| (0.7 * t as f64).sin()).collect();
        let mean = b.iter().sum::<f64>() / f as f64;
        b.iter_mut().for_each(|x| *x -= mean);
        let g = poisson.solve_many(&[&b]).remove(0);
        let residual = poisson
            .apply_many(&[&g])
            .remove(0)
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(residual <= 1e-12 * scale, "|A g − b| = {residual:e}");
        // A constant added to b is outside the range of A: it changes nothing.
        let shifted: Vec<f64> = b.iter().map(|x| x + 0.3).collect();
        let h = poisson.solve_many(&[&shifted]).remove(0);
        let difference = g
            .iter()
            .zip(&h)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        let size = g.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(difference <= 1e-12 * size, "{difference:e}");
    }
}
