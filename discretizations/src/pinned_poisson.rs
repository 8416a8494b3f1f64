//! Solves a singular Poisson system on the free nodes of a space, with the per-component constants
//! in its kernel where the space has them.

use faer::Mat;
use sprs::CsMat;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::discretization::{Mass, NodeSpace, NO_COMPONENT};
use tvf_solvers::{SolverError, SparseCholesky};

/// Factorization of a symmetric PSD stiffness `A` (`n × n`) of one space of a complex (cotan,
/// Crouzeix–Raviart, ...), whose kernel on the free nodes is spanned by the indicator functions
/// of the components listed in [`NodeSpace::constant_kernel`].
///
/// Method: every node that is not free (no face uses it, or the boundary condition fixes it to
/// zero) and the first free node of every component with constants in the kernel are pinned to
/// zero by replacing their row and column with the identity; the reduced matrix is SPD. For a
/// consistent right-hand side (zero sum over every such component), the result solves `A x = b`
/// on the free nodes exactly; it is then shifted to have zero mean (w.r.t. `mass`) on every such
/// component, and is zero on the nodes that are not free.
#[derive(Debug)]
pub struct PinnedPoisson {
    cholesky: SparseCholesky,
    pinned: Vec<bool>,
    /// Component of every node whose constants are in the kernel, else `NO_COMPONENT`.
    shifted: Vec<usize>,
    component_count: usize,
    mass: Mass,
}

impl PinnedPoisson {
    /// Factors `stiffness` (`n × n`) of the space `nodes` with `mass` (`n × n`, the space's inner
    /// product, used for the means).
    pub fn new(
        stiffness: &CsMat<f64>,
        nodes: &NodeSpace,
        mass: &Mass,
    ) -> Result<Self, SolverError> {
        let n = nodes.len();
        let component_count = nodes.constant_kernel.len();
        let mut pinned = vec![false; n];
        let mut shifted = vec![NO_COMPONENT; n];
        let mut seen = vec![false; component_count];
        for (node, &c) in nodes.components.iter().enumerate() {
            if !nodes.is_free(node) {
                pinned[node] = true;
            } else if nodes.constant_kernel[c] {
                shifted[node] = c;
                if !seen[c] {
                    seen[c] = true;
                    pinned[node] = true;
                }
            }
        }
        let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
        for (value, (i, j)) in stiffness.iter() {
            if !pinned[i] && !pinned[j] {
                rows.push(i);
                cols.push(j);
                values.push(*value);
            }
        }
        for (node, _) in pinned.iter().enumerate().filter(|(_, &p)| p) {
            rows.push(node);
            cols.push(node);
            values.push(1.0);
        }
        let reduced = from_triplets(n, n, rows, cols, values);
        Ok(Self {
            cholesky: SparseCholesky::new(&reduced)?,
            pinned,
            shifted,
            component_count,
            mass: mass.clone(),
        })
    }

    /// Solves `A x = rhs` on the free nodes (`rhs` must sum to zero over each component with
    /// constants in the kernel); the result has zero mass-weighted mean on every such component
    /// and is zero on the nodes that are not free.
    pub fn solve(&self, rhs: &[f64]) -> Vec<f64> {
        let mut solutions = self.solve_many(&[rhs]);
        solutions.pop().expect("one right-hand side, one solution")
    }

    /// [`Self::solve`] for several right-hand sides (each of length `n`) through one
    /// multi-column solve of the factorization (reading the factor once for all of them); one
    /// right-hand side gives the same bits as before this method existed (a one-column block).
    pub fn solve_many(&self, rhs: &[&[f64]]) -> Vec<Vec<f64>> {
        let n = self.pinned.len();
        let mut block = Mat::from_fn(
            n,
            rhs.len(),
            |i, j| {
                if self.pinned[i] {
                    0.0
                } else {
                    rhs[j][i]
                }
            },
        );
        self.cholesky.solve_in_place(block.as_mut());
        (0..rhs.len())
            .map(|j| {
                let mut x: Vec<f64> = (0..n).map(|i| block[(i, j)]).collect();
                let (sums, weights) = self.component_means(&x);
                for (xi, &c) in x.iter_mut().zip(&self.shifted) {
                    if c != NO_COMPONENT && weights[c] > 0.0 {
                        *xi -= sums[c] / weights[c];
                    }
                }
                x
            })
            .collect()
    }

    /// Per component with constants in the kernel: `Σ (M x)_i` and `Σ (M 1)_i` over its nodes
    /// (a diagonal mass: `Σ m_i x_i` and `Σ m_i`). Masses do not couple components.
    fn component_means(&self, x: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let mut sums = vec![0.0; self.component_count];
        let mut weights = vec![0.0; self.component_count];
        match self.mass.diagonal_values() {
            Some(mass) => {
                for ((&xi, &c), &m) in x.iter().zip(&self.shifted).zip(mass) {
                    if c != NO_COMPONENT {
                        sums[c] += m * xi;
                        weights[c] += m;
                    }
                }
            }
            None => {
                let indicator: Vec<f64> = self
                    .shifted
                    .iter()
                    .map(|&c| if c != NO_COMPONENT { 1.0 } else { 0.0 })
                    .collect();
                let masked: Vec<f64> = x.iter().zip(&indicator).map(|(a, b)| a * b).collect();
                let (mx, m_one) = (self.mass.apply(&masked), self.mass.apply(&indicator));
                for (i, &c) in self.shifted.iter().enumerate() {
                    if c != NO_COMPONENT {
                        sums[c] += mx[i];
                        weights[c] += m_one[i];
                    }
                }
            }
        }
        (sums, weights)
    }
}
