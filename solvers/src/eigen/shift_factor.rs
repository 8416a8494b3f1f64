//! [`ShiftFactor`]: the factorization of a pencil at one shift σ, and how the Krylov vectors
//! are solved with it.
//!
//! - Standard pencils factor `A − σM` (`n × n`); the Krylov vectors are kept in its
//!   elimination order, so a solve needs no permutation.
//! - Mixed pencils (`A = d1 W⁻¹ d1ᵀ`, dimension `n2`) solve `(A − σN) x = b` as the saddle
//!   system `K(σ) [u; x] = [0; b]`, `K(σ) = [[−W, d1ᵀ], [d1, −σN]]` (`n1 + n2`), with
//!   `u = W⁻¹ d1ᵀ x`.
//!   - With a diagonal `N` they factor the Schur complement of `−σN` in it, times `−σ`: the
//!     edges' matrix `C(σ) = d1ᵀ N⁻¹ d1 − σW` (`n1 × n1`, the pattern of `W`: for Whitney
//!     forms the 1-form pencil `(d1ᵀ M2 d1, M1)` at σ). A solve of `K(σ) [u; x] = [g; b]` is
//!     `u = C(σ)⁻¹ (σg + d1ᵀ N⁻¹ b)`, then `x = N⁻¹ (d1 u − b) / σ`; the Krylov vectors stay
//!     in the input order. Why: on `bunny-closed.obj` the factor of `C(σ)` has 3.47M entries
//!     for 104,499 rows against `K(σ)`'s 4.04M for 174,165, and a solve of 8 right-hand sides
//!     costs about what the Crouzeix–Raviart matrix's does, where `K(σ)`'s cost 1.6–1.8× as
//!     much (`docs/performance.md`).
//!   - With a sparse `N` they factor `K(σ)` itself. The Krylov vectors (`n2` rows) are kept in
//!     the order in which the `x` unknowns appear in `K`'s elimination order, so a solve
//!     scatters them into the positions of those unknowns (the `u` rows zero), solves, and
//!     gathers them back: two monotone passes, no search.
//!
//! Neither is as accurate as a backward-stable solve of `A − σN`. `LDLᵀ` without pivoting of
//! the indefinite `K(σ)` grows: a `ψ` unknown eliminated before its edges has the pivot
//! `−σN_ff`, and the edges' Schur complement then carries `d1ᵀ d1 / (σN)`, so a solve is
//! accurate only to about `ε ‖d1‖² / (σ N_min ‖W‖)` relative; `C(σ)` carries that term from the
//! start. The Krylov expansion tolerates that (the computed `LDLᵀ` is exactly symmetric, so the
//! operator is a nearby self-adjoint one, and the Rayleigh–Ritz against the true `A` restores
//! the values), but the eigenvectors are then only that accurate, and their eigenfield
//! residuals (see `refinement.rs`) stay far above the target, out of reach of further steps
//! with the same factorization (with `C(σ)` on `bunny-closed.obj`: 280 of 500 pairs above the
//! target, the worst at 2.1e-7). So the solves that set the vectors' accuracy — the
//! inverse-iteration step of every locked vector and the refinement — take one step of
//! iterative refinement on the saddle system ([`ShiftFactor::solve_rows_refined`]: its residual
//! from products with `W` and `d1`, and one more solve), which restores the accuracy of a
//! backward-stable solve. Standard pencils solve as before.
//!
//! [`KrylovFrame`] holds what depends only on the elimination order (the same for every
//! shift of a pencil: its factorizations share one fill-reducing ordering): the Krylov order,
//! the sparse mass in it, and the incidence or the saddle positions of a mixed pencil. It is
//! formed once per pencil.

use super::mass::permuted;
use super::mixed_operator::ordered_incidence;
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
    /// For a mixed pencil: how its solves go through the factored matrix.
    mixed: Option<MixedSolve>,
}

/// The factored matrix of a mixed pencil and how a solve goes through it (see the module
/// documentation).
enum MixedSolve {
    /// `K(σ)`, for a sparse `N`.
    Saddle(Saddle),
    /// `C(σ) = d1ᵀ N⁻¹ d1 − σW`, for a diagonal `N`.
    EdgeSchur(EdgeSchur),
}

