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
//!
//! Where the factor's elimination tree splits into two independent parts, each pass runs them
//! on two threads with the same operations in the same order as one thread
//! (`packed_solve_split.rs`), so the solutions do not depend on it.

use crate::calling_thread::join;
use faer::perm::PermRef;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLdltRef, SymbolicSupernodalCholesky};
use faer::MatMut;

use crate::kernel_dispatch::{fma_dispatch, multiply_add};
use crate::packed_rows::{Row, WIDTH};
use crate::packed_solve_split::{SolveSplit, NOT_KEPT};

/// Overwrites `rhs` (`n × r`) with the solution of `P L D Lᵀ Pᵀ X = rhs` for the supernodal
/// factor (`symbolic`, `values`) and the fill-reducing permutation `perm` (`None`: identity;
/// faer's convention: row `i` of the permuted system is row `perm.forward[i]` of the original),
/// [`WIDTH`] columns at a time, on two threads where `split` (made for `symbolic`) is given.
pub(crate) fn solve_packed(
    factor: PackedFactor<'_>,
    perm: Option<PermRef<'_, usize>>,
    rhs: MatMut<'_, f64>,
) {
    solve_packed_with(factor, perm, rhs, solve_rows);
}

/// Overwrites the packed rows `x` (`n` rows of up to [`WIDTH`] right-hand sides, in the
/// factor's elimination order: no permutation) with the solution of `L D Lᵀ X = x`.
pub(crate) fn solve_packed_rows(factor: PackedFactor<'_>, x: &mut [Row]) {
    solve_rows(factor, x);
}

/// A supernodal `LDLᵀ` factor as the packed solves take it: its symbolic part, its values and,
/// if one was made for it, the split of its supernodes between two threads.
#[derive(Clone, Copy)]
pub(crate) struct PackedFactor<'a> {
    pub symbolic: &'a SymbolicSupernodalCholesky<usize>,
    pub values: &'a [f64],
    pub split: Option<&'a SolveSplit>,
}

impl<'a> PackedFactor<'a> {
    fn supernodal(self) -> SupernodalLdltRef<'a, usize, f64> {
        SupernodalLdltRef::new(self.symbolic, self.values)
    }
}

/// [`solve_packed`] with the portable loops whatever the CPU (to test them where FMA exists).
#[cfg(test)]
pub(crate) fn solve_packed_portable(
    factor: PackedFactor<'_>,
    perm: Option<PermRef<'_, usize>>,
    rhs: MatMut<'_, f64>,
) {
    solve_packed_with(factor, perm, rhs, |factor, x| {
        let factor = factor.supernodal();
        let n = factor.symbolic().n_supernodes();
        forward_nodes_body::<false>(factor, 0..n, x, 0, None);
        let end = x.len();
        backward_nodes_body::<false>(factor, 0..n, x, 0, (&[], end));
    });
}

