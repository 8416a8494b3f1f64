//! [`ShiftFactor`]: the factorization of a pencil at one shift σ, and how the Krylov vectors
//! are solved with it.
//!
//! - Standard pencils factor `A − σM` (`n × n`); the Krylov vectors are kept in its
//!   elimination order, so a solve needs no permutation.
//! - Mixed pencils (`A = d1 W⁻¹ d1ᵀ`, dimension `n2`) factor the saddle matrix
//!   `K(σ) = [[−W, d1ᵀ], [d1, −σN]]` (`n1 + n2`): `(A − σN) x = b ⟺ K(σ) [u; x] = [0; b]`
//!   with `u = W⁻¹ d1ᵀ x`. The Krylov vectors (`n2` rows) are kept in the order in which the
//!   `x` unknowns appear in `K`'s elimination order, so a solve scatters them into the
//!   positions of those unknowns (the `u` rows zero), solves, and gathers them back: two
//!   monotone passes, no search.
//!
//! [`KrylovFrame`] holds what depends only on the elimination order (the same for every
//! shift of a pencil: its factorizations share one fill-reducing ordering): the Krylov order,
//! the sparse mass in it, and the saddle positions. It is formed once per pencil.

use super::mass::permuted;
use super::symmetric_products::Row;
use crate::error::SolverError;
use crate::sparse_ldlt::SparseLdlt;
use faer::sparse::{SparseColMat, SparseColMatRef};
use faer::{Mat, MatMut};

/// What the Krylov vectors of every shift of a pencil share (see the module documentation).
pub(crate) struct KrylovFrame {
    /// Row `i` of a Krylov vector is unknown `order[i]` of the pencil (`None`: the input order).
    order: Option<Vec<usize>>,
    /// `P M Pᵀ` in the Krylov order, for a sparse mass.
    mass: Option<SparseColMat<usize, f64>>,
    /// For a mixed pencil: `positions[i]` is the row of `K`'s elimination order holding Krylov
    /// row `i` (ascending), and `K` has `rows` rows.
    saddle: Option<(Vec<usize>, usize)>,
}

impl KrylovFrame {
    /// The frame of a standard pencil whose first factorization is `ldlt`, with its sparse
    /// mass `mass` (full storage, input order) if it has one.
    pub(crate) fn standard(
        ldlt: &SparseLdlt,
        mass: Option<SparseColMatRef<'_, usize, f64>>,
    ) -> Result<Self, SolverError> {
        let order = ldlt.elimination_order().map(<[usize]>::to_vec);
        Self::with_order(order, mass, None)
    }

    /// The frame of a mixed pencil (`inner` = `n1` unknowns `u` first in `K`'s input order,
    /// then the `n2` unknowns `x`) whose first factorization is `ldlt`.
    pub(crate) fn saddle(
        ldlt: &SparseLdlt,
        inner: usize,
        mass: Option<SparseColMatRef<'_, usize, f64>>,
    ) -> Result<Self, SolverError> {
        let rows = ldlt.dimension();
        let elimination: Vec<usize> = match ldlt.elimination_order() {
            Some(order) => order.to_vec(),
            None => (0..rows).collect(),
        };
        let positions: Vec<usize> = (0..rows).filter(|&k| elimination[k] >= inner).collect();
        let order = positions.iter().map(|&k| elimination[k] - inner).collect();
        Self::with_order(Some(order), mass, Some((positions, rows)))
    }

    fn with_order(
        order: Option<Vec<usize>>,
        mass: Option<SparseColMatRef<'_, usize, f64>>,
        saddle: Option<(Vec<usize>, usize)>,
    ) -> Result<Self, SolverError> {
        let mass = match (mass, &order) {
            (Some(m), Some(order)) => Some(permuted(m, order)?),
            (Some(m), None) => Some(permuted(m, &(0..m.nrows()).collect::<Vec<_>>())?),
            (None, _) => None,
        };
        Ok(Self {
            order,
            mass,
            saddle,
        })
    }
}

/// The factorization of a pencil at one shift (see the module documentation).
pub(crate) struct ShiftFactor {
    ldlt: SparseLdlt,
    frame: std::sync::Arc<KrylovFrame>,
}

impl ShiftFactor {
    pub(crate) fn new(ldlt: SparseLdlt, frame: std::sync::Arc<KrylovFrame>) -> Self {
        Self { ldlt, frame }
    }

    /// The inertia of the factored matrix (`A − σM`, or `K(σ)` with its `n1` negatives of `−W`).
    pub(crate) fn inertia(&self) -> crate::sparse_ldlt::Inertia {
        self.ldlt.inertia()
    }

    /// The order of the Krylov vectors: row `i` is unknown `order[i]` of the pencil (`None`:
    /// the input order).
    pub(crate) fn krylov_order(&self) -> Option<&[usize]> {
        self.frame.order.as_deref()
    }