/// What a solve through `C(σ) = d1ᵀ N⁻¹ d1 − σW` needs besides its factorization: the Krylov
/// vectors (`n2` rows) are in the input order, the edges (`n1`) in `C`'s elimination order.
struct EdgeSchur {
    /// `d1` (`n2 × n1`): column `k` gathers `(d1ᵀ y)` of the `k`-th eliminated edge.
    by_edge: SparseColMat<usize, f64>,
    /// `d1ᵀ` (`n1 × n2`, rows in elimination order): column `f` gathers `(d1 u)_f`.
    by_face: SparseColMat<usize, f64>,
    /// `N`, the `n2` masses (kept beside their inverses so that the refinement's residual
    /// multiplies by `N` itself).
    mass: Vec<f64>,
    /// `N⁻¹`, the `n2` inverse masses.
    inverse_mass: Vec<f64>,
    /// `W` (`n1 × n1`, full symmetric storage, permuted to `C`'s elimination order), for the
    /// residuals of iterative refinement.
    w: SparseColMat<usize, f64>,
}

impl EdgeSchur {
    /// Row `f` of `d1 u` for the packed edge rows `u` (`n1` rows, elimination order).
    fn face_row_of_d1_times(&self, f: usize, u: &[Row]) -> Row {
        let (col_ptr, row_idx, values) = (
            self.by_face.symbolic().col_ptr(),
            self.by_face.symbolic().row_idx(),
            self.by_face.val(),
        );
        let mut sum = [0.0; 8];
        for p in col_ptr[f]..col_ptr[f + 1] {
            for (s, u) in sum.iter_mut().zip(&u[row_idx[p]]) {
                *s += values[p] * u;
            }
        }
        sum
    }
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

/// Buffers of a refined solve of a mixed pencil (at most `n1 + n2` rows each; resized as needed).
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
        Self::with_order(Some(order), mass, Some(MixedSolve::Saddle(saddle)))
    }

    /// The frame of a mixed pencil with the diagonal mass `N` (`mass`, `n2` positive values)
    /// whose first factorization `ldlt` is of `C(σ) = d1ᵀ N⁻¹ d1 − σW` (`n1 × n1`), with `d1`
    /// (`incidence`, `n2 × n1`, input order): the Krylov vectors stay in the input order.
    /// `w_full` is `W` in full symmetric storage, input order.
    pub(crate) fn edge_schur(
        ldlt: &SparseLdlt,
        incidence: SparseColMatRef<'_, usize, f64>,
        mass: &[f64],
        w_full: SparseColMatRef<'_, usize, f64>,
    ) -> Result<Self, SolverError> {
        let elimination: Vec<usize> = match ldlt.elimination_order() {
            Some(order) => order.to_vec(),
            None => (0..ldlt.dimension()).collect(),
        };
        let mut position = vec![0; elimination.len()];
        for (k, &e) in elimination.iter().enumerate() {
            position[e] = k;
        }
        let (by_edge, by_face) = ordered_incidence(incidence, &position)?;
        let schur = EdgeSchur {
            by_edge,
            by_face,
            mass: mass.to_vec(),
            inverse_mass: mass.iter().map(|m| m.recip()).collect(),
            w: permuted(w_full, &elimination)?,
        };
        Self::with_order(None, None, Some(MixedSolve::EdgeSchur(schur)))
    }

    fn with_order(
        order: Option<Vec<usize>>,
        mass: Option<SparseColMatRef<'_, usize, f64>>,
        mixed: Option<MixedSolve>,
    ) -> Result<Self, SolverError> {
        let mass = match (mass, &order) {
            (Some(m), Some(order)) => Some(permuted(m, order)?),
            (Some(m), None) => Some(permuted(m, &(0..m.nrows()).collect::<Vec<_>>())?),
            (None, _) => None,
        };
        Ok(Self { order, mass, mixed })
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
        if self.frame.mixed.is_some() {
            2
        } else {
            1
        }
    }

    /// The inertia of the factored matrix (`A − σM`, `K(σ)` with its `n1` negatives of `−W`, or
    /// `C(σ)`: see [`super::pencil::Pencil`] for the counts that follow from each).
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
    /// `buffer` holds the system of a mixed pencil (resized, contents unspecified).
    pub(crate) fn solve_rows(&self, rows: &mut [Row], buffer: &mut Vec<Row>) {
        let saddle = match &self.frame.mixed {
            None => {
                self.ldlt.solve_rows_in_elimination_order(rows);
                return;
            }
            Some(MixedSolve::EdgeSchur(schur)) => {
                self.solve_through_edges(schur, None, rows, buffer);
                return;
            }
            Some(MixedSolve::Saddle(saddle)) => saddle,
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
        let saddle = match &self.frame.mixed {
            None => {
                self.ldlt.solve_rows_in_elimination_order(rows);
                return;
            }
            Some(MixedSolve::EdgeSchur(schur)) => {
                self.solve_through_edges_refined(schur, rows, scratch);
                return;
            }
            Some(MixedSolve::Saddle(saddle)) => saddle,
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
        if self.frame.mixed.is_none() {
            self.ldlt.solve_in_place(rhs);
            return;
        }
        let identity: Vec<usize>;
        let order = match self.krylov_order() {
            Some(order) => order,
            None => {
                identity = (0..rhs.nrows()).collect();
                &identity
            }
        };
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

    /// The saddle system `K(σ) [u; x] = [g; b]` solved through `C(σ)` (see the module
    /// documentation): `t = N⁻¹ b`, `u = C(σ)⁻¹ (σg + d1ᵀ t)`, `x = (N⁻¹ d1 u − t) / σ`. `rows`
    /// holds `b` (`n2` rows, input order) and is overwritten with `x`; `edge_rhs` is `g`
    /// (`n1` rows, elimination order; `None`: zero, which makes `x = (A − σN)⁻¹ b`); `u` is
    /// left in `buffer` (resized to `n1` rows).
    fn solve_through_edges(
        &self,
        schur: &EdgeSchur,
        edge_rhs: Option<&[Row]>,
        rows: &mut [Row],
        buffer: &mut Vec<Row>,
    ) {
        for (row, inverse) in rows.iter_mut().zip(&schur.inverse_mass) {
            row.iter_mut().for_each(|v| *v *= inverse);
        }
        buffer.resize(schur.by_edge.ncols(), [0.0; 8]);
        gather_times(schur.by_edge.as_ref(), rows, buffer);
        if let Some(g) = edge_rhs {
            for (target, g) in buffer.iter_mut().zip(g) {
                for (t, g) in target.iter_mut().zip(g) {
                    *t += self.shift * g;
                }
            }
        }
        self.ldlt.solve_rows_in_elimination_order(buffer);
        let inverse_shift = self.shift.recip();
        for (f, (row, inverse)) in rows.iter_mut().zip(&schur.inverse_mass).enumerate() {
            let d1u = schur.face_row_of_d1_times(f, buffer);
            for (x, d) in row.iter_mut().zip(d1u) {
                *x = (inverse * d - *x) * inverse_shift;
            }
        }
    }

    /// [`Self::solve_through_edges`] of `(A − σN) x = b` with one step of iterative refinement on
    /// the saddle system (see the module documentation): the residual `[g; r] = [0; b] − K(σ)
    /// [u; x]` (products with `W` and `d1` only), then `[u; x] += K(σ)⁻¹ [g; r]` through `C(σ)`.
    fn solve_through_edges_refined(
        &self,
        schur: &EdgeSchur,
        rows: &mut [Row],
        scratch: &mut SaddleScratch,
    ) {
        let n1 = schur.by_edge.ncols();
        scratch.rhs.clear();
        scratch.rhs.extend_from_slice(rows);
        self.solve_through_edges(schur, None, rows, &mut scratch.solution);
        // g = W u − d1ᵀ x (the first block of K(σ) [u; x] is −W u + d1ᵀ x, its right side 0).
        scratch.residual.resize(n1, [0.0; 8]);
        scratch.product.resize(n1, [0.0; 8]);
        gather_times(schur.w.as_ref(), &scratch.solution, &mut scratch.residual);
        gather_times(schur.by_edge.as_ref(), rows, &mut scratch.product);
        for (g, d) in scratch.residual.iter_mut().zip(&scratch.product) {
            *g = std::array::from_fn(|j| g[j] - d[j]);
        }
        // r = b − d1 u + σ N x, in place of b.
        for (f, (b, x)) in scratch.rhs.iter_mut().zip(rows.iter()).enumerate() {
            let d1u = schur.face_row_of_d1_times(f, &scratch.solution);
            let weight = self.shift * schur.mass[f];
            *b = std::array::from_fn(|j| b[j] - d1u[j] + weight * x[j]);
        }
        self.solve_through_edges(
            schur,
            Some(&scratch.residual),
            &mut scratch.rhs,
            &mut scratch.solution,
        );
        for (x, dx) in rows.iter_mut().zip(&scratch.rhs) {
            *x = std::array::from_fn(|j| x[j] + dx[j]);
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

    /// A mixed pencil with a diagonal mass factors `C(σ) = d1ᵀ N⁻¹ d1 − σW`: the count below σ
    /// (`negatives(C(σ)) + n2 − n1`, none below a negative shift) is the dense one, and the
    /// plain, the refined and the column solve through it solve `(A − σN) x = b`, for shifts in
    /// the spectrum and one below it (`d1` with more edges than faces, like a mesh's).
    #[test]
    fn edge_schur_counts_and_solves_the_reduced_system() {
        use super::super::mass::MassMatrix;
        use super::super::mixed_operator::small_mixed_matrices;
        use super::super::pencil::Pencil;
        use super::super::statistics::Phase;
        let (n1, n2) = (11, 6);
        let (w, d1, a) = small_mixed_matrices(n1, n2, 2);
        let n: Vec<f64> = (0..n2).map(|f| 0.5 + f as f64 / 5.0).collect();
        let (values, _) =
            crate::dense_eigen::dense_generalized_eigen(a.as_ref(), &n).expect("eigen");
        let pencil = Pencil::mixed(&w, &d1, MassMatrix::Diagonal(&n)).expect("a valid pencil");
        let shifts = [
            -0.5 * values[n2 - 1],
            0.5 * (values[1] + values[2]),
            0.5 * (values[4] + values[5]),
        ];
        for sigma in shifts {
            let (factor, count) = pencil
                .factor(sigma, Phase::Counting, faer::Par::Seq)
                .expect("factors");
            let below = values.iter().filter(|&&v| v < sigma).count();
            assert_eq!(count.below, below, "σ = {sigma}");
            assert!(factor.krylov_order().is_none(), "the input order");
            let b: Vec<f64> = (0..n2).map(|f| f as f64 - 1.5).collect();
            let shifted = Mat::from_fn(n2, n2, |i, j| {
                a[(i, j)] - if i == j { sigma * n[i] } else { 0.0 }
            });
            let residual = |x: &dyn Fn(usize) -> f64| {
                (0..n2)
                    .map(|i| ((0..n2).map(|j| shifted[(i, j)] * x(j)).sum::<f64>() - b[i]).abs())
                    .fold(0.0, f64::max)
            };
            // Row `i` of the packed rows is unknown `order[i]`.
            let order: Vec<usize> = match factor.krylov_order() {
                Some(order) => order.to_vec(),
                None => (0..n2).collect(),
            };
            let rows = || -> Vec<Row> {
                order
                    .iter()
                    .map(|&f| std::array::from_fn(|j| if j == 0 { b[f] } else { 0.0 }))
                    .collect()
            };
            let unknowns = |rows: &[Row]| {
                let mut x = vec![0.0; n2];
                for (row, &f) in rows.iter().zip(&order) {
                    x[f] = row[0];
                }
                x
            };
            let mut plain = rows();
            factor.solve_rows(&mut plain, &mut Vec::new());
            let x = unknowns(&plain);
            assert!(residual(&|j| x[j]) <= 1e-12, "σ = {sigma}: plain solve");
            let mut refined = rows();
            factor.solve_rows_refined(&mut refined, &mut SaddleScratch::default());
            let x = unknowns(&refined);
            assert!(residual(&|j| x[j]) <= 1e-12, "σ = {sigma}: refined solve");
            let mut column = Mat::from_fn(n2, 1, |i, _| b[i]);
            factor.solve_in_place(column.as_mut());
            assert!(
                residual(&|j| column[(j, 0)]) <= 1e-12,
                "σ = {sigma}: column solve"
            );
        }
    }

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