/// [`solve_packed`] with `solve` for the packed triangular solves.
fn solve_packed_with(
    factor: PackedFactor<'_>,
    perm: Option<PermRef<'_, usize>>,
    mut rhs: MatMut<'_, f64>,
    solve: fn(PackedFactor<'_>, &mut [Row]),
) {
    let n = rhs.nrows();
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

/// `x ← (L D Lᵀ)⁻¹ x` on packed rows: on two threads where the factor has a split, with the
/// same operations in the same order as on one (the results are identical bit for bit).
fn solve_rows(factor: PackedFactor<'_>, x: &mut [Row]) {
    forward_rows(factor, x);
    let supernodal = factor.supernodal();
    let Some(split) = factor.split else {
        let n = supernodal.symbolic().n_supernodes();
        let end = x.len();
        backward(supernodal, 0..n, x, 0, (&[], end));
        return;
    };
    // The top last-to-first, then the two parts at once: each reads the top and writes only
    // its own unknowns.
    let [first, second, top] = split.parts_of(x);
    let top_unknown = split.top_unknown();
    let end = top_unknown + top.len();
    backward(supernodal, split.top_nodes(), top, top_unknown, (&[], end));
    let top = (&*top, top_unknown);
    join(
        || backward(supernodal, split.first_nodes(), first, 0, top),
        || {
            backward(
                supernodal,
                split.second_nodes(),
                second,
                split.second_unknown(),
                top,
            )
        },
    );
}

/// [`backward_nodes_body`] in its best compilation.
fn backward(
    factor: SupernodalLdltRef<'_, usize, f64>,
    nodes: std::ops::Range<usize>,
    part: &mut [Row],
    offset: usize,
    top: (&[Row], usize),
) {
    fma_dispatch!(backward_nodes_body(
        factor: SupernodalLdltRef<'_, usize, f64>,
        nodes: std::ops::Range<usize>,
        part: &mut [Row],
        offset: usize,
        top: (&[Row], usize),
    ));
}

/// `x ← D⁻¹ L⁻¹ x` on packed rows, on two threads where the factor has a split: the two parts
/// at once, each leaving the rows of the top it updates for later ([`forward_tails_body`]
/// replays those updates afterwards, the first part's before the second's, as one thread makes
/// them), then the top.
fn forward_rows(factor: PackedFactor<'_>, x: &mut [Row]) {
    let supernodal = factor.supernodal();
    let Some(split) = factor.split else {
        let n = supernodal.symbolic().n_supernodes();
        forward(supernodal, 0..n, x, 0, None);
        return;
    };
    let mut kept = split.kept_buffer();
    let [first_kept, second_kept] = split.kept_parts(&mut kept);
    let [first, second, top] = split.parts_of(x);
    join(
        || forward(supernodal, split.first_nodes(), first, 0, Some(first_kept)),
        || {
            forward(
                supernodal,
                split.second_nodes(),
                second,
                split.second_unknown(),
                Some(second_kept),
            )
        },
    );
    let (bases, kept, offset) = (split.kept_bases(), kept.as_slice(), split.top_unknown());
    fma_dispatch!(forward_tails_body(
        supernodal: SupernodalLdltRef<'_, usize, f64>,
        bases: &[usize],
        kept: &[Row],
        top: &mut [Row],
        offset: usize,
    ));
    forward(
        supernodal,
        split.top_nodes(),
        top,
        split.top_unknown(),
        None,
    );
}

/// [`forward_nodes_body`] in its best compilation.
fn forward(
    factor: SupernodalLdltRef<'_, usize, f64>,
    nodes: std::ops::Range<usize>,
    part: &mut [Row],
    offset: usize,
    kept: Option<KeptValues<'_>>,
) {
    fma_dispatch!(forward_nodes_body(
        factor: SupernodalLdltRef<'_, usize, f64>,
        nodes: std::ops::Range<usize>,
        part: &mut [Row],
        offset: usize,
        kept: Option<KeptValues<'_>>,
    ));
}

/// `bᵀ (L D Lᵀ)⁻¹ b` for each of the packed columns `b` of `x` (`n` rows in the factor's
/// elimination order; overwritten with `D⁻¹ L⁻¹ b`): the forward pass only, then
/// `Σ_k D_k z_k²` with `z = D⁻¹ L⁻¹ b`. Half the memory traffic of a solve followed by a
/// product, and for a positive definite factor a sum of positive terms.
pub(crate) fn inverse_energy_rows(factor: PackedFactor<'_>, x: &mut [Row]) -> Row {
    forward_rows(factor, x);
    let factor = factor.supernodal();
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

/// The values of the supernodes of one part of a split whose later rows reach into the top,
/// as the forward pass has them before the diagonal scaling (the top's updates from them are
/// made afterwards): supernode `s` keeps its `size` rows from `rows[base[s] − first..]`
/// (`base[s]` = [`NOT_KEPT`]: it reaches no top row).
pub(crate) struct KeptValues<'a> {
    pub base: &'a [usize],
    pub first: usize,
    pub rows: &'a mut [Row],
}

/// Forward substitution and diagonal scaling, `x ← D⁻¹ L⁻¹ x`, over the supernodes `nodes`
/// (ascending) whose unknowns lie in `part` (unknowns `offset..offset + part.len()`), a group of
/// columns at a time: later rows past the end of `part` (the top of a split) are skipped, the
/// values they need kept in `kept`.
#[inline(always)]
fn forward_nodes_body<const FUSED: bool>(
    factor: SupernodalLdltRef<'_, usize, f64>,
    nodes: std::ops::Range<usize>,
    part: &mut [Row],
    offset: usize,
    mut kept: Option<KeptValues<'_>>,
) {
    let end = offset + part.len();
    for s in nodes {
        let node = factor.supernode(s);
        let (start, pattern, block) = (node.start(), node.pattern(), node.val());
        let inside = &pattern[..pattern.partition_point(|&row| row < end)];
        let size = block.ncols();
        let mut keep = kept.as_mut().and_then(|kept| {
            let base = kept.base[s];
            (base != NOT_KEPT).then(|| &mut kept.rows[base - kept.first..][..size])
        });
        let mut first = 0;
        while first < size {
            let width = GROUP.min(size - first);
            let keep = keep
                .as_deref_mut()
                .map(|rows| &mut rows[first..first + width]);
            let x = (&mut *part, offset);
            match width {
                4 => forward_group::<4, FUSED>(
                    ColumnGroup::new(block, start, inside, first),
                    x,
                    keep,
                ),
                3 => forward_group::<3, FUSED>(
                    ColumnGroup::new(block, start, inside, first),
                    x,
                    keep,
                ),
                2 => forward_group::<2, FUSED>(
                    ColumnGroup::new(block, start, inside, first),
                    x,
                    keep,
                ),
                _ => forward_group::<1, FUSED>(
                    ColumnGroup::new(block, start, inside, first),
                    x,
                    keep,
                ),
            }
            first += width;
        }
    }
}

/// The top's updates that [`forward_nodes_body`] left out: for each supernode `s` below the top
/// with values kept (`bases[s]` ≠ [`NOT_KEPT`]), in ascending order, each later row of it in
/// `top` (unknowns `offset..`) loses `Σ_k L[row, k] · y_k` with the values `y` kept from
/// `kept[bases[s]..]`, group by group as the forward pass makes them.
#[inline(always)]
fn forward_tails_body<const FUSED: bool>(
    factor: SupernodalLdltRef<'_, usize, f64>,
    bases: &[usize],
    kept: &[Row],
    top: &mut [Row],
    offset: usize,
) {
    let kept_nodes = bases
        .iter()
        .enumerate()
        .filter(|&(_, &base)| base != NOT_KEPT);
    for (s, &base) in kept_nodes {
        let node = factor.supernode(s);
        let (pattern, block) = (node.pattern(), node.val());
        let cut = pattern.partition_point(|&row| row < offset);
        let size = block.ncols();
        let mut first = 0;
        while first < size {
            let width = GROUP.min(size - first);
            let values = &kept[base + first..base + first + width];
            let x = (&mut *top, offset);
            match width {
                4 => update_later::<4, FUSED>(
                    ColumnGroup::tail(block, pattern, cut, first),
                    x,
                    values,
                ),
                3 => update_later::<3, FUSED>(
                    ColumnGroup::tail(block, pattern, cut, first),
                    x,
                    values,
                ),
                2 => update_later::<2, FUSED>(
                    ColumnGroup::tail(block, pattern, cut, first),
                    x,
                    values,
                ),
                _ => update_later::<1, FUSED>(
                    ColumnGroup::tail(block, pattern, cut, first),
                    x,
                    values,
                ),
            }
            first += width;
        }
    }
}

/// Backward substitution, `x ← L⁻ᵀ x`, over the supernodes `nodes` (taken last to first) whose
/// unknowns lie in `part` (unknowns `offset..offset + part.len()`); later rows past the end of
/// `part` are read from `top` (its rows and the unknown of the first).
#[inline(always)]
fn backward_nodes_body<const FUSED: bool>(
    factor: SupernodalLdltRef<'_, usize, f64>,
    nodes: std::ops::Range<usize>,
    part: &mut [Row],
    offset: usize,
    top: (&[Row], usize),
) {
    let end = offset + part.len();
    for s in nodes.rev() {
        let node = factor.supernode(s);
        let (start, pattern, block) = (node.start(), node.pattern(), node.val());
        let cut = pattern.partition_point(|&row| row < end);
        let size = block.ncols();
        let mut last = size;
        while last > 0 {
            let first = last.saturating_sub(GROUP);
            let x = (&mut *part, offset);
            match last - first {
                4 => backward_group::<4, FUSED>(block, start, (pattern, cut), first, x, top),
                3 => backward_group::<3, FUSED>(block, start, (pattern, cut), first, x, top),
                2 => backward_group::<2, FUSED>(block, start, (pattern, cut), first, x, top),
                _ => backward_group::<1, FUSED>(block, start, (pattern, cut), first, x, top),
            }
            last = first;
        }
    }
}

/// Columns `first..first + K` of a supernode (`block`: its `(size + pattern) × size` values,
/// column-major; its unknowns start at `start`) and the later rows they update or read.
struct ColumnGroup<'a, const K: usize> {
    /// The group's columns of the block, whole.
    columns: [&'a [f64]; K],
    /// Column of the block the group starts at.
    first: usize,
    /// Unknown of the group's first column.
    unknown: usize,
    /// Position in the block's columns of the first later row.
    below: usize,
    /// Unknowns of the later rows: the rest of the supernode's own unknowns, then (part of) its
    /// pattern.
    later: std::iter::Chain<std::ops::Range<usize>, std::iter::Copied<std::slice::Iter<'a, usize>>>,
}

impl<'a, const K: usize> ColumnGroup<'a, K> {
    /// The group with the rest of its supernode's own rows and the rows `pattern` (the start of
    /// the supernode's pattern, or all of it) for later rows.
    #[inline(always)]
    fn new(block: faer::MatRef<'a, f64>, start: usize, pattern: &'a [usize], first: usize) -> Self {
        let size = block.ncols();
        Self {
            columns: std::array::from_fn(|k| block_column(block, first + k)),
            first,
            unknown: start + first,
            below: first + K,
            later: (start + first + K..start + size).chain(pattern.iter().copied()),
        }
    }

    /// The group with the rows `pattern[cut..]` of its supernode's pattern alone for later rows.
    #[inline(always)]
    fn tail(block: faer::MatRef<'a, f64>, pattern: &'a [usize], cut: usize, first: usize) -> Self {
        let size = block.ncols();
        Self {
            columns: std::array::from_fn(|k| block_column(block, first + k)),
            first,
            unknown: 0,
            below: size + cut,
            later: (0..0).chain(pattern[cut..].iter().copied()),
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
        let below: [&[f64]; K] = std::array::from_fn(|k| &self.columns[k][self.below..]);
        self.later
            .enumerate()
            .map(move |(i, unknown)| (unknown, std::array::from_fn(|k| below[k][i])))
    }
}

/// Forward substitution of a group of `K` columns of a supernode in `x` (its rows, the first
/// one unknown `offset`): the triangle among them, then every later row of `group` loses
/// `Σ_k L[row, first + k] · y_k` ([`update_later`]), the values `y` go to `keep` if given, and
/// are divided by their pivots.
#[inline(always)]
fn forward_group<const K: usize, const FUSED: bool>(
    group: ColumnGroup<'_, K>,
    (x, offset): (&mut [Row], usize),
    keep: Option<&mut [Row]>,
) {
    let unknown = group.unknown - offset;
    let mut values: [Row; K] = std::array::from_fn(|k| x[unknown + k]);
    for k in 0..K {
        for later in k + 1..K {
            let source = values[k];
            subtract_scaled::<FUSED>(&mut values[later], group.triangle(later, k), &source);
        }
    }
    if let Some(keep) = keep {
        keep.copy_from_slice(&values);
    }
    // The group's part of y is final: z = D⁻¹ y (D is on the diagonal of the block).
    let pivots: [f64; K] = std::array::from_fn(|k| group.triangle(k, k));
    update_later::<K, FUSED>(group, (&mut *x, offset), &values);
    for (k, value) in values.iter().enumerate() {
        let inverse = pivots[k].recip();
        x[unknown + k] = value.map(|v| v * inverse);
    }
}

/// Every later row of `group` in `x` (its rows, the first one unknown `offset`) loses
/// `Σ_k L[row, first + k] · values[k]`, the terms in the order of `k`.
#[inline(always)]
fn update_later<const K: usize, const FUSED: bool>(
    group: ColumnGroup<'_, K>,
    (x, offset): (&mut [Row], usize),
    values: &[Row],
) {
    for (target, l) in group.later_rows() {
        let target = &mut x[target - offset];
        let mut sum = *target;
        for k in 0..K {
            subtract_scaled::<FUSED>(&mut sum, l[k], &values[k]);
        }
        *target = sum;
    }
}

/// Backward substitution of columns `first..first + K` of a supernode (`block`, unknowns from
/// `start`, `pattern` whose rows from `cut` on lie in `top`): each loses
/// `Σ_row L[row, column] · x[row]` over the later rows of the block, those in `x` (its rows,
/// the first one unknown `offset`) first, then those in `top` (the first one unknown
/// `top_offset`), every row read once for the whole group; then the triangle among them.
#[inline(always)]
fn backward_group<const K: usize, const FUSED: bool>(
    block: faer::MatRef<'_, f64>,
    start: usize,
    (pattern, cut): (&[usize], usize),
    first: usize,
    (x, offset): (&mut [Row], usize),
    (top, top_offset): (&[Row], usize),
) {
    let inside = ColumnGroup::<K>::new(block, start, &pattern[..cut], first);
    let unknown = inside.unknown - offset;
    let mut values: [Row; K] = std::array::from_fn(|k| x[unknown + k]);
    let triangle: [[f64; K]; K] = std::array::from_fn(|later| {
        std::array::from_fn(|k| {
            if later > k {
                inside.triangle(later, k)
            } else {
                0.0
            }
        })
    });
    for (source, l) in inside.later_rows() {
        let source = x[source - offset];
        for k in 0..K {
            subtract_scaled::<FUSED>(&mut values[k], l[k], &source);
        }
    }
    if cut < pattern.len() {
        for (source, l) in ColumnGroup::<K>::tail(block, pattern, cut, first).later_rows() {
            let source = top[source - top_offset];
            for k in 0..K {
                subtract_scaled::<FUSED>(&mut values[k], l[k], &source);
            }
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