    /// A sparse mass in the Krylov order (`None` for a diagonal mass).
    pub(crate) fn krylov_mass(&self) -> Option<SparseColMatRef<'_, usize, f64>> {
        self.frame.mass.as_ref().map(|m| m.as_ref())
    }

    /// Overwrites the packed rows `rows` (`n` rows, Krylov order) with `(A − σM)⁻¹ rows`;
    /// `buffer` holds the saddle system of a mixed pencil (resized, contents unspecified).
    pub(crate) fn solve_rows(&self, rows: &mut [Row], buffer: &mut Vec<Row>) {
        let Some((positions, total)) = &self.frame.saddle else {
            self.ldlt.solve_rows_in_elimination_order(rows);
            return;
        };
        buffer.clear();
        buffer.resize(*total, [0.0; 8]);
        for (row, &k) in rows.iter().zip(positions) {
            buffer[k] = *row;
        }
        self.ldlt.solve_rows_in_elimination_order(buffer);
        for (row, &k) in rows.iter_mut().zip(positions) {
            *row = buffer[k];
        }
    }

    /// Overwrites the `n × r` block `rhs` (input order) with `(A − σM)⁻¹ rhs`.
    pub(crate) fn solve_in_place(&self, mut rhs: MatMut<'_, f64>) {
        let Some((_, total)) = &self.frame.saddle else {
            self.ldlt.solve_in_place(rhs);
            return;
        };
        let inner = total - rhs.nrows();
        let mut full = Mat::<f64>::zeros(*total, rhs.ncols());
        full.as_mut()
            .subrows_mut(inner, rhs.nrows())
            .copy_from(rhs.as_ref());
        self.ldlt.solve_in_place(full.as_mut());
        rhs.copy_from(full.as_ref().subrows(inner, rhs.nrows()));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ordering::FillOrdering;
    use faer::sparse::Triplet;

    /// A tiny saddle matrix `K(σ) = [[−W, d1ᵀ], [d1, −σN]]`: its negative pivots are `n1` plus
    /// the eigenvalues of `(d1 W⁻¹ d1ᵀ, N)` below σ, and the packed saddle solve (scatter,
    /// solve, gather) solves `(A − σN) x = b`.
    #[test]
    fn saddle_counts_and_solves_the_reduced_system() {
        let (n1, n2) = (9, 5);
        let w = Mat::from_fn(n1, n1, |i, j| match i.abs_diff(j) {
            0 => 4.0 + i as f64 / 4.0,
            1 => -1.0,
            _ => 0.0,
        });
        let d1 = Mat::from_fn(n2, n1, |f, e| match (e + 2 * n2 - 2 * f) % 7 {
            0 => 1.0,
            3 => -1.0,
            5 => 0.5,
            _ => 0.0,
        });
        let n: Vec<f64> = (0..n2).map(|f| 0.5 + f as f64 / 5.0).collect();
        let w_inverse = faer::linalg::solvers::DenseSolveCore::inverse(
            &w.as_ref().llt(faer::Side::Lower).expect("SPD"),
        );
        let a = &d1 * &w_inverse * d1.transpose();
        let (values, _) =
            crate::dense_eigen::dense_generalized_eigen(a.as_ref(), &n).expect("eigen");
        for sigma in [0.5 * (values[1] + values[2]), 0.5 * (values[3] + values[4])] {
            let mut triplets = Vec::new();
            for j in 0..n1 + n2 {
                for i in 0..=j {
                    let value = match (i < n1, j < n1) {
                        (true, true) => -w[(i, j)],
                        (true, false) => d1[(j - n1, i)],
                        _ if i == j => -sigma * n[i - n1],
                        _ => 0.0,
                    };
                    if value != 0.0 || i == j {
                        triplets.push(Triplet::new(i, j, value));
                    }
                }
            }
            let upper =
                SparseColMat::try_new_from_triplets(n1 + n2, n1 + n2, &triplets).expect("valid");
            let ldlt =
                SparseLdlt::with_ordering(upper.as_ref(), FillOrdering::Amd).expect("factors");
            let below = values.iter().filter(|&&v| v < sigma).count();
            assert_eq!(ldlt.inertia().negative, n1 + below, "σ = {sigma}");
            let frame = KrylovFrame::saddle(&ldlt, n1, None).expect("frame");
            let order = frame.order.clone().expect("an order");
            let factor = ShiftFactor::new(ldlt, std::sync::Arc::new(frame));
            let b: Vec<f64> = (0..n2).map(|f| f as f64 - 1.5).collect();
            let mut rows: Vec<Row> = order
                .iter()
                .map(|&f| std::array::from_fn(|j| if j == 0 { b[f] } else { 0.0 }))
                .collect();
            factor.solve_rows(&mut rows, &mut Vec::new());
            let shifted = Mat::from_fn(n2, n2, |i, j| {
                a[(i, j)] - if i == j { sigma * n[i] } else { 0.0 }
            });
            let mut x = vec![0.0; n2];
            for (row, &f) in rows.iter().zip(&order) {
                x[f] = row[0];
            }
            for i in 0..n2 {
                let r: f64 = (0..n2).map(|j| shifted[(i, j)] * x[j]).sum::<f64>() - b[i];
                assert!(r.abs() <= 1e-12, "σ = {sigma}: residual {r:e}");
            }
            let mut column = Mat::from_fn(n2, 1, |i, _| b[i]);
            factor.solve_in_place(column.as_mut());
            for i in 0..n2 {
                assert!((column[(i, 0)] - x[i]).abs() <= 1e-12);
            }
        }
    }
}
