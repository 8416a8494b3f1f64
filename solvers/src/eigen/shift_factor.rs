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
//! `LDLᵀ` without pivoting of the indefinite `K(σ)` grows: a `ψ` unknown eliminated before its
//! edges has the pivot `−σN_ff`, and the edges' Schur complement then carries `d1ᵀ d1 / (σN)`,
//! so a solve is accurate only to about `ε ‖d1‖² / (σ N_min ‖W‖)` relative. The Krylov
//! expansion tolerates that (the computed `LDLᵀ` is exactly symmetric, so the operator is a
//! nearby self-adjoint one, and the Rayleigh–Ritz against the true `A` restores the values),
//! but the eigenvectors are then only that accurate, and their eigenfield residuals (see
//! `refinement.rs`) stay far above the target, out of reach of further steps with the same
//! factorization. So the solves that set the vectors' accuracy — the inverse-iteration step of
//! every locked vector and the refinement — take one step of iterative refinement on the saddle
//! system ([`ShiftFactor::solve_rows_refined`]: one more solve and a product with `K(σ)`), which
//! restores the accuracy of a backward-stable solve. Standard pencils solve as before.
//!
//! [`KrylovFrame`] holds what depends only on the elimination order (the same for every
//! shift of a pencil: its factorizations share one fill-reducing ordering): the Krylov order,
//! the sparse mass in it, and the saddle positions. It is formed once per pencil.

use super::mass::permuted;
use super::stored_mass::StoredMass;
use super::symmetric_products::{gather_times, Row};
use crate::convert::ShiftedPattern;
use crate::error::SolverError;
use crate::sparse_ldlt::SparseLdlt;
use faer::sparse::Triplet;
use faer::sparse::{SparseColMat, SparseColMatRef};
use faer::MatMut;

/// What the Krylov vectors of every shift of a pencil share (see the module documentation).
pub(crate) struct KrylovFrame {
    /// Row `i` of a Krylov vector is unknown `order[i]` of the pencil (`None`: the input order).
    order: Option<Vec<usize>>,
    /// `P M Pᵀ` in the Krylov order, for a sparse mass.
    mass: Option<SparseColMat<usize, f64>>,
    /// For a mixed pencil: the positions of the Krylov rows in `K` and `K(σ)` itself.
    saddle: Option<Saddle>,
}

/// The saddle system of a mixed pencil in its elimination order.
struct Saddle {
    /// `positions[i]` is the row of `K`'s elimination order holding Krylov row `i` (ascending).
    positions: Vec<usize>,
    /// `K(σ) = base − σ · shift_part`, full symmetric storage, permuted to `K`'s elimination
    /// order (the residuals of iterative refinement).
    base: SparseColMat<usize, f64>,
    shift_part: SparseColMat<usize, f64>,
}

/// Buffers of a refined saddle solve (each `n1 + n2` rows; resized as needed).
#[derive(Default)]
pub(crate) struct SaddleScratch {
    rhs: Vec<Row>,
    solution: Vec<Row>,
    residual: Vec<Row>,
    product: Vec<Row>,
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
    /// then the `n2` unknowns `x`) whose first factorization is `ldlt`, with
    /// `K(σ) = base − σ · shift_part` (full symmetric storage, input order).
    pub(crate) fn saddle(
        ldlt: &SparseLdlt,
        inner: usize,
        mass: Option<SparseColMatRef<'_, usize, f64>>,
        (base, shift_part): (
            SparseColMatRef<'_, usize, f64>,
            SparseColMatRef<'_, usize, f64>,
        ),
    ) -> Result<Self, SolverError> {
        let rows = ldlt.dimension();
        let elimination: Vec<usize> = match ldlt.elimination_order() {
            Some(order) => order.to_vec(),
            None => (0..rows).collect(),
        };
        let positions: Vec<usize> = (0..rows).filter(|&k| elimination[k] >= inner).collect();
        let order = positions.iter().map(|&k| elimination[k] - inner).collect();
        let saddle = Saddle {
            positions,
            base: permuted(base, &elimination)?,
            shift_part: permuted(shift_part, &elimination)?,
        };
        Self::with_order(Some(order), mass, Some(saddle))
    }

