//! The triangular solves of a supernodal `LDLᵀ` factor with right-hand sides packed in rows of
//! [`WIDTH`] (one 64-byte cache line per unknown), written by hand.
//!
//! Why: faer's supernodal solve (0.24) handles each supernode with a dense triangular solve and
//! a matrix product through its general kernels, then scatters the product into the
//! column-major right-hand side one column at a time, and applies the fill-reducing
//! permutation column by column before and after. On surface meshes most supernodes have a
//! handful of columns, so the per-supernode dispatch and the column-wise scatters dominate.
//! Here every update of an unknown is an 8-wide multiply–add on its packed row, the
//! columns of a supernode go in groups of four (each row below them is loaded and stored once
//! per group, not once per column), the diagonal scaling is folded
//! into the forward pass, the permutation is applied while packing, and the loops are compiled
//! with and without AVX2 + FMA (chosen at run time, `kernel_dispatch.rs`). Groups of six or eight columns, and an
//! AVX-512 build of the loops, were slower (timings in `docs/performance.md`).

use faer::perm::PermRef;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLdltRef, SymbolicSupernodalCholesky};
use faer::MatMut;

use crate::kernel_dispatch::{fma_dispatch, multiply_add};
use crate::packed_rows::{Row, WIDTH};

/// Overwrites `rhs` (`n × r`) with the solution of `P L D Lᵀ Pᵀ X = rhs` for the supernodal
/// factor (`symbolic`, `values`) and the fill-reducing permutation `perm` (`None`: identity;
/// faer's convention: row `i` of the permuted system is row `perm.forward[i]` of the original),
/// [`WIDTH`] columns at a time.
pub(crate) fn solve_packed(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    values: &[f64],
    perm: Option<PermRef<'_, usize>>,
    rhs: MatMut<'_, f64>,
) {
    solve_packed_with(symbolic, values, perm, rhs, solve_rows);
}

/// Overwrites the packed rows `x` (`n` rows of up to [`WIDTH`] right-hand sides, in the
/// factor's elimination order: no permutation) with the solution of `L D Lᵀ X = x`.
pub(crate) fn solve_packed_rows(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    values: &[f64],
    x: &mut [Row],
) {
    solve_rows(SupernodalLdltRef::new(symbolic, values), x);
}

/// [`solve_packed`] with the portable loops whatever the CPU (to test them where FMA exists).
#[cfg(test)]
pub(crate) fn solve_packed_portable(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    values: &[f64],
    perm: Option<PermRef<'_, usize>>,
    rhs: MatMut<'_, f64>,
) {
    solve_packed_with(symbolic, values, perm, rhs, solve_rows_body::<false>);
}

