//! Solves a singular Poisson system whose kernel is spanned by the per-component constants.

use sprs::CsMat;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::discretization::NO_COMPONENT;
use tvf_solvers::{SolverError, SparseCholesky};

/// Factorization of a symmetric PSD stiffness `A` (`n × n`) whose kernel is spanned by the
/// indicator functions of the connected components (cotan and Crouzeix–Raviart matrices).
///
/// Method: the first node of every component (and every node of no component) is pinned to
/// zero by replacing its row and column with the identity; the reduced matrix is SPD. For a
/// consistent right-hand side (zero sum over every component), the result solves `A x = b`
/// exactly; it is then shifted to have zero mean (w.r.t. `mass`) on every component.
#[derive(Debug)]
pub struct PinnedPoisson {
    cholesky: SparseCholesky,
    pinned: Vec<bool>,
    components: Vec<usize>,
    component_count: usize,
    mass: Vec<f64>,
}

impl PinnedPoisson {
    /// Factors `stiffness` with the node → component map `components` and lumped `mass`.
    pub fn new(
        stiffness: &CsMat<f64>,
        components: &[usize],
        component_count: usize,
        mass: &[f64],
    ) -> Result<Self, SolverError> {
        let n = components.len();
        let mut pinned = vec![false; n];
        let mut seen = vec![false; component_count];
        for (node, &c) in components.iter().enumerate() {
            if c == NO_COMPONENT {
                pinned[node] = true;
            } else if !seen[c] {
                seen[c] = true;
                pinned[node] = true;
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
            components: components.to_vec(),
            component_count,
            mass: mass.to_vec(),
        })
    }

    /// Solves `A x = rhs` (`rhs` must sum to zero over each component); the result has zero
    /// mass-weighted mean on every component and is zero on nodes of no component.
    pub fn solve(&self, rhs: &[f64]) -> Vec<f64> {
        let reduced: Vec<f64> = rhs
            .iter()
            .zip(&self.pinned)
            .map(|(&b, &p)| if p { 0.0 } else { b })
            .collect();
        let mut x = self.cholesky.solve(&reduced);
        let mut sums = vec![0.0; self.component_count];
        let mut weights = vec![0.0; self.component_count];
        for ((&xi, &c), &m) in x.iter().zip(&self.components).zip(&self.mass) {
            if c != NO_COMPONENT {
                sums[c] += m * xi;
                weights[c] += m;
            }
        }
        for (xi, &c) in x.iter_mut().zip(&self.components) {
            if c != NO_COMPONENT && weights[c] > 0.0 {
                *xi -= sums[c] / weights[c];
            }
        }
        x
    }
}