    fn with_order(
        order: Option<Vec<usize>>,
        mass: Option<SparseColMatRef<'_, usize, f64>>,
        saddle: Option<Saddle>,
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
    /// The shift σ of the factored matrix.
    shift: f64,
    frame: std::sync::Arc<KrylovFrame>,
}

impl ShiftFactor {
    pub(crate) fn new(ldlt: SparseLdlt, shift: f64, frame: std::sync::Arc<KrylovFrame>) -> Self {
        Self { ldlt, shift, frame }
    }

    /// Solves of the factorization per right-hand side of [`Self::solve_rows_refined`] (2 for
    /// a mixed pencil, whose solves are refined once; 1 otherwise).
    pub(crate) fn refined_solve_cost(&self) -> usize {
        if self.frame.saddle.is_some() {
            2
        } else {
            1
        }
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
        let Some(saddle) = &self.frame.saddle else {
            self.ldlt.solve_rows_in_elimination_order(rows);
            return;
        };
        scatter(rows, &saddle.positions, self.ldlt.dimension(), buffer);
        self.ldlt.solve_rows_in_elimination_order(buffer);
        for (row, &k) in rows.iter_mut().zip(&saddle.positions) {
            *row = buffer[k];
        }
    }

    /// [`Self::solve_rows`] with one step of iterative refinement on the saddle system of a
    /// mixed pencil (see the module documentation); the plain solve for a standard pencil.
    pub(crate) fn solve_rows_refined(&self, rows: &mut [Row], scratch: &mut SaddleScratch) {
        let Some(saddle) = &self.frame.saddle else {
            self.ldlt.solve_rows_in_elimination_order(rows);
            return;
        };
        let total = self.ldlt.dimension();
        scatter(rows, &saddle.positions, total, &mut scratch.rhs);
        scratch.solution.clone_from(&scratch.rhs);
        self.ldlt
            .solve_rows_in_elimination_order(&mut scratch.solution);
        // r = b − K z, K z = base z − σ · shift_part z.
        scratch.residual.resize(total, [0.0; 8]);
        scratch.product.resize(total, [0.0; 8]);
        gather_times(
            saddle.base.as_ref(),
            &scratch.solution,
            &mut scratch.residual,
        );
        gather_times(
            saddle.shift_part.as_ref(),
            &scratch.solution,
            &mut scratch.product,
        );
        for ((r, p), b) in scratch
            .residual
            .iter_mut()
            .zip(&scratch.product)
            .zip(&scratch.rhs)
        {
            *r = std::array::from_fn(|j| b[j] - (r[j] - self.shift * p[j]));
        }
        self.ldlt
            .solve_rows_in_elimination_order(&mut scratch.residual);
        for (row, &k) in rows.iter_mut().zip(&saddle.positions) {
            *row = std::array::from_fn(|j| scratch.solution[k][j] + scratch.residual[k][j]);
        }
    }