/// [`solve_packed`] with `solve` for the packed triangular solves.
fn solve_packed_with(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    values: &[f64],
    perm: Option<PermRef<'_, usize>>,
    mut rhs: MatMut<'_, f64>,
    solve: fn(SupernodalLdltRef<'_, usize, f64>, &mut [Row]),
) {
    let n = rhs.nrows();
    let factor = SupernodalLdltRef::new(symbolic, values);
    let mut x: Vec<Row> = vec![[0.0; WIDTH]; n];
    let mut first = 0;
    while first < rhs.ncols() {
        let width = WIDTH.min(rhs.ncols() - first);
        // Row i of the permuted system is row forward[i] of rhs; one column at a time, so the
        // random accesses stay inside one contiguous column.
        let forward = perm.map(|p| p.arrays().0);
        x.iter_mut().for_each(|row| *row = [0.0; WIDTH]);
        for j in 0..width {
            let column = rhs.rb().col(first + j);
            match forward {
                Some(forward) => {
                    for (row, &from) in x.iter_mut().zip(forward) {
                        row[j] = column[from];
                    }
                }
                None => {
                    for (row, value) in x.iter_mut().zip(column.iter()) {
                        row[j] = *value;
                    }
                }
            }
        }
        solve(factor, &mut x);
        for j in 0..width {
            let mut column = rhs.rb_mut().col_mut(first + j);
            match forward {
                Some(forward) => {
                    for (row, &to) in x.iter().zip(forward) {
                        column[to] = row[j];
                    }
                }
                None => {
                    for (row, value) in x.iter().zip(column.iter_mut()) {
                        *value = row[j];
                    }
                }
            }
        }
        first += width;
    }
}

/// `x ← (L D Lᵀ)⁻¹ x` on packed rows.
fn solve_rows(factor: SupernodalLdltRef<'_, usize, f64>, x: &mut [Row]) {
    fma_dispatch!(solve_rows_body(factor: SupernodalLdltRef<'_, usize, f64>, x: &mut [Row]));
}

/// `bᵀ (L D Lᵀ)⁻¹ b` for each of the packed columns `b` of `x` (`n` rows in the factor's
/// elimination order; overwritten with `D⁻¹ L⁻¹ b`): the forward pass only, then
/// `Σ_k D_k z_k²` with `z = D⁻¹ L⁻¹ b`. Half the memory traffic of a solve followed by a
/// product, and for a positive definite factor a sum of positive terms.
pub(crate) fn inverse_energy_rows(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    values: &[f64],
    x: &mut [Row],
) -> Row {
    let factor = SupernodalLdltRef::new(symbolic, values);
    fma_dispatch!(forward_rows_body(factor: SupernodalLdltRef<'_, usize, f64>, x: &mut [Row]));
    let mut energy = [0.0; WIDTH];
    for s in 0..factor.symbolic().n_supernodes() {
        let node = factor.supernode(s);
        let (start, block) = (node.start(), node.val());
        for c in 0..block.ncols() {
            let (pivot, z) = (block[(c, c)], &x[start + c]);
            for j in 0..WIDTH {
                energy[j] += pivot * z[j] * z[j];
            }
        }
    }
    energy
}

/// Columns of a supernode handled together: their values stay in registers while every row
/// below them is read and written once per group instead of once per column.
const GROUP: usize = 4;

/// Column `c` of a supernode's block (its unit lower-triangular part, then the rows of its
/// pattern), contiguous.
#[inline(always)]
fn block_column<'a>(block: faer::MatRef<'a, f64>, c: usize) -> &'a [f64] {
    block
        .col(c)
        .try_as_col_major()
        .expect("contiguous supernode")
        .as_slice()
}

#[inline(always)]
fn solve_rows_body<const FUSED: bool>(factor: SupernodalLdltRef<'_, usize, f64>, x: &mut [Row]) {
    forward_rows_body::<FUSED>(factor, x);
    // Backward: Lᵀ x = z, supernodes and groups of columns in reverse.
    for s in (0..factor.symbolic().n_supernodes()).rev() {
        let node = factor.supernode(s);
        let (start, pattern, block) = (node.start(), node.pattern(), node.val());
        let size = block.ncols();
        let mut end = size;
        while end > 0 {
            let first = end.saturating_sub(GROUP);
            match end - first {
                4 => backward_group::<4, FUSED>(ColumnGroup::new(block, start, pattern, first), x),
                3 => backward_group::<3, FUSED>(ColumnGroup::new(block, start, pattern, first), x),
                2 => backward_group::<2, FUSED>(ColumnGroup::new(block, start, pattern, first), x),
                _ => backward_group::<1, FUSED>(ColumnGroup::new(block, start, pattern, first), x),
            }
            end = first;
        }
    }
}

/// The forward pass and diagonal of [`solve_rows_body`]: `x ← D⁻¹ L⁻¹ x`.
#[inline(always)]
fn forward_rows_body<const FUSED: bool>(factor: SupernodalLdltRef<'_, usize, f64>, x: &mut [Row]) {
    // Forward and diagonal: L D z = b, supernode by supernode, a group of columns at a time.
    for s in 0..factor.symbolic().n_supernodes() {
        let node = factor.supernode(s);
        let (start, pattern, block) = (node.start(), node.pattern(), node.val());
        let size = block.ncols();
        let mut first = 0;
        while first < size {
            let width = GROUP.min(size - first);
            match width {
                4 => forward_group::<4, FUSED>(ColumnGroup::new(block, start, pattern, first), x),
                3 => forward_group::<3, FUSED>(ColumnGroup::new(block, start, pattern, first), x),
                2 => forward_group::<2, FUSED>(ColumnGroup::new(block, start, pattern, first), x),
                _ => forward_group::<1, FUSED>(ColumnGroup::new(block, start, pattern, first), x),
            }
            first += width;
        }
    }
}

/// Columns `first..first + K` of a supernode (`block`: its `(size + pattern) × size` values,
/// column-major; its unknowns start at `start`).
struct ColumnGroup<'a, const K: usize> {
    /// The group's columns of the block, whole.
    columns: [&'a [f64]; K],
    /// Column of the block the group starts at.
    first: usize,
    /// Unknown of the group's first column.
    unknown: usize,
    /// Unknowns of the rows of the block after the group: the rest of the supernode's own
    /// unknowns, then its pattern.
    later: std::iter::Chain<std::ops::Range<usize>, std::iter::Copied<std::slice::Iter<'a, usize>>>,
}

impl<'a, const K: usize> ColumnGroup<'a, K> {
    #[inline(always)]
    fn new(block: faer::MatRef<'a, f64>, start: usize, pattern: &'a [usize], first: usize) -> Self {
        let size = block.ncols();
        Self {
            columns: std::array::from_fn(|k| block_column(block, first + k)),
            first,
            unknown: start + first,
            later: (start + first + K..start + size).chain(pattern.iter().copied()),
        }
    }

    /// `L[first + later, first + k]`: the group's triangle.
    #[inline(always)]
    fn triangle(&self, later: usize, k: usize) -> f64 {
        self.columns[k][self.first + later]
    }

    /// The later rows, each as its unknown and the group's `K` values of `L` on it.
    #[inline(always)]
    fn later_rows(self) -> impl Iterator<Item = (usize, [f64; K])> + 'a {
        let below: [&[f64]; K] = std::array::from_fn(|k| &self.columns[k][self.first + K..]);
        self.later
            .enumerate()
            .map(move |(i, unknown)| (unknown, std::array::from_fn(|k| below[k][i])))
    }
}

/// Forward substitution of a group of `K` columns of a supernode: the triangle among them,
/// then every later row of the block loses `Σ_k L[row, first + k] · x[start + first + k]`, and
/// the group's values are divided by their pivots.
#[inline(always)]
fn forward_group<const K: usize, const FUSED: bool>(group: ColumnGroup<'_, K>, x: &mut [Row]) {
    let unknown = group.unknown;
    let mut values: [Row; K] = std::array::from_fn(|k| x[unknown + k]);
    for k in 0..K {
        for later in k + 1..K {
            let source = values[k];
            subtract_scaled::<FUSED>(&mut values[later], group.triangle(later, k), &source);
        }
    }
    // The group's part of y is final: z = D⁻¹ y (D is on the diagonal of the block).
    let pivots: [f64; K] = std::array::from_fn(|k| group.triangle(k, k));
    for (target, l) in group.later_rows() {
        let mut sum = x[target];
        for k in 0..K {
            subtract_scaled::<FUSED>(&mut sum, l[k], &values[k]);
        }
        x[target] = sum;
    }
    for (k, value) in values.iter().enumerate() {
        let inverse = pivots[k].recip();
        x[unknown + k] = value.map(|v| v * inverse);
    }
}

/// Backward substitution of a group of `K` columns of a supernode: each loses
/// `Σ_row L[row, column] · x[row]` over the later rows of the block (every row read once for
/// the whole group), then the triangle among them.
#[inline(always)]
fn backward_group<const K: usize, const FUSED: bool>(group: ColumnGroup<'_, K>, x: &mut [Row]) {
    let unknown = group.unknown;
    let mut values: [Row; K] = std::array::from_fn(|k| x[unknown + k]);
    let triangle: [[f64; K]; K] = std::array::from_fn(|later| {
        std::array::from_fn(|k| {
            if later > k {
                group.triangle(later, k)
            } else {
                0.0
            }
        })
    });
    for (source, l) in group.later_rows() {
        let source = x[source];
        for k in 0..K {
            subtract_scaled::<FUSED>(&mut values[k], l[k], &source);
        }
    }
    for k in (0..K).rev() {
        for later in k + 1..K {
            let source = values[later];
            subtract_scaled::<FUSED>(&mut values[k], triangle[later][k], &source);
        }
    }
    for (k, value) in values.iter().enumerate() {
        x[unknown + k] = *value;
    }
}

/// `target − l · source` row-wise, fused when `FUSED` (only in functions compiled with FMA).
#[inline(always)]
fn subtract_scaled<const FUSED: bool>(target: &mut Row, l: f64, source: &Row) {
    for j in 0..WIDTH {
        target[j] = multiply_add::<FUSED>(-l, source[j], target[j]);
    }
}