    /// Overwrites the `n × r` block `rhs` (input order) with `(A − σM)⁻¹ rhs` (refined once
    /// for a mixed pencil, see [`Self::solve_rows_refined`]).
    pub(crate) fn solve_in_place(&self, mut rhs: MatMut<'_, f64>) {
        if self.frame.saddle.is_none() {
            self.ldlt.solve_in_place(rhs);
            return;
        }
        let order = self.krylov_order().unwrap_or(&[]);
        let mut scratch = SaddleScratch::default();
        for first in (0..rhs.ncols()).step_by(8) {
            let width = 8.min(rhs.ncols() - first);
            let mut rows: Vec<Row> = order
                .iter()
                .map(|&i| {
                    std::array::from_fn(|j| if j < width { rhs[(i, first + j)] } else { 0.0 })
                })
                .collect();
            self.solve_rows_refined(&mut rows, &mut scratch);
            for (row, &i) in rows.iter().zip(order) {
                for j in 0..width {
                    rhs[(i, first + j)] = row[j];
                }
            }
        }
    }
}

/// `buffer` (`total` rows) ← the rows `rows` at `positions`, zero elsewhere.
fn scatter(rows: &[Row], positions: &[usize], total: usize, buffer: &mut Vec<Row>) {
    buffer.clear();
    buffer.resize(total, [0.0; 8]);
    for (row, &k) in rows.iter().zip(positions) {
        buffer[k] = *row;
    }
}

/// The upper triangle of `K(σ) = [[−W, d1ᵀ], [d1, −σN]]` for every σ (rows `0..n1` the `u`
/// unknowns, `n1..n1 + n2` the `ψ` unknowns).
pub(crate) fn saddle_pattern(
    w_upper: &SparseColMat<usize, f64>,
    d1: &sprs::CsMat<f64>,
    mass: &StoredMass<'_>,
    n1: usize,
    n2: usize,
) -> Result<ShiftedPattern, SolverError> {
    let total = n1 + n2;
    let mut base = Vec::with_capacity(w_upper.val().len() + d1.nnz());
    let (col_ptr, row_idx) = (w_upper.symbolic().col_ptr(), w_upper.symbolic().row_idx());
    for j in 0..n1 {
        for p in col_ptr[j]..col_ptr[j + 1] {
            base.push(Triplet::new(row_idx[p], j, -w_upper.val()[p]));
        }
    }
    for (value, (f, e)) in d1.iter() {
        base.push(Triplet::new(e, n1 + f, *value));
    }
    let mut shift = Vec::new();
    match mass {
        StoredMass::Diagonal(d) => {
            shift.extend(
                d.iter()
                    .enumerate()
                    .map(|(f, &m)| Triplet::new(n1 + f, n1 + f, m)),
            );
        }
        StoredMass::Sparse(m) => {
            let (col_ptr, row_idx) = (m.full.symbolic().col_ptr(), m.full.symbolic().row_idx());
            for g in 0..n2 {
                for p in col_ptr[g]..col_ptr[g + 1] {
                    if row_idx[p] <= g {
                        shift.push(Triplet::new(n1 + row_idx[p], n1 + g, m.full.val()[p]));
                    }
                }
            }
        }
    }
    let build = |triplets: &[Triplet<usize, usize, f64>]| {
        SparseColMat::try_new_from_triplets(total, total, triplets)
            .map_err(|e| SolverError::Factorization(format!("{e:?}")))
    };
    ShiftedPattern::new(&build(&base)?, &build(&shift)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ordering::FillOrdering;
    use faer::sparse::Triplet;
    use faer::Mat;

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
            let full = |shifted: bool| {
                let mut triplets = Vec::new();
                for j in 0..n1 + n2 {
                    for i in 0..n1 + n2 {
                        let value = match (i < n1, j < n1, shifted) {
                            (true, true, false) => -w[(i, j)],
                            (true, false, false) => d1[(j - n1, i)],
                            (false, true, false) => d1[(i - n1, j)],
                            (false, false, true) if i == j => n[i - n1],
                            _ => 0.0,
                        };
                        if value != 0.0 {
                            triplets.push(Triplet::new(i, j, value));
                        }
                    }
                }
                SparseColMat::try_new_from_triplets(n1 + n2, n1 + n2, &triplets).expect("valid")
            };
            let (base, shift_part) = (full(false), full(true));
            let frame = KrylovFrame::saddle(&ldlt, n1, None, (base.as_ref(), shift_part.as_ref()))
                .expect("frame");
            let order = frame.order.clone().expect("an order");
            let factor = ShiftFactor::new(ldlt, sigma, std::sync::Arc::new(frame));
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
            let mut refined: Vec<Row> = order
                .iter()
                .map(|&f| std::array::from_fn(|j| if j == 0 { b[f] } else { 0.0 }))
                .collect();
            factor.solve_rows_refined(&mut refined, &mut SaddleScratch::default());
            for (row, &f) in refined.iter().zip(&order) {
                assert!((row[0] - x[f]).abs() <= 1e-12, "refined solve");
            }
            let mut column = Mat::from_fn(n2, 1, |i, _| b[i]);
            factor.solve_in_place(column.as_mut());
            for i in 0..n2 {
                assert!((column[(i, 0)] - x[i]).abs() <= 1e-12);
            }
        }
    }
}
